#include "asset/asset_report.h"

#include <algorithm>
#include <cstdio>
#include <set>
#include <sstream>

#include "asset/mesh_lod.h"
#include "asset/vertex_order.h"
#include "asset/standing.h"

namespace crowdprof {

namespace {

// "LINEAR" or "LINEAR+STEP": the interpolations an action uses.
std::string interpolations(const Action& action) {
  std::set<std::string> names;
  for (const Channel& c : action.channels) names.insert(to_string(c.interpolation));
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : "+") + n;
  return out;
}

nlohmann::json describe_action(const Action& a) {
  return {{"name", a.name},
          {"start_s", a.start},
          {"end_s", a.end},
          {"duration_s", a.duration()},
          {"channels", a.channels.size()},
          {"interpolation", interpolations(a)}};
}

nlohmann::json describe_fixups(const Fixups& f) {
  return {{"influences_trimmed", f.influences_trimmed},     {"weights_renormalised", f.weights_renormalised},
          {"weightless_vertices", f.weightless_vertices},   {"normals_computed", f.normals_computed},
          {"rotations_normalised", f.rotations_normalised}, {"channels_dropped", f.channels_dropped},
          {"names_made_unique", f.names_made_unique},       {"actions_dropped", f.actions_dropped}};
}

}  // namespace

std::array<size_t, 4> influence_histogram(const SkinnedMesh& mesh) {
  std::array<size_t, 4> histogram{};
  for (const glm::vec4& w : mesh.weights) {
    int used = (w.x > 0) + (w.y > 0) + (w.z > 0) + (w.w > 0);
    ++histogram[static_cast<size_t>(std::max(used, 1) - 1)];
  }
  return histogram;
}

namespace {

// The levels `--mesh-lod on` would draw for the character (asset/mesh_lod.h):
// the file's own or meshoptimizer's.
nlohmann::json describe_mesh_lods(const Character& character) {
  nlohmann::json levels = nlohmann::json::array();
  const float height = standing_of(character).height;
  for (const MeshLod& lod : mesh_lods_of(character))
    levels.push_back({{"triangles", lod.mesh.triangle_count()},
                      {"vertices", lod.mesh.vertex_count()},
                      {"error", lod.error},
                      {"error_fraction", height > 0 ? lod.error / height : 0.0f}});
  return levels;
}

// For each primitive of the mesh, then each mesh LOD level: every cache
// model's ACMR and ATVR (asset/vertex_order.h) in the order given (the file's;
// a level's as mesh LOD builds it) and in vertex-cache order.
nlohmann::json describe_vertex_cache(const Character& character) {
  nlohmann::json parts = nlohmann::json::array();
  auto describe = [](const SkinnedMesh& mesh, std::span<const uint32_t> given, std::span<const uint32_t> optimized) {
    nlohmann::json models = nlohmann::json::array();
    for (const VertexCacheModel& model : kVertexCacheModels) {
      const VertexCacheFigures a = analyze_vertex_cache(given, mesh.vertex_count(), model);
      const VertexCacheFigures b = analyze_vertex_cache(optimized, mesh.vertex_count(), model);
      models.push_back({{"model", model.name},
                        {"cache_size", model.cache_size},
                        {"warp_size", model.warp_size},
                        {"primgroup_size", model.primgroup_size},
                        {"file", {{"acmr", a.acmr}, {"atvr", a.atvr}}},
                        {"optimized", {{"acmr", b.acmr}, {"atvr", b.atvr}}}});
    }
    return models;
  };
  const SkinnedMesh& mesh = character.mesh;
  const std::vector<uint32_t> optimized = vertex_cache_order(mesh);
  for (size_t p = 0; p < mesh.primitives.size(); ++p) {
    const Primitive& prim = mesh.primitives[p];
    if (prim.first_index > mesh.indices.size() || prim.index_count > mesh.indices.size() - prim.first_index) continue;
    const std::span<const uint32_t> given(mesh.indices.data() + prim.first_index, prim.index_count);
    const std::span<const uint32_t> ordered(optimized.data() + prim.first_index, prim.index_count);
    parts.push_back({{"primitive", p}, {"models", describe(mesh, given, ordered)}});
  }
  const std::vector<MeshLod> lods = mesh_lods_of(character);
  for (size_t l = 0; l < lods.size(); ++l) {
    const std::vector<uint32_t> level_optimized = vertex_cache_order(lods[l].mesh);
    parts.push_back({{"level", l + 1}, {"models", describe(lods[l].mesh, lods[l].mesh.indices, level_optimized)}});
  }
  return parts;
}

// "1.23/1.98 -> 0.71/1.14" per model, on one line.
std::string vertex_cache_line(const nlohmann::json& models) {
  std::string line;
  for (const nlohmann::json& m : models) {
    char text[160];
    std::snprintf(text, sizeof text, "%s%s %u/%u/%u %.2f/%.2f -> %.2f/%.2f", line.empty() ? "" : "; ",
                  m["model"].get<std::string>().c_str(), m["cache_size"].get<unsigned>(),
                  m["warp_size"].get<unsigned>(), m["primgroup_size"].get<unsigned>(), m["file"]["acmr"].get<double>(),
                  m["file"]["atvr"].get<double>(), m["optimized"]["acmr"].get<double>(),
                  m["optimized"]["atvr"].get<double>());
    line += text;
  }
  return line;
}

// Each joint's name and its parent's index (-1 for a root), in the skeleton's
// order (parents first).
nlohmann::json describe_joints(const Skeleton& skeleton) {
  nlohmann::json joints = nlohmann::json::array();
  for (size_t j = 0; j < skeleton.joint_count(); ++j)
    joints.push_back({{"name", skeleton.names[j]}, {"parent", skeleton.parents[j]}});
  return joints;
}

// The joints as an indented tree, a joint a line under its parent. Joints
// come parents first, a subtree contiguous (gltf_convert.cpp's order), so
// the skeleton's order is the tree's.
std::string joint_tree(const Skeleton& skeleton) {
  std::vector<size_t> depth(skeleton.joint_count(), 0);
  std::string tree;
  for (size_t j = 0; j < skeleton.joint_count(); ++j) {
    const int parent = skeleton.parents[j];
    if (parent >= 0) depth[j] = depth[static_cast<size_t>(parent)] + 1;
    tree += "    " + std::string(2 * depth[j], ' ') + skeleton.names[j] + "\n";
  }
  return tree;
}

}  // namespace

nlohmann::json describe_asset(const GltfAsset& asset, int only_skin) {
  nlohmann::json out = {{"file", asset.file}, {"draco_decoded", asset.draco_decoded}};
  out["characters"] = nlohmann::json::array();
  for (size_t s = 0; s < asset.characters.size(); ++s) {
    if (only_skin >= 0 && s != static_cast<size_t>(only_skin)) continue;
    const Character& c = asset.characters[s];
    auto histogram = influence_histogram(c.mesh);
    nlohmann::json actions = nlohmann::json::array();
    for (const Action& a : c.actions) actions.push_back(describe_action(a));
    out["characters"].push_back(
        {{"skin", s},
         {"name", c.name},
         {"joints", c.skeleton.joint_count()},
         {"hierarchy_depth", c.skeleton.depth()},
         {"joint_tree", describe_joints(c.skeleton)},
         {"vertices", c.mesh.vertex_count()},
         {"triangles", c.mesh.triangle_count()},
         {"primitives", c.mesh.primitives.size()},
         {"height", standing_of(c).height},
         {"influences_histogram", {{"1", histogram[0]}, {"2", histogram[1]}, {"3", histogram[2]}, {"4", histogram[3]}}},
         {"fixups", describe_fixups(c.fixups)},
         {"actions", actions},
         {"draco_decoded", c.draco_decoded},
         {"mesh_lods", describe_mesh_lods(c)},
         {"mesh_lods_source", mesh_lods_source(c)},
         {"vertex_cache", describe_vertex_cache(c)},
         {"shared_bytes", c.shared_bytes()}});
  }
  if (asset.characters.empty()) {
    nlohmann::json actions = nlohmann::json::array();
    for (const Action& a : asset.node_actions) actions.push_back(describe_action(a));
    out["node_animations"] = actions;
  }
  return out;
}

std::string format_asset(const GltfAsset& asset, int only_skin) {
  std::ostringstream out;
  out << asset.file << (asset.draco_decoded ? " (Draco decoded)" : "") << "\n";
  if (asset.characters.empty()) {
    out << "  no skin: nothing crowdprof can animate as a character\n";
    out << "  node animations: " << asset.node_actions.size() << "\n";
    for (const Action& a : asset.node_actions)
      out << "    " << a.name << ": " << a.start << "-" << a.end << " s, " << a.channels.size() << " channels, "
          << interpolations(a) << "\n";
    return out.str();
  }
  for (size_t s = 0; s < asset.characters.size(); ++s) {
    if (only_skin >= 0 && s != static_cast<size_t>(only_skin)) continue;
    const Character& c = asset.characters[s];
    auto h = influence_histogram(c.mesh);
    out << "character " << s << " \"" << c.name << "\"";
    if (asset.characters.size() > 1 && only_skin < 0) out << "  (select with " << asset.file << "#skin=" << s << ")";
    out << "\n";
    out << "  joints:      " << c.skeleton.joint_count() << " (hierarchy depth " << c.skeleton.depth() << ")\n";
    out << "  vertices:    " << c.mesh.vertex_count() << "\n";
    out << "  triangles:   " << c.mesh.triangle_count() << "\n";
    out << "  primitives:  " << c.mesh.primitives.size() << "\n";
    char height[64];
    std::snprintf(height, sizeof height, "%.3f", standing_of(c).height);
    out << "  height:      " << height << " m as it stands (rest pose in world space, +Y up)\n";
    out << "  mesh LOD:    ";
    const nlohmann::json lods = describe_mesh_lods(c);
    if (lods.empty())
      out << (c.mesh.vertex_count() >= 3 * c.mesh.triangle_count()
                  ? "none (no vertex is shared between triangles, so the simplifier can merge none: weld the mesh's "
                    "vertices in its exporter)"
                  : "none (the simplifier found nothing to remove within its error limits)");
    if (!c.file_lods.empty())
      out << "the file's own (MSFT_lod, " << c.file_lods.size() << " level" << (c.file_lods.size() > 1 ? "s" : "")
          << " used; error: surface distance)\n               ";
    for (size_t l = 0; l < lods.size(); ++l) {
      char error[64];
      std::snprintf(error, sizeof error, "%.2f mm, %.2f%% of its height", 1000.0 * lods[l]["error"].get<double>(),
                    100.0 * lods[l]["error_fraction"].get<double>());
      out << (l ? "\n               " : "") << l + 1 << ": " << lods[l]["triangles"].get<size_t>() << " triangles, "
          << lods[l]["vertices"].get<size_t>() << " vertices, error " << error;
    }
    out << "\n";
    out << "  vertex cache: ACMR/ATVR (vertices shaded per triangle / per vertex), file order -> optimized\n";
    for (const nlohmann::json& part : describe_vertex_cache(c))
      out << "    "
          << (part.contains("primitive") ? "primitive " + part["primitive"].dump() : "LOD " + part["level"].dump())
          << ": " << vertex_cache_line(part["models"]) << "\n";
    out << "  influences:  1: " << h[0] << "  2: " << h[1] << "  3: " << h[2] << "  4: " << h[3] << " vertices\n";
    const Fixups& f = c.fixups;
    out << "  fix-ups:     " << (f.total() ? "" : "none");
    nlohmann::json fixups = describe_fixups(f);
    bool first = true;
    for (auto& [name, value] : fixups.items())
      if (value.get<size_t>() > 0) {
        out << (first ? "" : ", ") << name << " " << value.get<size_t>();
        first = false;
      }
    out << "\n";
    out << "  actions:     " << c.actions.size() << "\n";
    for (const Action& a : c.actions)
      out << "    " << a.name << ": " << a.duration() << " s (" << a.start << "-" << a.end << "), " << a.channels.size()
          << " channels, " << interpolations(a) << "\n";
    out << "  Draco:       " << (c.draco_decoded ? "decoded" : "no") << "\n";
    out << "  shared data: " << c.shared_bytes() << " bytes\n";
    out << "  joint tree:  each joint under its parent\n" << joint_tree(c.skeleton);
  }
  return out.str();
}

}  // namespace crowdprof
