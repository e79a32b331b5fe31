// Bad input, part 2: well-formed bytes that describe an impossible character:
// indices to nothing, joints past the skin, a cyclic node graph, NaN and Inf,
// unknown interpolations (issue 2, "Bad input, for every command").
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "gltf_fixture.h"
#include "loader_checks.h"

namespace crowdprof::test {
namespace {

// Writes `f` as a GLB in a fresh folder and expects it refused with `words`.
void expect_refused(const GltfFixture& f, const std::string& test, const std::vector<std::string>& words) {
  std::string file = (scratch_dir(test) / "character.glb").string();
  f.write_glb(file);
  expect_bad_input(file, words);
}

TEST(BadGraph, MissingAccessor) {
  SkinnedFixture f;
  f.json["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 99;
  expect_refused(f, "missing_accessor_attr", {"mesh 0 primitive 0", "POSITION", "99", "accessors"});
  SkinnedFixture g;
  g.json["meshes"][0]["primitives"][0]["indices"] = 42;
  expect_refused(g, "missing_accessor_indices", {"mesh 0 primitive 0", "indices", "42"});
  SkinnedFixture h;
  h.json["skins"][0]["inverseBindMatrices"] = 17;
  expect_refused(h, "missing_accessor_ibm", {"skin 0", "inverseBindMatrices", "17"});
  SkinnedFixture k;
  k.json["animations"][0]["samplers"][1]["output"] = -3;
  expect_refused(k, "missing_accessor_output", {"animation 0 sampler 1", "output", "-3"});
}

TEST(BadGraph, MissingBufferView) {
  SkinnedFixture f;
  f.accessor(f.weights)["bufferView"] = 12;
  expect_refused(f, "missing_view", {"accessor 3", "bufferView", "bufferViews[12]"});
  SkinnedFixture g;
  g.accessor(g.indices)["bufferView"] = 12;
  expect_refused(g, "missing_view_indices", {"accessor 4", "bufferViews[12]"});
}

TEST(BadGraph, MissingBuffer) {
  SkinnedFixture f;
  f.view_of(f.normals)["buffer"] = 1;
  expect_refused(f, "missing_buffer", {"buffer view 1", "buffers[1]"});
}

TEST(BadGraph, MissingNodeAsChild) {
  SkinnedFixture f;
  f.json["nodes"][2]["children"] = {3, 4};
  expect_refused(f, "missing_child", {"node 2", "children", "4", "nodes"});
}

TEST(BadGraph, MissingNodeAsSkinJoint) {
  SkinnedFixture f;
  f.json["skins"][0]["joints"] = {1, 2, 7};
  expect_refused(f, "missing_joint_node", {"skin 0", "joints", "7", "nodes"});
  SkinnedFixture g;
  g.json["skins"][0]["skeleton"] = 9;
  expect_refused(g, "missing_skeleton_node", {"skin 0", "skeleton", "9"});
}

TEST(BadGraph, MissingNodeAsChannelTarget) {
  SkinnedFixture f;
  f.json["animations"][0]["channels"][1]["target"]["node"] = 40;
  expect_refused(f, "missing_target", {"animation 0 channel 1", "node", "40"});
  SkinnedFixture g;
  g.json["animations"][0]["channels"][0]["sampler"] = 2;
  expect_refused(g, "missing_sampler", {"animation 0 channel 0", "sampler", "2"});
}

TEST(BadGraph, MissingMeshAndSkin) {
  SkinnedFixture f;
  f.json["nodes"][0]["mesh"] = 1;
  expect_refused(f, "missing_mesh", {"node 0", "mesh", "1", "meshes"});
  SkinnedFixture g;
  g.json["nodes"][0]["skin"] = 3;
  expect_refused(g, "missing_skin", {"node 0", "skin", "3", "skins"});
  // An index too large for tiny_gltf's int must not wrap to a valid one.
  SkinnedFixture h;
  h.json["nodes"][0]["mesh"] = uint64_t(1) << 32;
  expect_refused(h, "wrapping_mesh", {"node 0", "mesh", "4294967296"});
}

TEST(BadGraph, JointIndexAtOrPastJointCount) {
  SkinnedFixture f;
  f.set<uint16_t>(f.joints, 4 * 5 + 1, 3);  // vertex 5, second influence
  expect_refused(f, "joint_past_count", {"mesh 0 primitive 0", "vertex 5", "joint 3", "3 joints"});
  SkinnedFixture g;
  g.set<uint16_t>(g.joints, 0, 65535);
  expect_refused(g, "joint_far_past_count", {"vertex 0", "joint 65535"});
}

TEST(BadGraph, FewerInverseBindMatricesThanJoints) {
  SkinnedFixture f;
  f.accessor(f.inverse_binds)["count"] = 2;
  expect_refused(f, "few_ibms", {"skin 0", "2 inverse bind matrices for 3 joints"});
}

TEST(BadGraph, CycleInNodeGraph) {
  SkinnedFixture f;
  f.json["nodes"][3]["children"] = {1};  // hip > spine > head > hip
  expect_refused(f, "cycle", {"cycle"});
  SkinnedFixture g;
  g.json["nodes"][2]["children"] = {3, 2};
  expect_refused(g, "self_cycle", {"node 2", "cycle"});
  SkinnedFixture h;
  h.json["nodes"][0]["children"] = {3};  // head under both spine and body
  expect_refused(h, "two_parents", {"node 3", "two parents"});
}

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

TEST(BadGraph, NanOrInfInPositions) {
  SkinnedFixture f;
  f.set<float>(f.positions, 7, kNaN);  // vertex 2's y
  expect_refused(f, "nan_position", {"POSITION", "accessor 0 element 2", "NaN"});
  SkinnedFixture g;
  g.set<float>(g.positions, 0, -kInf);
  expect_refused(g, "inf_position", {"POSITION", "accessor 0 element 0", "Inf"});
}

TEST(BadGraph, NanOrInfInWeights) {
  SkinnedFixture f;
  f.set<float>(f.weights, 9, kInf);
  expect_refused(f, "inf_weight", {"WEIGHTS_0", "accessor 3 element 2", "Inf"});
  SkinnedFixture g;
  g.set<float>(g.weights, 0, kNaN);
  expect_refused(g, "nan_weight", {"WEIGHTS_0", "NaN"});
}

TEST(BadGraph, NanOrInfInMatrices) {
  SkinnedFixture f;
  f.set<float>(f.inverse_binds, 16 + 13, kNaN);
  expect_refused(f, "nan_ibm", {"skin 0 inverse bind matrices", "accessor 5 element 1", "NaN"});
  // JSON has no NaN; a number beyond float's range becomes Inf when narrowed.
  SkinnedFixture g;
  g.json["nodes"][2]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 1e39, 0, 1};
  g.json["nodes"][2].erase("translation");
  expect_refused(g, "huge_matrix", {"node 2", "NaN or Inf"});
  SkinnedFixture h;
  h.json["nodes"][3]["translation"] = {0, 1e300, 0};
  expect_refused(h, "huge_translation", {"node 3", "NaN or Inf"});
}

TEST(BadGraph, NanOrInfInKeyTimesAndValues) {
  SkinnedFixture f;
  f.set<float>(f.times, 1, kNaN);
  expect_refused(f, "nan_time", {"animation 0 sampler 0 input", "NaN"});
  SkinnedFixture g;
  g.set<float>(g.times, 1, kInf);
  expect_refused(g, "inf_time", {"input", "Inf"});
  SkinnedFixture h;
  h.set<float>(h.rotations, 5, kNaN);
  expect_refused(h, "nan_rotation_key", {"animation 0 sampler 0 output", "NaN"});
  SkinnedFixture k;
  k.set<float>(k.times, 0, -1.0f);
  expect_refused(k, "negative_time", {"animation 0 sampler 0", "negative"});
  SkinnedFixture m;
  m.set<float>(m.times, 1, 0.0f);
  expect_refused(m, "flat_time", {"key times do not increase"});
}

TEST(BadGraph, UnknownInterpolation) {
  SkinnedFixture f;
  f.json["animations"][0]["samplers"][1]["interpolation"] = "SMOOTHSTEP";
  expect_refused(f, "interpolation", {"animation 0 sampler 1", "unknown interpolation \"SMOOTHSTEP\""});
}

TEST(BadGraph, UnknownTargetPathAndDuplicateTarget) {
  SkinnedFixture f;
  f.json["animations"][0]["channels"][0]["target"]["path"] = "colour";
  expect_refused(f, "target_path", {"animation 0 channel 0", "unknown target path \"colour\""});
  SkinnedFixture g;
  g.json["animations"][0]["channels"][1] = {{"sampler", 0}, {"target", {{"node", 2}, {"path", "rotation"}}}};
  expect_refused(g, "duplicate_target", {"animation 0", "channels 0 and 1", "node 2 rotation"});
}

TEST(BadGraph, MessagesStayOnOneLine) {
  // Strings from the file are quoted, cut short and kept on one line.
  SkinnedFixture f;
  f.json["animations"][0]["samplers"][1]["interpolation"] = "LIN\nEAR" + std::string(5000, 'x');
  std::string file = (scratch_dir("one_line") / "character.glb").string();
  f.write_glb(file);
  std::string message = input_error(file);
  EXPECT_EQ(message.find('\n'), std::string::npos);
  EXPECT_LT(message.size(), 400u);
  expect_bad_input(file, {"unknown interpolation"});
}

}  // namespace
}  // namespace crowdprof::test
