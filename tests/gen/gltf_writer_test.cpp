// The glTF writer: what tinygltf reads back from its files, and write -> load
// round trips through crowdprof's own loader (exact, or within Draco's
// quantisation). Also keeps scenes/humanoid.glb equal to what `gen` makes.
#include "gen/gltf_writer.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "base/errors.h"
#include "asset/gltf_loader.h"
#include "gen/humanoid.h"
#include "test_support.h"

using namespace crowdprof;

namespace {

tinygltf::Model parse(const std::vector<uint8_t>& bytes, bool binary) {
  tinygltf::TinyGLTF gltf;
  tinygltf::Model model;
  std::string err, warn;
  bool ok = binary ? gltf.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), unsigned(bytes.size()), "")
                   : gltf.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                              unsigned(bytes.size()), "");
  EXPECT_TRUE(ok) << err;
  EXPECT_EQ(err, "");
  EXPECT_EQ(warn, "");
  return model;
}

template <typename T>
std::vector<T> read(const tinygltf::Model& model, int index) {
  const tinygltf::Accessor& a = model.accessors.at(size_t(index));
  const tinygltf::BufferView& view = model.bufferViews.at(size_t(a.bufferView));
  const std::vector<unsigned char>& data = model.buffers.at(size_t(view.buffer)).data;
  const size_t stride = view.byteStride ? view.byteStride : sizeof(T);
  std::vector<T> out(a.count);
  for (size_t i = 0; i < a.count; ++i) {
    size_t at = view.byteOffset + a.byteOffset + i * stride;
    EXPECT_LE(at + sizeof(T), data.size());
    std::memcpy(&out[i], data.data() + at, sizeof(T));
  }
  return out;
}

template <typename T>
std::vector<char> bytes_of(const std::vector<T>& v) {
  return std::vector<char>(reinterpret_cast<const char*>(v.data()), reinterpret_cast<const char*>(v.data() + v.size()));
}

std::filesystem::path write(const Character& c, const std::string& name, GltfWriteOptions options) {
  auto path = test::scratch_dir("gltf_writer") / name;
  write_gltf(c, path.string(), options);
  return path;
}

// Everything but the mesh, which Draco may reorder.
void expect_same_skeleton_and_actions(const Character& a, const Character& b) {
  EXPECT_EQ(a.skeleton.names, b.skeleton.names);
  EXPECT_EQ(a.skeleton.parents, b.skeleton.parents);
  EXPECT_EQ(bytes_of(a.skeleton.rest_translations), bytes_of(b.skeleton.rest_translations));
  EXPECT_EQ(bytes_of(a.skeleton.rest_rotations), bytes_of(b.skeleton.rest_rotations));
  EXPECT_EQ(bytes_of(a.skeleton.rest_scales), bytes_of(b.skeleton.rest_scales));
  EXPECT_EQ(bytes_of(a.skeleton.inverse_binds), bytes_of(b.skeleton.inverse_binds));
  EXPECT_EQ(bytes_of(a.skeleton.parent_offsets), bytes_of(b.skeleton.parent_offsets));
  ASSERT_EQ(a.actions.size(), b.actions.size());
  for (size_t i = 0; i < a.actions.size(); ++i) {
    const Action &x = a.actions[i], &y = b.actions[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.start, y.start);
    EXPECT_EQ(x.end, y.end);
    ASSERT_EQ(x.channels.size(), y.channels.size());
    for (size_t k = 0; k < x.channels.size(); ++k) {
      EXPECT_EQ(x.channels[k].joint, y.channels[k].joint);
      EXPECT_EQ(x.channels[k].path, y.channels[k].path);
      EXPECT_EQ(x.channels[k].interpolation, y.channels[k].interpolation);
      EXPECT_EQ(x.channels[k].times, y.channels[k].times);
      EXPECT_EQ(bytes_of(x.channels[k].values), bytes_of(y.channels[k].values)) << x.name << " channel " << k;
    }
  }
}

void expect_exact_round_trip(const Character& original, const Character& back) {
  EXPECT_EQ(back.fixups.total(), 0u);
  EXPECT_FALSE(back.draco_decoded);
  expect_same_skeleton_and_actions(original, back);
  const SkinnedMesh &a = original.mesh, &b = back.mesh;
  EXPECT_EQ(bytes_of(a.positions), bytes_of(b.positions));
  EXPECT_EQ(bytes_of(a.normals), bytes_of(b.normals));
  EXPECT_EQ(bytes_of(a.joints), bytes_of(b.joints));
  EXPECT_EQ(bytes_of(a.weights), bytes_of(b.weights));
  EXPECT_EQ(a.indices, b.indices);
  EXPECT_EQ(bytes_of(a.primitives), bytes_of(b.primitives));
}

// A triangle as its three original vertex ids, rotated to start at the
// smallest: the same triangle with the same winding gives the same triple.
std::array<uint32_t, 3> canonical(uint32_t a, uint32_t b, uint32_t c) {
  if (b < a && b < c) return {b, c, a};
  if (c < a && c < b) return {c, a, b};
  return {a, b, c};
}

// Draco keeps every vertex and triangle but may renumber them: match each
// decoded vertex to the original with the nearest position, then compare the
// attributes within quantisation (joints exactly) and the triangles exactly.
void expect_draco_round_trip(const Character& original, const Character& back) {
  EXPECT_TRUE(back.draco_decoded);
  EXPECT_EQ(back.fixups.total(), 0u) << "weights should still sum to 1 after quantisation";
  expect_same_skeleton_and_actions(original, back);
  const SkinnedMesh &a = original.mesh, &b = back.mesh;
  ASSERT_EQ(a.vertex_count(), b.vertex_count());
  ASSERT_EQ(a.triangle_count(), b.triangle_count());
  ASSERT_EQ(a.primitives.size(), b.primitives.size());
  glm::vec3 lo(1e9f), hi(-1e9f);
  for (const glm::vec3& p : a.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const float step = glm::length(hi - lo) / 16383.0f;  // 14 bits over the largest extent, generously
  std::vector<uint32_t> to_original(b.vertex_count());
  std::vector<int> hits(a.vertex_count(), 0);
  float worst_position = 0, worst_normal = 0, worst_weight = 0;
  auto influences = [](glm::u16vec4 j, glm::vec4 w) {
    std::map<int, float> m;
    for (int k = 0; k < 4; ++k)
      if (w[k] > 0.0f) m[j[k]] += w[k];
    return m;
  };
  for (size_t p = 0; p < b.primitives.size(); ++p) {
    const Primitive &pa = a.primitives[p], &pb = b.primitives[p];
    ASSERT_EQ(pa.vertex_count, pb.vertex_count);
    for (uint32_t v = pb.first_vertex; v < pb.first_vertex + pb.vertex_count; ++v) {
      float best = 1e9f;
      uint32_t match = 0;
      for (uint32_t u = pa.first_vertex; u < pa.first_vertex + pa.vertex_count; ++u) {
        float d = glm::length(a.positions[u] - b.positions[v]);
        if (d < best) best = d, match = u;
      }
      ASSERT_LT(best, step) << "decoded vertex " << v << " has no original nearby";
      to_original[v] = match;
      hits[match]++;
      worst_position = std::max(worst_position, best);
      worst_normal = std::max(worst_normal, glm::length(a.normals[match] - b.normals[v]));
      std::map<int, float> wa = influences(a.joints[match], a.weights[match]),
                           wb = influences(b.joints[v], b.weights[v]);
      for (auto [j, w] : wa) worst_weight = std::max(worst_weight, std::abs(w - wb[j]));
      for (auto [j, w] : wb) worst_weight = std::max(worst_weight, std::abs(w - wa[j]));
    }
  }
  EXPECT_EQ(std::count(hits.begin(), hits.end(), 1), std::ptrdiff_t(a.vertex_count())) << "matching is not one to one";
  EXPECT_LT(worst_normal, 0.01f);
  EXPECT_LT(worst_weight, 1e-3f) << "a weight moved, or a joint index changed";
  std::vector<std::array<uint32_t, 3>> ta, tb;
  for (size_t i = 0; i < a.indices.size(); i += 3)
    ta.push_back(canonical(a.indices[i], a.indices[i + 1], a.indices[i + 2]));
  for (size_t i = 0; i < b.indices.size(); i += 3)
    tb.push_back(canonical(to_original[b.indices[i]], to_original[b.indices[i + 1]], to_original[b.indices[i + 2]]));
  std::sort(ta.begin(), ta.end());
  std::sort(tb.begin(), tb.end());
  EXPECT_TRUE(ta == tb) << "Draco changed the triangles";
  std::cout << "draco round trip: position error " << worst_position << " m, normal " << worst_normal << ", weight "
            << worst_weight << "\n";
}

// The humanoid's mesh twice, side by side, as two primitives.
Character two_primitives(Character c) {
  SkinnedMesh& m = c.mesh;
  const uint32_t n = uint32_t(m.vertex_count()), i = uint32_t(m.indices.size());
  for (uint32_t v = 0; v < n; ++v) {
    m.positions.push_back(m.positions[v] + glm::vec3(1, 0, 0));
    m.normals.push_back(m.normals[v]);
    m.joints.push_back(m.joints[v]);
    m.weights.push_back(m.weights[v]);
  }
  for (uint32_t k = 0; k < i; ++k) m.indices.push_back(m.indices[k] + n);
  m.primitives = {{0, i, 0, n}, {i, i, n, n}};
  return c;
}

}  // namespace

TEST(GltfWriter, TinygltfReadsTheGlb) {
  Character c = generate_humanoid();
  tinygltf::Model model = parse(encode_gltf(c), true);
  ASSERT_EQ(model.skins.size(), 1u);
  const tinygltf::Skin& skin = model.skins[0];
  ASSERT_EQ(skin.joints.size(), 69u);
  EXPECT_EQ(skin.skeleton, 0);
  for (int j = 0; j < 69; ++j) {
    EXPECT_EQ(skin.joints[size_t(j)], j);
    const tinygltf::Node& node = model.nodes[size_t(j)];
    EXPECT_EQ(node.name, c.skeleton.names[size_t(j)]);
    const glm::quat q = c.skeleton.rest_rotations[size_t(j)];
    const glm::vec3 t = c.skeleton.rest_translations[size_t(j)];
    // Exact floats; glTF's defaults (identity, zero) may be left out.
    std::vector<double> r = node.rotation.empty() ? std::vector<double>{0, 0, 0, 1} : node.rotation;
    std::vector<double> m = node.translation.empty() ? std::vector<double>{0, 0, 0} : node.translation;
    ASSERT_EQ(r.size(), 4u) << node.name;
    ASSERT_EQ(m.size(), 3u) << node.name;
    EXPECT_EQ(glm::quat(float(r[3]), float(r[0]), float(r[1]), float(r[2])), q) << node.name;
    EXPECT_EQ(glm::vec3(float(m[0]), float(m[1]), float(m[2])), t) << node.name;
    EXPECT_TRUE(node.scale.empty() && node.matrix.empty());
    for (int child : model.nodes[size_t(j)].children) EXPECT_EQ(c.skeleton.parents[size_t(child)], j);
  }
  EXPECT_EQ(bytes_of(read<glm::mat4>(model, skin.inverseBindMatrices)), bytes_of(c.skeleton.inverse_binds));

  ASSERT_EQ(model.meshes.size(), 1u);
  ASSERT_EQ(model.meshes[0].primitives.size(), 1u);
  const tinygltf::Primitive& prim = model.meshes[0].primitives[0];
  const tinygltf::Node& mesh_node = model.nodes.back();
  EXPECT_EQ(mesh_node.mesh, 0);
  EXPECT_EQ(mesh_node.skin, 0);
  EXPECT_EQ(model.scenes.at(0).nodes, (std::vector<int>{0, int(model.nodes.size()) - 1}));

  const tinygltf::Accessor& pos = model.accessors[size_t(prim.attributes.at("POSITION"))];
  EXPECT_EQ(pos.count, 4951u);
  ASSERT_EQ(pos.minValues.size(), 3u);
  glm::vec3 lo(1e9f), hi(-1e9f);
  for (const glm::vec3& p : c.mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(float(pos.minValues[size_t(k)]), lo[k]);
    EXPECT_EQ(float(pos.maxValues[size_t(k)]), hi[k]);
  }
  EXPECT_EQ(bytes_of(read<glm::vec3>(model, prim.attributes.at("POSITION"))), bytes_of(c.mesh.positions));
  EXPECT_EQ(bytes_of(read<glm::vec3>(model, prim.attributes.at("NORMAL"))), bytes_of(c.mesh.normals));
  EXPECT_EQ(bytes_of(read<glm::vec4>(model, prim.attributes.at("WEIGHTS_0"))), bytes_of(c.mesh.weights));
  EXPECT_EQ(model.accessors[size_t(prim.attributes.at("JOINTS_0"))].componentType,
            TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE);
  std::vector<glm::u8vec4> joints = read<glm::u8vec4>(model, prim.attributes.at("JOINTS_0"));
  EXPECT_TRUE(std::equal(joints.begin(), joints.end(), c.mesh.joints.begin(),
                         [](glm::u8vec4 x, glm::u16vec4 y) { return glm::u16vec4(x) == y; }));
  EXPECT_EQ(model.accessors[size_t(prim.indices)].componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  std::vector<uint16_t> indices = read<uint16_t>(model, prim.indices);
  EXPECT_TRUE(std::equal(indices.begin(), indices.end(), c.mesh.indices.begin(), c.mesh.indices.end()));

  ASSERT_EQ(model.animations.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    const tinygltf::Animation& a = model.animations[i];
    EXPECT_EQ(a.name, c.actions[i].name);
    ASSERT_EQ(a.channels.size(), 70u);
    for (size_t k = 0; k < a.channels.size(); ++k) {
      const tinygltf::AnimationSampler& s = a.samplers[size_t(a.channels[k].sampler)];
      EXPECT_EQ(s.interpolation, "LINEAR");
      const tinygltf::Accessor& input = model.accessors[size_t(s.input)];
      ASSERT_EQ(input.minValues.size(), 1u) << "glTF requires min/max on animation inputs";
      EXPECT_EQ(input.minValues[0], 0.0);
      EXPECT_EQ(float(input.maxValues[0]), c.actions[i].end);
      EXPECT_EQ(a.channels[k].target_node, c.actions[i].channels[k].joint);
      EXPECT_EQ(read<float>(model, s.input), c.actions[i].channels[k].times);
    }
  }
}

TEST(GltfWriter, JsonGltfEmbedsTheSameBuffer) {
  Character c = generate_humanoid({30, 800, 3});
  std::vector<uint8_t> glb = encode_gltf(c), text = encode_gltf(c, {false, false});
  EXPECT_EQ(text.front(), '{');
  tinygltf::Model from_glb = parse(glb, true), from_text = parse(text, false);
  ASSERT_EQ(from_text.buffers.size(), 1u);
  EXPECT_EQ(from_text.buffers[0].uri.rfind("data:application/octet-stream;base64,", 0), 0u);
  EXPECT_EQ(from_text.buffers[0].data, from_glb.buffers[0].data);
}

TEST(GltfWriter, RoundTripIsExact) {
  for (bool binary : {true, false}) {
    for (auto [bones, vertices] : {std::pair{69, 4951}, std::pair{300, 3000}, std::pair{40, 70000}}) {
      SCOPED_TRACE(std::to_string(bones) + " bones, " + std::to_string(vertices) + " vertices, " +
                   (binary ? "glb" : "gltf"));
      Character c = generate_humanoid({bones, vertices, 5});
      Character back = load_character(write(c, binary ? "h.glb" : "h.gltf", {binary, false}).string());
      expect_exact_round_trip(c, back);
    }
  }
}

TEST(GltfWriter, WideJointsAndIndicesWhenNeeded) {
  Character c = generate_humanoid({300, 70000, 1});
  tinygltf::Model model = parse(encode_gltf(c), true);
  const tinygltf::Primitive& prim = model.meshes.at(0).primitives.at(0);
  EXPECT_EQ(model.accessors[size_t(prim.attributes.at("JOINTS_0"))].componentType,
            TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  EXPECT_EQ(model.accessors[size_t(prim.indices)].componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
  EXPECT_EQ(read<uint32_t>(model, prim.indices), c.mesh.indices);
}

TEST(GltfWriter, SeveralPrimitivesRoundTrip) {
  Character c = two_primitives(generate_humanoid({25, 600, 1}));
  expect_exact_round_trip(c, load_character(write(c, "two.glb", {}).string()));
  expect_draco_round_trip(c, load_character(write(c, "two_draco.glb", {true, true}).string()));
}

TEST(GltfWriter, ParentOffsetsBecomeNodes) {
  Character c = generate_humanoid({20, 500, 1});
  c.skeleton.parent_offsets[0] = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.5f, 0.0f));
  c.skeleton.parent_offsets[3] = glm::rotate(glm::mat4(1.0f), 0.5f, glm::vec3(0.0f, 1.0f, 0.0f));
  tinygltf::Model model = parse(encode_gltf(c), true);
  EXPECT_EQ(model.nodes.size(), 20u + 2u + 1u);
  EXPECT_EQ(model.skins.at(0).skeleton, 20) << "the root's offset node is the skeleton root";
  Character back = load_character(write(c, "offsets.glb", {}).string());
  ASSERT_EQ(back.skeleton.parent_offsets.size(), 20u);
  for (size_t j = 0; j < 20; ++j)
    for (int col = 0; col < 4; ++col)
      for (int row = 0; row < 4; ++row)
        EXPECT_NEAR(back.skeleton.parent_offsets[j][col][row], c.skeleton.parent_offsets[j][col][row], 1e-6f) << j;
}

TEST(GltfWriter, DracoRoundTripWithinQuantisation) {
  for (auto [bones, vertices] : {std::pair{69, 4951}, std::pair{300, 3000}}) {
    SCOPED_TRACE(std::to_string(bones) + " bones");
    Character c = generate_humanoid({bones, vertices, 1});
    std::vector<uint8_t> bytes = encode_gltf(c, {true, true});
    tinygltf::Model model = parse(bytes, true);
    EXPECT_EQ(model.extensionsUsed, std::vector<std::string>{"KHR_draco_mesh_compression"});
    EXPECT_EQ(model.extensionsRequired, std::vector<std::string>{"KHR_draco_mesh_compression"});
    const tinygltf::Primitive& prim = model.meshes.at(0).primitives.at(0);
    ASSERT_TRUE(prim.extensions.count("KHR_draco_mesh_compression"));
    const tinygltf::Value& attrs = prim.extensions.at("KHR_draco_mesh_compression").Get("attributes");
    for (const char* name : {"POSITION", "NORMAL", "JOINTS_0", "WEIGHTS_0"}) EXPECT_TRUE(attrs.Has(name)) << name;
    EXPECT_LT(bytes.size(), encode_gltf(c).size());
    expect_draco_round_trip(c, load_character(write(c, "d.glb", {true, true}).string()));
    expect_draco_round_trip(c, load_character(write(c, "d.gltf", {false, true}).string()));
  }
}

TEST(GltfWriter, SameCharacterSameBytes) {
  Character c = generate_humanoid();
  EXPECT_TRUE(encode_gltf(c) == encode_gltf(generate_humanoid()));
  EXPECT_TRUE(encode_gltf(c, {true, true}) == encode_gltf(c, {true, true}));
  EXPECT_TRUE(encode_gltf(c, {false, false}) == encode_gltf(c, {false, false}));
}

TEST(GltfWriter, UnwritablePathIsAUsageError) {
  Character c = generate_humanoid({20, 500, 1});
  auto dir = test::scratch_dir("gltf_writer_unwritable");
  std::vector<std::string> paths = {(dir / "missing" / "x.glb").string(), dir.string()};
  if (std::filesystem::is_character_file("/dev/full")) paths.push_back("/dev/full");  // a full disk
  for (const std::string& path : paths) {
    try {
      write_gltf(c, path, {});
      ADD_FAILURE() << "wrote " << path;
    } catch (const UsageError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("cannot write GLB file '" + path + "': ", 0), 0u) << e.what();
    }
  }
}

TEST(GltfWriter, DefaultSceneIsUpToDate) {
  const auto path = test::source_dir() / "scenes" / "humanoid.glb";
  std::ifstream in(path, std::ios::binary);
  ASSERT_TRUE(in) << path << " is missing: crowdprof gen -o scenes/humanoid.glb";
  std::vector<uint8_t> committed((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_TRUE(committed == encode_gltf(generate_humanoid(), {}))
      << path << " differs from what the generator makes now; regenerate it: crowdprof gen -o scenes/humanoid.glb";
}
