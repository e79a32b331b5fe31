#include "gen/gltf_writer.h"

#include <map>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "base/errors.h"
#include "gen/gltf_draco_encode.h"
#include "base/output_file.h"

namespace crowdprof {
namespace {

using Json = nlohmann::ordered_json;  // keys in the order written: readable, and stable

enum : int {  // glTF component types and buffer view targets
  kUnsignedByte = 5121,
  kUnsignedShort = 5123,
  kUnsignedInt = 5125,
  kFloat = 5126,
  kArrayBuffer = 34962,
  kElementArrayBuffer = 34963,
};

Json vec(glm::vec3 v) {
  return Json::array({v.x, v.y, v.z});
}

// One glTF document under construction: its JSON and its single binary buffer.
class Document {
 public:
  Json root = {{"asset", {{"version", "2.0"}, {"generator", "crowdprof"}}}};
  std::vector<uint8_t> bin;

  int view(const void* data, size_t bytes, int target = 0) {
    bin.resize((bin.size() + 3) & ~size_t(3), 0);  // 4-byte aligned, as every component type needs
    Json v = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}};
    if (target) v["target"] = target;
    const uint8_t* p = static_cast<const uint8_t*>(data);
    bin.insert(bin.end(), p, p + bytes);
    return push("bufferViews", std::move(v));
  }
  template <typename T>
  int view(const std::vector<T>& data, int target = 0) {
    return view(data.data(), data.size() * sizeof(T), target);
  }

  // An accessor; `view` < 0 for one whose data is Draco-compressed.
  int accessor(int view, int component, size_t count, const char* type, Json min = nullptr, Json max = nullptr) {
    Json a;
    if (view >= 0) a["bufferView"] = view;
    a["componentType"] = component;
    a["count"] = count;
    a["type"] = type;
    if (!min.is_null()) a["min"] = std::move(min), a["max"] = std::move(max);
    return push("accessors", std::move(a));
  }

  int push(const char* array, Json value) {
    Json& list = root[array];
    if (list.is_null()) list = Json::array();
    list.push_back(std::move(value));
    return static_cast<int>(list.size()) - 1;
  }
};

void check(const Character& c) {
  const Skeleton& s = c.skeleton;
  const size_t joints = s.joint_count();
  auto fail = [](const std::string& what) { throw std::invalid_argument("cannot write character: " + what); };
  if (s.parents.size() != joints || s.rest_translations.size() != joints || s.rest_rotations.size() != joints ||
      s.rest_scales.size() != joints || s.inverse_binds.size() != joints)
    fail("skeleton arrays differ in length");
  for (size_t j = 0; j < joints; ++j)
    if (s.parents[j] >= static_cast<int>(j)) fail("joint " + std::to_string(j) + " comes before its parent");
  std::vector<const SkinnedMesh*> meshes = {&c.mesh};
  for (const SkinnedMesh& lod : c.file_lods) meshes.push_back(&lod);
  for (const SkinnedMesh* mesh : meshes) {
    const SkinnedMesh& m = *mesh;
    const size_t n = m.vertex_count();
    if (m.normals.size() != n || m.joints.size() != n || m.weights.size() != n) fail("mesh arrays differ in length");
    for (const glm::u16vec4& v : m.joints)
      for (int k = 0; k < 4; ++k)
        if (v[k] >= joints) fail("a vertex names a joint past the skeleton");
    for (const Primitive& p : m.primitives) {
      if (size_t(p.first_vertex) + p.vertex_count > n || size_t(p.first_index) + p.index_count > m.indices.size() ||
          p.index_count % 3 != 0)
        fail("a primitive lies outside the mesh");
      for (uint32_t i = p.first_index; i < p.first_index + p.index_count; ++i)
        if (m.indices[i] < p.first_vertex || m.indices[i] - p.first_vertex >= p.vertex_count)
          fail("a primitive's index leaves its vertex range");
    }
  }
  if (!c.file_lods.empty() && c.mesh.vertex_count() == 0) fail("levels of detail without a mesh");
  for (const Action& a : c.actions)
    for (const Channel& ch : a.channels) {
      size_t per_key = static_cast<size_t>(ch.components()) * (ch.interpolation == Interpolation::CubicSpline ? 3 : 1);
      if (ch.joint < 0 || size_t(ch.joint) >= joints || ch.times.empty() ||
          ch.values.size() != ch.times.size() * per_key)
        fail("a channel of action '" + a.name + "' does not fit the skeleton or its keys");
    }
}

void write_skeleton(Document& doc, const Skeleton& s, std::vector<int>& scene_nodes) {
  const size_t joints = s.joint_count();
  Json nodes = Json::array();
  std::vector<int> top(joints);  // the node that attaches joint j to its parent
  for (size_t j = 0; j < joints; ++j) {
    Json node = {{"name", s.names[j]}};
    const glm::vec3 t = s.rest_translations[j], sc = s.rest_scales[j];
    const glm::quat q = s.rest_rotations[j];
    if (t != glm::vec3(0.0f)) node["translation"] = vec(t);
    if (q != glm::quat(1, 0, 0, 0)) node["rotation"] = Json::array({q.x, q.y, q.z, q.w});
    if (sc != glm::vec3(1.0f)) node["scale"] = vec(sc);
    nodes.push_back(std::move(node));
    top[j] = static_cast<int>(j);
  }
  for (size_t j = 0; j < joints; ++j) {  // non-joint nodes between a joint and its parent
    if (j >= s.parent_offsets.size() || s.parent_offsets[j] == glm::mat4(1.0f)) continue;
    const float* m = &s.parent_offsets[j][0][0];
    nodes.push_back(
        {{"name", s.names[j] + ".offset"}, {"matrix", std::vector<float>(m, m + 16)}, {"children", Json::array({j})}});
    top[j] = static_cast<int>(nodes.size()) - 1;
  }
  for (size_t j = 0; j < joints; ++j) {
    int parent = s.parents[j];
    if (parent < 0)
      scene_nodes.push_back(top[j]);
    else
      nodes[static_cast<size_t>(parent)]["children"].push_back(top[j]);
  }
  doc.root["nodes"] = std::move(nodes);

  Json skin = {{"inverseBindMatrices", doc.accessor(doc.view(s.inverse_binds), kFloat, joints, "MAT4")}};
  if (scene_nodes.size() == 1) skin["skeleton"] = scene_nodes[0];
  Json list = Json::array();
  for (size_t j = 0; j < joints; ++j) list.push_back(j);
  skin["joints"] = std::move(list);
  doc.push("skins", std::move(skin));
}

Json write_primitive(Document& doc, const SkinnedMesh& m, const Primitive& p, bool joints_u8, bool draco) {
  const size_t first = p.first_vertex, n = p.vertex_count;
  std::span<const glm::vec3> positions(m.positions.data() + first, n), normals(m.normals.data() + first, n);
  std::span<const glm::u16vec4> joints(m.joints.data() + first, n);
  std::span<const glm::vec4> weights(m.weights.data() + first, n);
  std::vector<uint32_t> indices(m.indices.begin() + p.first_index, m.indices.begin() + p.first_index + p.index_count);
  for (uint32_t& i : indices) i -= p.first_vertex;
  const int joint_type = joints_u8 ? kUnsignedByte : kUnsignedShort;
  Json prim = {{"attributes", Json::object()}, {"mode", 4}};
  Json& attrs = prim["attributes"];

  if (draco) {
    DracoPrimitive d = encode_draco_primitive(positions, normals, joints, weights, indices, joints_u8);
    const size_t points = d.points;
    attrs["POSITION"] = doc.accessor(-1, kFloat, points, "VEC3", vec(d.min), vec(d.max));
    attrs["NORMAL"] = doc.accessor(-1, kFloat, points, "VEC3");
    attrs["JOINTS_0"] = doc.accessor(-1, joint_type, points, "VEC4");
    attrs["WEIGHTS_0"] = doc.accessor(-1, kFloat, points, "VEC4");
    prim["indices"] = doc.accessor(-1, points <= 65535 ? kUnsignedShort : kUnsignedInt, d.faces * 3, "SCALAR");
    Json ids = {
        {"POSITION", d.position_id}, {"NORMAL", d.normal_id}, {"JOINTS_0", d.joints_id}, {"WEIGHTS_0", d.weights_id}};
    prim["extensions"] = {{"KHR_draco_mesh_compression", {{"bufferView", doc.view(d.bytes)}, {"attributes", ids}}}};
    return prim;
  }

  glm::vec3 lo = n ? positions[0] : glm::vec3(0.0f), hi = lo;
  for (const glm::vec3& v : positions) lo = glm::min(lo, v), hi = glm::max(hi, v);
  attrs["POSITION"] = doc.accessor(doc.view(positions.data(), n * sizeof(glm::vec3), kArrayBuffer), kFloat, n, "VEC3",
                                   vec(lo), vec(hi));
  attrs["NORMAL"] = doc.accessor(doc.view(normals.data(), n * sizeof(glm::vec3), kArrayBuffer), kFloat, n, "VEC3");
  int joints_view;
  if (joints_u8)
    joints_view = doc.view(std::vector<glm::u8vec4>(joints.begin(), joints.end()), kArrayBuffer);
  else
    joints_view = doc.view(joints.data(), n * sizeof(glm::u16vec4), kArrayBuffer);
  attrs["JOINTS_0"] = doc.accessor(joints_view, joint_type, n, "VEC4");
  attrs["WEIGHTS_0"] = doc.accessor(doc.view(weights.data(), n * sizeof(glm::vec4), kArrayBuffer), kFloat, n, "VEC4");
  // 65535 is the primitive-restart value, which glTF forbids as an index.
  if (n <= 65535) {
    std::vector<uint16_t> narrow(indices.begin(), indices.end());
    prim["indices"] = doc.accessor(doc.view(narrow, kElementArrayBuffer), kUnsignedShort, narrow.size(), "SCALAR");
  } else {
    prim["indices"] = doc.accessor(doc.view(indices, kElementArrayBuffer), kUnsignedInt, indices.size(), "SCALAR");
  }
  return prim;
}

void write_actions(Document& doc, const std::vector<Action>& actions) {
  std::map<std::vector<float>, int> time_accessors;  // channels keyed at the same times share them
  static const char* kType[] = {"VEC3", "VEC4", "VEC3"};
  for (const Action& a : actions) {
    Json samplers = Json::array(), channels = Json::array();
    for (const Channel& c : a.channels) {
      auto [it, fresh] = time_accessors.try_emplace(c.times, -1);
      if (fresh)
        it->second = doc.accessor(doc.view(c.times), kFloat, c.times.size(), "SCALAR", Json::array({c.times.front()}),
                                  Json::array({c.times.back()}));
      const size_t count = c.values.size() / static_cast<size_t>(c.components());
      int output = doc.accessor(doc.view(c.values), kFloat, count, kType[static_cast<int>(c.path)]);
      channels.push_back({{"sampler", samplers.size()}, {"target", {{"node", c.joint}, {"path", to_string(c.path)}}}});
      samplers.push_back({{"input", it->second}, {"interpolation", to_string(c.interpolation)}, {"output", output}});
    }
    doc.push("animations", {{"name", a.name}, {"channels", std::move(channels)}, {"samplers", std::move(samplers)}});
  }
}

std::string base64(const std::vector<uint8_t>& data) {
  static const char* kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((data.size() + 2) / 3 * 4);
  for (size_t i = 0; i < data.size(); i += 3) {
    uint32_t v = uint32_t(data[i]) << 16;
    if (i + 1 < data.size()) v |= uint32_t(data[i + 1]) << 8;
    if (i + 2 < data.size()) v |= data[i + 2];
    out += kDigits[(v >> 18) & 63];
    out += kDigits[(v >> 12) & 63];
    out += i + 1 < data.size() ? kDigits[(v >> 6) & 63] : '=';
    out += i + 2 < data.size() ? kDigits[v & 63] : '=';
  }
  return out;
}

void put_u32(std::vector<uint8_t>& out, uint32_t v) {
  for (int k = 0; k < 4; ++k) out.push_back(static_cast<uint8_t>(v >> (8 * k)));
}

}  // namespace

std::vector<uint8_t> encode_gltf(const Character& c, const GltfWriteOptions& options) {
  check(c);
  Document doc;
  std::vector<int> scene_nodes;
  write_skeleton(doc, c.skeleton, scene_nodes);

  if (c.mesh.vertex_count() > 0) {
    const bool joints_u8 = c.skeleton.joint_count() <= 256;
    auto write_mesh = [&](const SkinnedMesh& mesh, const std::string& name) {
      std::vector<Primitive> primitives = mesh.primitives;
      if (primitives.empty())
        primitives.push_back({0, uint32_t(mesh.indices.size()), 0, uint32_t(mesh.vertex_count())});
      Json prims = Json::array();
      for (const Primitive& p : primitives) prims.push_back(write_primitive(doc, mesh, p, joints_u8, options.draco));
      return doc.push("meshes", {{"name", name}, {"primitives", std::move(prims)}});
    };
    // glTF ignores a skinned mesh node's own transform; it sits at the scene root.
    Json node = {{"name", c.name}, {"mesh", write_mesh(c.mesh, c.name)}, {"skin", 0}};
    if (!c.file_lods.empty()) {
      // MSFT_lod: the coarser levels on nodes of their own, outside the scene
      // (a viewer without the extension draws the full mesh alone).
      Json ids = Json::array();
      for (size_t l = 0; l < c.file_lods.size(); ++l) {
        const std::string name = c.name + ".lod" + std::to_string(l + 1);
        ids.push_back(doc.push("nodes", {{"name", name}, {"mesh", write_mesh(c.file_lods[l], name)}, {"skin", 0}}));
      }
      node["extensions"] = {{"MSFT_lod", {{"ids", std::move(ids)}}}};
    }
    scene_nodes.push_back(doc.push("nodes", std::move(node)));
  }
  write_actions(doc, c.actions);
  doc.root["scene"] = 0;
  doc.root["scenes"] = Json::array({{{"name", c.name}, {"nodes", scene_nodes}}});
  if (options.draco) {
    doc.root["extensionsUsed"] = Json::array({"KHR_draco_mesh_compression"});
    doc.root["extensionsRequired"] = Json::array({"KHR_draco_mesh_compression"});
  }
  if (!c.file_lods.empty() && c.mesh.vertex_count() > 0) doc.root["extensionsUsed"].push_back("MSFT_lod");
  Json buffer = {{"byteLength", doc.bin.size()}};
  if (!options.binary) buffer["uri"] = "data:application/octet-stream;base64," + base64(doc.bin);
  doc.root["buffers"] = Json::array({std::move(buffer)});

  // Names from other files may not be valid UTF-8: replace, do not throw.
  const auto replace = Json::error_handler_t::replace;
  if (!options.binary) {
    std::string text = doc.root.dump(1, ' ', false, replace) + "\n";
    return {text.begin(), text.end()};
  }
  std::string text = doc.root.dump(-1, ' ', false, replace);
  text.resize((text.size() + 3) & ~size_t(3), ' ');
  doc.bin.resize((doc.bin.size() + 3) & ~size_t(3), 0);
  std::vector<uint8_t> out;
  out.reserve(28 + text.size() + doc.bin.size());
  put_u32(out, 0x46546C67);  // "glTF"
  put_u32(out, 2);
  put_u32(out, static_cast<uint32_t>(28 + text.size() + doc.bin.size()));
  put_u32(out, static_cast<uint32_t>(text.size()));
  put_u32(out, 0x4E4F534A);  // "JSON"
  out.insert(out.end(), text.begin(), text.end());
  put_u32(out, static_cast<uint32_t>(doc.bin.size()));
  put_u32(out, 0x004E4942);  // "BIN\0"
  out.insert(out.end(), doc.bin.begin(), doc.bin.end());
  return out;
}

void write_gltf(const Character& character, const std::string& path, const GltfWriteOptions& options) {
  require_writable(path, options.binary ? "GLB" : "glTF");
  std::vector<uint8_t> bytes = encode_gltf(character, options);
  write_file(path, options.binary ? "GLB" : "glTF",
             std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace crowdprof
