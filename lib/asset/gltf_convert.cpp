// Turning a tinygltf::Model into characters: the skeleton, the skinned mesh and
// the actions of one skin, checking every index and value on the way.
#include "asset/gltf_convert.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#define GLM_ENABLE_EXPERIMENTAL
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/gtx/matrix_decompose.hpp>
#include <tiny_gltf.h>

#include "base/errors.h"
#include "asset/gltf_accessor.h"
#include "asset/gltf_container.h"
#include "asset/mesh_lod.h"
#include "asset/mesh_normals.h"

namespace crowdprof {

namespace {

template <typename V>
bool finite(const V& v) {
  for (int i = 0; i < V::length(); ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

struct Trs {
  glm::vec3 t{0.0f};
  glm::quat r{1.0f, 0.0f, 0.0f, 0.0f};
  glm::vec3 s{1.0f};
};

Trs node_trs(const tinygltf::Node& node, size_t index, const std::string& file) {
  Trs trs;
  auto check = [&](const std::vector<double>& v, size_t size, const char* what) {
    if (!v.empty() && v.size() != size)
      throw InputError(file,
                       "node " + str(index) + " has a " + what + " of " + str(v.size()) + " numbers, not " + str(size));
    // Beyond float's range a value would become Inf when narrowed.
    for (double x : v)
      if (!(std::abs(x) <= double(std::numeric_limits<float>::max())))
        throw InputError(file, "node " + str(index) + " has a NaN or Inf " + what + " (or a value past float's range)");
  };
  check(node.matrix, 16, "matrix");
  check(node.translation, 3, "translation");
  check(node.rotation, 4, "rotation");
  check(node.scale, 3, "scale");
  if (node.matrix.size() == 16) {
    glm::mat4 m = glm::make_mat4(node.matrix.data());
    glm::vec3 skew;
    glm::vec4 perspective;
    if (!glm::decompose(m, trs.s, trs.r, trs.t, skew, perspective) || !finite(trs.t) || !finite(trs.s) ||
        !finite(glm::vec4(trs.r.x, trs.r.y, trs.r.z, trs.r.w)))
      throw InputError(file, "node " + str(index) + " has a matrix that is not a transform");
    return trs;
  }
  if (node.translation.size() == 3) trs.t = glm::vec3(glm::make_vec3(node.translation.data()));
  if (node.scale.size() == 3) trs.s = glm::vec3(glm::make_vec3(node.scale.data()));
  if (node.rotation.size() == 4) {
    const auto& q = node.rotation;
    trs.r = glm::quat(static_cast<float>(q[3]), static_cast<float>(q[0]), static_cast<float>(q[1]),
                      static_cast<float>(q[2]));
    if (glm::length(trs.r) < 1e-6f) throw InputError(file, "node " + str(index) + " has a zero rotation");
    // Like animation keys: only a rotation that is visibly not unit is touched,
    // so files round-trip bit for bit.
    if (std::abs(glm::length(trs.r) - 1.0f) > 1e-3f) trs.r = glm::normalize(trs.r);
  }
  return trs;
}

glm::mat4 to_matrix(const Trs& trs) {
  return glm::translate(glm::mat4(1.0f), trs.t) * glm::mat4_cast(trs.r) * glm::scale(glm::mat4(1.0f), trs.s);
}

// Joint names must be unique for string-path lookups to find the right joint:
// nameless joints get "joint<N>", repeats get Blender's ".001" suffixes.
std::vector<std::string> unique_names(std::vector<std::string> names, Fixups& fixups) {
  std::set<std::string> seen;
  for (size_t j = 0; j < names.size(); ++j) {
    std::string base = names[j].empty() ? "joint" + str(j) : names[j];
    std::string name = base;
    for (int n = 1; seen.count(name); ++n) {
      char suffix[16];
      std::snprintf(suffix, sizeof suffix, ".%03d", n);
      name = base + suffix;
    }
    if (name != names[j]) ++fixups.names_made_unique;
    seen.insert(name);
    names[j] = name;
  }
  return names;
}

struct Skin {
  std::vector<int> nodes;          // joint -> node, in crowdprof's parent-first order
  std::vector<int> from_skin;      // skin's joint index -> crowdprof joint
  std::vector<int> node_to_joint;  // node -> crowdprof joint, -1 if none
};

// Orders the skin's joints parent first (depth-first, keeping the file's order
// among siblings), so subtrees are contiguous and parents[j] < j.
Skin order_joints(const tinygltf::Model& model, const std::vector<int>& parents, const tinygltf::Skin& skin, int s,
                  const std::string& file) {
  size_t node_count = model.nodes.size();
  std::vector<int> skin_index(node_count, -1);
  for (size_t i = 0; i < skin.joints.size(); ++i) {
    int node = skin.joints[i];
    if (node < 0 || static_cast<size_t>(node) >= node_count)
      throw InputError(file, "skin " + str(s) + " joint " + str(i) + " names node " + std::to_string(node) +
                                 ", which does not exist");
    if (skin_index[static_cast<size_t>(node)] >= 0)
      throw InputError(file, "skin " + str(s) + " lists node " + std::to_string(node) + " twice");
    skin_index[static_cast<size_t>(node)] = static_cast<int>(i);
  }
  std::vector<std::vector<int>> children(skin.joints.size());
  std::vector<int> roots;
  for (size_t i = 0; i < skin.joints.size(); ++i) {
    int up = parents[static_cast<size_t>(skin.joints[i])];
    while (up >= 0 && skin_index[static_cast<size_t>(up)] < 0) up = parents[static_cast<size_t>(up)];
    if (up < 0)
      roots.push_back(static_cast<int>(i));
    else
      children[static_cast<size_t>(skin_index[static_cast<size_t>(up)])].push_back(static_cast<int>(i));
  }
  Skin out;
  out.from_skin.assign(skin.joints.size(), -1);
  out.node_to_joint.assign(node_count, -1);
  std::vector<int> stack(roots.rbegin(), roots.rend());
  while (!stack.empty()) {
    int i = stack.back();
    stack.pop_back();
    int node = skin.joints[static_cast<size_t>(i)];
    out.from_skin[static_cast<size_t>(i)] = static_cast<int>(out.nodes.size());
    out.node_to_joint[static_cast<size_t>(node)] = static_cast<int>(out.nodes.size());
    out.nodes.push_back(node);
    const auto& kids = children[static_cast<size_t>(i)];
    stack.insert(stack.end(), kids.rbegin(), kids.rend());
  }
  return out;
}

Skeleton build_skeleton(const tinygltf::Model& model, const std::vector<int>& parents, const Skin& order,
                        const tinygltf::Skin& skin, int s, const std::string& file, Fixups& fixups) {
  size_t count = order.nodes.size();
  Skeleton sk;
  sk.parents.resize(count);
  sk.parent_offsets.resize(count);
  std::vector<std::string> names(count);
  for (size_t j = 0; j < count; ++j) {
    size_t node = static_cast<size_t>(order.nodes[j]);
    Trs trs = node_trs(model.nodes[node], node, file);
    sk.rest_translations.push_back(trs.t);
    sk.rest_rotations.push_back(trs.r);
    sk.rest_scales.push_back(trs.s);
    names[j] = model.nodes[node].name;
    // Fold the non-joint nodes between this joint and its parent joint.
    glm::mat4 offset(1.0f);
    int up = parents[node];
    while (up >= 0 && order.node_to_joint[static_cast<size_t>(up)] < 0) {
      offset = to_matrix(node_trs(model.nodes[static_cast<size_t>(up)], static_cast<size_t>(up), file)) * offset;
      up = parents[static_cast<size_t>(up)];
    }
    sk.parents[j] = up < 0 ? -1 : order.node_to_joint[static_cast<size_t>(up)];
    sk.parent_offsets[j] = offset;
  }
  sk.names = unique_names(std::move(names), fixups);
  sk.inverse_binds.assign(count, glm::mat4(1.0f));
  if (skin.inverseBindMatrices >= 0) {
    AccessorReader reader{model, file};
    std::vector<float> ibm = reader.floats(skin.inverseBindMatrices, 16, "skin " + str(s) + " inverse bind matrices");
    if (ibm.size() / 16 < count)
      throw InputError(file, "skin " + str(s) + " has " + str(ibm.size() / 16) + " inverse bind matrices for " +
                                 str(count) + " joints");
    for (size_t i = 0; i < count; ++i)
      sk.inverse_binds[static_cast<size_t>(order.from_skin[i])] = glm::make_mat4(&ibm[16 * i]);
  }
  return sk;
}

void append_primitive(const tinygltf::Model& model, size_t m, size_t p, const Skin& order, size_t joint_count,
                      const std::string& file, SkinnedMesh& mesh, Fixups& fixups) {
  const tinygltf::Primitive& prim = model.meshes[m].primitives[p];
  std::string where = "mesh " + str(m) + " primitive " + str(p);
  if (prim.mode != TINYGLTF_MODE_TRIANGLES)
    throw InputError(file, where + ": mode " + std::to_string(prim.mode) + " is not supported (triangles only)");
  auto attribute = [&](const char* name) {
    auto it = prim.attributes.find(name);
    return it == prim.attributes.end() ? -1 : it->second;
  };
  AccessorReader reader{model, file};
  if (attribute("POSITION") < 0) throw InputError(file, where + ": has no POSITION");
  if (attribute("JOINTS_0") < 0 || attribute("WEIGHTS_0") < 0)
    throw InputError(file, where + ": is bound to a skin but has no JOINTS_0/WEIGHTS_0");
  std::vector<float> positions = reader.floats(attribute("POSITION"), 3, where + " POSITION");
  size_t n = positions.size() / 3;
  if (mesh.positions.size() + n > kMaxMeshVertices)
    throw InputError(file, where + ": the skinned mesh would have more than " + str(kMaxMeshVertices) +
                               " vertices; refused as absurd");
  auto same_count = [&](const std::vector<float>& v, int components, const char* name) {
    if (v.size() != n * static_cast<size_t>(components))
      throw InputError(file, where + ": " + name + " has " + str(v.size() / static_cast<size_t>(components)) +
                                 " elements, POSITION " + str(n));
  };
  std::vector<float> normals;
  if (attribute("NORMAL") >= 0) {
    normals = reader.floats(attribute("NORMAL"), 3, where + " NORMAL");
    same_count(normals, 3, "NORMAL");
  }
  // Up to two sets of four influences (JOINTS_1/WEIGHTS_1 carry the next four).
  std::vector<uint32_t> joints[2];
  std::vector<float> weights[2];
  int sets = attribute("JOINTS_1") >= 0 && attribute("WEIGHTS_1") >= 0 ? 2 : 1;
  for (int set = 0; set < sets; ++set) {
    std::string suffix = set == 0 ? "_0" : "_1";
    joints[set] = reader.uints(attribute(("JOINTS" + suffix).c_str()), 4, where + " JOINTS" + suffix);
    weights[set] = reader.floats(attribute(("WEIGHTS" + suffix).c_str()), 4, where + " WEIGHTS" + suffix);
    std::vector<float> as_float(joints[set].begin(), joints[set].end());
    same_count(as_float, 4, ("JOINTS" + suffix).c_str());
    same_count(weights[set], 4, ("WEIGHTS" + suffix).c_str());
  }
  std::vector<uint32_t> indices;
  if (prim.indices >= 0) {
    indices = reader.uints(prim.indices, 1, where + " indices");
    for (size_t i = 0; i < indices.size(); ++i)
      if (indices[i] >= n)
        throw InputError(file, where + ": index " + str(i) + " is " + std::to_string(indices[i]) + ", past its " +
                                   str(n) + " vertices");
  } else {
    indices.resize(n);
    for (size_t i = 0; i < n; ++i) indices[i] = static_cast<uint32_t>(i);
  }
  if (indices.size() % 3)
    throw InputError(file, where + ": " + str(indices.size()) + " indices is not whole triangles");
  if (mesh.indices.size() + indices.size() > 3 * kMaxMeshVertices)
    throw InputError(file, where + ": the skinned mesh would have more than " + str(kMaxMeshVertices) +
                               " triangles; refused as absurd");

  uint32_t base = static_cast<uint32_t>(mesh.positions.size());
  Primitive range{static_cast<uint32_t>(mesh.indices.size()), static_cast<uint32_t>(indices.size()), base,
                  static_cast<uint32_t>(n)};
  for (uint32_t i : indices) mesh.indices.push_back(base + i);
  for (size_t v = 0; v < n; ++v) {
    mesh.positions.emplace_back(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
    struct Influence {
      float weight;
      uint32_t joint;
    } influence[8];
    int used = 0;
    for (int set = 0; set < sets; ++set)
      for (size_t k = 0; k < 4; ++k) {
        uint32_t joint = joints[set][4 * v + k];
        float weight = weights[set][4 * v + k];
        if (joint >= joint_count)
          throw InputError(file, where + ": vertex " + str(v) + " uses joint " + std::to_string(joint) +
                                     ", but the skin has " + str(joint_count) + " joints");
        if (weight < 0.0f) throw InputError(file, where + ": vertex " + str(v) + " has a negative weight");
        if (weight > 0.0f) influence[used++] = {weight, joint};
      }
    // Largest first; ties keep file order, so loading is deterministic.
    std::stable_sort(influence, influence + used,
                     [](const Influence& a, const Influence& b) { return a.weight > b.weight; });
    bool trimmed = used > 4;
    if (trimmed) {
      ++fixups.influences_trimmed;  // the renormalisation that follows is part of this fix-up
      used = 4;
    }
    glm::u16vec4 out_joints(0);
    glm::vec4 out_weights(0.0f);
    float sum = 0.0f;
    for (int k = 0; k < used; ++k) sum += influence[k].weight;
    if (!std::isfinite(sum))
      throw InputError(file, where + ": vertex " + str(v) + "'s weights add up past float's range");
    if (used == 0) {
      ++fixups.weightless_vertices;
      out_weights[0] = 1.0f;
    } else {
      bool renormalise = std::abs(sum - 1.0f) > 1e-5f;
      if (renormalise && !trimmed) ++fixups.weights_renormalised;
      for (int k = 0; k < used; ++k) {
        out_joints[k] = static_cast<uint16_t>(order.from_skin[influence[k].joint]);
        out_weights[k] = renormalise ? influence[k].weight / sum : influence[k].weight;
      }
    }
    mesh.joints.push_back(out_joints);
    mesh.weights.push_back(out_weights);
  }
  if (normals.empty()) {
    std::vector<glm::vec3> computed = face_normals(std::span(mesh.positions).subspan(base), std::span(indices));
    mesh.normals.insert(mesh.normals.end(), computed.begin(), computed.end());
    fixups.normals_computed += n;
  } else {
    for (size_t v = 0; v < n; ++v) {
      glm::vec3 normal(normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]);
      float length = glm::length(normal);
      if (length < 1e-12f) {
        normal = glm::vec3(0.0f, 0.0f, 1.0f);
        ++fixups.normals_computed;
      } else if (std::abs(length - 1.0f) > 1e-3f) {
        normal /= length;
      }
      mesh.normals.push_back(normal);
    }
  }
  mesh.primitives.push_back(range);
}

// The last check before a character leaves the loader. Values read from the file
// were checked as they were read; this catches what was computed from them
// (normals of huge triangles, decomposed matrices, sums of huge weights).
// Per node: the nodes its MSFT_lod names, coarser in turn (empty without),
// for the nodes of skin `s` with a mesh. Each must be another node of that
// skin with a mesh and no MSFT_lod of its own, named once.
std::vector<std::vector<int>> lod_chains(const tinygltf::Model& model, int s, const std::string& file) {
  std::vector<std::vector<int>> chains(model.nodes.size());
  std::set<int> named;
  for (size_t n = 0; n < model.nodes.size(); ++n) {
    const tinygltf::Node& node = model.nodes[n];
    auto it = node.extensions.find("MSFT_lod");
    if (node.skin != s || node.mesh < 0 || it == node.extensions.end()) continue;
    const std::string where = "node " + str(n) + "'s MSFT_lod";
    if (!it->second.IsObject() || !it->second.Has("ids") || !it->second.Get("ids").IsArray())
      throw InputError(file, where + " has no \"ids\" array");
    const tinygltf::Value& ids = it->second.Get("ids");
    if (ids.ArrayLen() > 16) throw InputError(file, where + " names " + str(ids.ArrayLen()) + " levels; at most 16");
    for (size_t k = 0; k < ids.ArrayLen(); ++k) {
      const tinygltf::Value& id = ids.Get(static_cast<int>(k));
      if (!id.IsInt()) throw InputError(file, where + ": ids[" + str(k) + "] is not a node index");
      if (id.Get<int>() < 0 || static_cast<size_t>(id.Get<int>()) >= model.nodes.size())
        throw InputError(file, where + " names a node that is not there (ids[" + str(k) + "])");
      const int lod = id.Get<int>();
      const tinygltf::Node& target = model.nodes[static_cast<size_t>(lod)];
      if (static_cast<size_t>(lod) == n || target.mesh < 0 || target.skin != s)
        throw InputError(file, where + " names node " + str(static_cast<size_t>(lod)) +
                                   ", which is not another node with a mesh bound to skin " +
                                   str(static_cast<size_t>(s)));
      if (target.extensions.count("MSFT_lod"))
        throw InputError(file,
                         where + " names node " + str(static_cast<size_t>(lod)) + ", which has levels of its own");
      if (!named.insert(lod).second)
        throw InputError(file, where + " names node " + str(static_cast<size_t>(lod)) + " a second time");
      chains[n].push_back(lod);
    }
  }
  return chains;
}

// Keeps the file's levels that are coarser than the one before (fewer
// vertices, at least one triangle): a copy's room for vertices is the full
// mesh's, and a level with nothing to draw would count as exact. Measures
// each kept level's surface distance from the full mesh, once, here.
void keep_coarser_levels(Character& c) {
  std::vector<SkinnedMesh> kept;
  size_t previous = c.mesh.vertex_count();
  for (SkinnedMesh& lod : c.file_lods) {
    if (lod.triangle_count() == 0 || lod.vertex_count() >= previous) continue;
    previous = lod.vertex_count();
    kept.push_back(std::move(lod));
  }
  c.file_lods = std::move(kept);
  c.file_lod_errors.clear();
  for (const SkinnedMesh& lod : c.file_lods) c.file_lod_errors.push_back(surface_distance(c.mesh, lod));
}

void check_finite(const Character& c, int s, const std::string& file) {
  auto fail = [&](const std::string& what) {
    throw InputError(
        file, "skin " + str(static_cast<size_t>(s)) + ": " + what + " is not finite (values in the file too large?)");
  };
  auto finite_matrix = [](const glm::mat4& m) { return finite(m[0]) && finite(m[1]) && finite(m[2]) && finite(m[3]); };
  const Skeleton& k = c.skeleton;
  for (size_t j = 0; j < k.joint_count(); ++j) {
    const glm::quat& r = k.rest_rotations[j];
    if (!finite(k.rest_translations[j]) || !finite(k.rest_scales[j]) || !finite(glm::vec4(r.x, r.y, r.z, r.w)) ||
        !finite_matrix(k.inverse_binds[j]) || !finite_matrix(k.parent_offsets[j]))
      fail("joint " + str(j) + "'s rest pose or bind matrix");
  }
  for (size_t v = 0; v < c.mesh.vertex_count(); ++v)
    if (!finite(c.mesh.positions[v]) || !finite(c.mesh.normals[v]) || !finite(c.mesh.weights[v]))
      fail("vertex " + str(v));
  for (size_t l = 0; l < c.file_lods.size(); ++l)
    for (size_t v = 0; v < c.file_lods[l].vertex_count(); ++v)
      if (!finite(c.file_lods[l].positions[v]) || !finite(c.file_lods[l].normals[v]) ||
          !finite(c.file_lods[l].weights[v]))
        fail("MSFT_lod level " + str(l + 1) + " vertex " + str(v));
  for (const Action& action : c.actions)
    for (const Channel& channel : action.channels)
      for (float x : channel.values)
        if (!std::isfinite(x)) fail("a key of action \"" + printable(action.name, 40) + "\"");
}

}  // namespace

std::vector<int> node_parents(const tinygltf::Model& model, const std::string& file) {
  size_t count = model.nodes.size();
  std::vector<int> parents(count, -1);
  for (size_t i = 0; i < count; ++i) {
    const tinygltf::Node& node = model.nodes[i];
    if (node.mesh >= 0 && static_cast<size_t>(node.mesh) >= model.meshes.size())
      throw InputError(file, "node " + str(i) + " names mesh " + std::to_string(node.mesh) + ", which does not exist");
    if (node.skin >= 0 && static_cast<size_t>(node.skin) >= model.skins.size())
      throw InputError(file, "node " + str(i) + " names skin " + std::to_string(node.skin) + ", which does not exist");
    for (int child : node.children) {
      if (child < 0 || static_cast<size_t>(child) >= count)
        throw InputError(file, "node " + str(i) + " has child " + std::to_string(child) + ", which does not exist");
      if (static_cast<size_t>(child) == i) throw InputError(file, "node " + str(i) + " is its own child (a cycle)");
      if (parents[static_cast<size_t>(child)] >= 0)
        throw InputError(file, "node " + std::to_string(child) + " has two parents (nodes " +
                                   std::to_string(parents[static_cast<size_t>(child)]) + " and " + str(i) + ")");
      parents[static_cast<size_t>(child)] = static_cast<int>(i);
    }
  }
  // Each node's depth, walking every chain once (a chain of a million nodes must
  // not take a million walks); a walk that meets its own chain is a cycle.
  std::vector<int> depth(count, 0);  // 0: unknown, -1: on the chain being walked
  std::vector<size_t> chain;
  for (size_t i = 0; i < count; ++i) {
    chain.clear();
    size_t n = i;
    int base = 0;
    while (true) {
      if (depth[n] > 0) {
        base = depth[n];
        break;
      }
      if (depth[n] < 0) throw InputError(file, "the node graph has a cycle through node " + str(n));
      depth[n] = -1;
      chain.push_back(n);
      if (parents[n] < 0) break;
      n = static_cast<size_t>(parents[n]);
    }
    for (size_t k = chain.size(); k-- > 0;) {
      depth[chain[k]] = ++base;
      if (base > kMaxNodeDepth)
        throw InputError(file, "node " + str(chain[k]) + " lies more than " + std::to_string(kMaxNodeDepth) +
                                   " levels deep in the node graph; refused as absurd");
    }
  }
  return parents;
}

Character convert_skin(const tinygltf::Model& model, const std::vector<int>& parents, int s, const std::string& file) {
  const tinygltf::Skin& skin = model.skins[static_cast<size_t>(s)];
  if (skin.joints.empty()) throw InputError(file, "skin " + str(static_cast<size_t>(s)) + " has no joints");
  if (skin.joints.size() > 65535)
    throw InputError(file, "skin " + str(static_cast<size_t>(s)) + " has " + str(skin.joints.size()) +
                               " joints; crowdprof supports at most 65535");
  Character character;
  Skin order = order_joints(model, parents, skin, s, file);
  character.skeleton = build_skeleton(model, parents, order, skin, s, file, character.fixups);
  std::string mesh_node_name;
  std::set<int> meshes_done;
  const std::vector<std::vector<int>> chains = lod_chains(model, s, file);
  std::set<int> lod_nodes;  // drawn only as levels, never with the full mesh
  for (const std::vector<int>& chain : chains) lod_nodes.insert(chain.begin(), chain.end());
  size_t levels = 0;
  for (const std::vector<int>& chain : chains) levels = std::max(levels, chain.size());
  levels = std::min(levels, kMeshLevels - 1);  // mesh LOD draws no more: the rest are not read
  character.file_lods.resize(levels);
  for (size_t n = 0; n < model.nodes.size(); ++n) {
    const tinygltf::Node& node = model.nodes[n];
    if (node.skin != s || node.mesh < 0 || lod_nodes.count(static_cast<int>(n)) ||
        !meshes_done.insert(node.mesh).second)
      continue;
    if (mesh_node_name.empty()) mesh_node_name = node.name;
    size_t m = static_cast<size_t>(node.mesh);
    for (size_t p = 0; p < model.meshes[m].primitives.size(); ++p)
      append_primitive(model, m, p, order, skin.joints.size(), file, character.mesh, character.fixups);
    // Each level of the file's: this node's own at that level, its coarsest
    // past the end of its chain, or its full mesh when it has none (what a
    // viewer of MSFT_lod draws for a part without levels).
    for (size_t level = 0; level < levels; ++level) {
      const std::vector<int>& chain = chains[n];
      const size_t lod_mesh =
          chain.empty()
              ? m
              : static_cast<size_t>(model.nodes[static_cast<size_t>(chain[std::min(level, chain.size() - 1)])].mesh);
      for (size_t p = 0; p < model.meshes[lod_mesh].primitives.size(); ++p) {
        append_primitive(model, lod_mesh, p, order, skin.joints.size(), file, character.file_lods[level],
                         character.fixups);
        size_t in_all = 0;
        for (const SkinnedMesh& lod : character.file_lods) in_all += lod.vertex_count();
        if (in_all > kMaxMeshVertices)
          throw InputError(file, "its MSFT_lod levels hold more than " + str(kMaxMeshVertices) +
                                     " vertices in all; refused as absurd");
      }
    }
  }
  keep_coarser_levels(character);
  character.actions = convert_actions(model, order.node_to_joint, file, &character.fixups);
  character.name = !skin.name.empty()        ? skin.name
                   : !mesh_node_name.empty() ? mesh_node_name
                                             : "skin" + str(static_cast<size_t>(s));
  check_finite(character, s, file);
  return character;
}

}  // namespace crowdprof
