// The loader on valid files: the spec's surprises (issue 2, "Follow the glTF spec
// where it surprises"), the fix-ups it must count, and files with several skins.
#include <filesystem>

#include <gtest/gtest.h>

#include "base/errors.h"
#include "asset/gltf_loader.h"
#include "draco_fixture.h"
#include "gltf_fixture.h"
#include "test_support.h"

namespace crowdprof::test {
namespace {

Character load_one(const GltfFixture& f, const std::string& test) {
  std::string file = (scratch_dir(test) / "character.glb").string();
  f.write_glb(file);
  GltfAsset asset = load_gltf(file);
  EXPECT_EQ(asset.characters.size(), 1u);
  return asset.characters.empty() ? Character{} : asset.characters[0];
}

void expect_near(glm::vec4 a, glm::vec4 b, float tolerance = 1e-6f) {
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(a[i], b[i], tolerance) << "component " << i;
}

TEST(Loader, FixtureInEveryForm) {
  std::filesystem::path dir = scratch_dir("forms");
  SkinnedFixture f;
  f.write_glb(dir / "a.glb");
  f.write_gltf(dir / "b.gltf");
  f.write_gltf(dir / "c.gltf", /*data_uri=*/true);
  for (const char* name : {"a.glb", "b.gltf", "c.gltf"}) {
    SCOPED_TRACE(name);
    Character c = load_character((dir / name).string());
    EXPECT_EQ(c.name, "rig");
    EXPECT_EQ(c.skeleton.names, (std::vector<std::string>{"hip", "spine", "head"}));
    EXPECT_EQ(c.skeleton.parents, (std::vector<int>{-1, 0, 1}));
    EXPECT_EQ(c.mesh.vertex_count(), 6u);
    EXPECT_EQ(c.mesh.triangle_count(), 4u);
    EXPECT_FALSE(c.draco_decoded);
    EXPECT_EQ(c.fixups.total(), 0u);
    ASSERT_EQ(c.actions.size(), 1u);
    EXPECT_EQ(c.actions[0].name, "bend");
    EXPECT_EQ(c.actions[0].channels.size(), 2u);
    EXPECT_FLOAT_EQ(c.actions[0].duration(), 1.0f);
    expect_near(c.mesh.weights[4], {0.75f, 0.25f, 0, 0});
    EXPECT_EQ(c.mesh.joints[4], glm::u16vec4(2, 1, 0, 0));
    EXPECT_FLOAT_EQ(c.skeleton.inverse_binds[2][3][1], -2.0f);
  }
}

TEST(Loader, SkinnedMeshIgnoresItsNodeTransform) {
  SkinnedFixture f;
  f.json["nodes"][0]["translation"] = {5, 0, 0};
  f.json["nodes"][0]["scale"] = {3, 3, 3};
  f.json["nodes"].push_back({{"name", "mover"}, {"translation", {0, 0, 9}}, {"children", {0}}});
  f.json["scenes"][0]["nodes"] = {4, 1};
  Character moved = load_one(f, "node_transform");
  Character plain = load_one(SkinnedFixture(), "node_transform_plain");
  EXPECT_EQ(moved.mesh.positions, plain.mesh.positions);
  EXPECT_EQ(moved.mesh.positions[5], glm::vec3(1, 2, 0));
}

TEST(Loader, ActionsMayStartAfterZero) {
  SkinnedFixture f;
  f.set<float>(f.times, 0, 0.5f);
  f.set<float>(f.times, 1, 1.75f);
  Character c = load_one(f, "late_start");
  ASSERT_EQ(c.actions.size(), 1u);
  EXPECT_FLOAT_EQ(c.actions[0].start, 0.5f);
  EXPECT_FLOAT_EQ(c.actions[0].end, 1.75f);
  EXPECT_FLOAT_EQ(c.actions[0].duration(), 1.25f);
}

TEST(Loader, SkinWithoutSkeleton) {
  SkinnedFixture f;
  f.json["skins"][0].erase("skeleton");
  Character c = load_one(f, "no_skeleton");
  EXPECT_EQ(c.skeleton.parents, (std::vector<int>{-1, 0, 1}));
}

TEST(Loader, NonIndexedPrimitive) {
  SkinnedFixture f;
  f.json["meshes"][0]["primitives"][0].erase("indices");
  Character c = load_one(f, "non_indexed");
  EXPECT_EQ(c.mesh.triangle_count(), 2u);
  EXPECT_EQ(c.mesh.indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
}

TEST(Loader, NormalisedIntegerWeightsAndByteJoints) {
  SkinnedFixture f;
  std::vector<uint8_t> joints8 = {0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 2, 1, 0, 0, 2, 1, 0, 0};
  std::vector<uint8_t> weights8 = {255, 0,   0, 0, 255, 0,  0, 0, 128, 127, 0, 0,
                                   128, 127, 0, 0, 192, 63, 0, 0, 192, 63,  0, 0};
  auto& attributes = f.json["meshes"][0]["primitives"][0]["attributes"];
  attributes["JOINTS_0"] = f.add_accessor(joints8, kUByte, "VEC4", 4);
  attributes["WEIGHTS_0"] = f.add_accessor(weights8, kUByte, "VEC4", 4, /*normalized=*/true);
  Character c = load_one(f, "unorm8");
  EXPECT_EQ(c.mesh.joints[4], glm::u16vec4(2, 1, 0, 0));
  expect_near(c.mesh.weights[2], {128 / 255.0f, 127 / 255.0f, 0, 0});
  EXPECT_EQ(c.fixups.total(), 0u);

  std::vector<uint16_t> weights16 = {65535, 0,     0, 0, 65535, 0,     0, 0, 32768, 32767, 0, 0,
                                     32768, 32767, 0, 0, 49152, 16383, 0, 0, 49152, 16383, 0, 0};
  attributes["WEIGHTS_0"] = f.add_accessor(weights16, kUShort, "VEC4", 4, /*normalized=*/true);
  Character d = load_one(f, "unorm16");
  expect_near(d.mesh.weights[4], {49152 / 65535.0f, 16383 / 65535.0f, 0, 0});
  EXPECT_EQ(d.fixups.total(), 0u);
}

TEST(Loader, MoreThanFourInfluencesKeepsTheLargest) {
  SkinnedFixture f;
  std::vector<uint16_t> joints1(24, 0);
  std::vector<float> weights1(24, 0.0f);
  // Vertex 4 already has 2 (0.75, 0.25); these make 5: 0.3 @2, 0.25 @1, 0.2 @1, 0.15 @0, 0.1 @0.
  f.set<float>(f.weights, 16, 0.3f);
  f.set<float>(f.weights, 17, 0.25f);
  f.set<float>(f.weights, 18, 0.1f);
  joints1[16] = 1;
  weights1[16] = 0.2f;
  weights1[17] = 0.15f;
  auto& attributes = f.json["meshes"][0]["primitives"][0]["attributes"];
  attributes["JOINTS_1"] = f.add_accessor(joints1, kUShort, "VEC4", 4);
  attributes["WEIGHTS_1"] = f.add_accessor(weights1, kFloat, "VEC4", 4);
  Character c = load_one(f, "five_influences");
  EXPECT_EQ(c.fixups.influences_trimmed, 1u);
  EXPECT_EQ(c.fixups.weights_renormalised, 0u);
  EXPECT_EQ(c.mesh.joints[4], glm::u16vec4(2, 1, 1, 0));
  expect_near(c.mesh.weights[4], glm::vec4(0.3f, 0.25f, 0.2f, 0.15f) / 0.9f);
}

TEST(Loader, WeightsNotSummingToOneAreRenormalised) {
  SkinnedFixture f;
  f.set<float>(f.weights, 0, 0.5f);  // vertex 0: 0.5
  f.set<float>(f.weights, 8, 2.0f);  // vertex 2: 2 + 0.5
  Character c = load_one(f, "renormalise");
  EXPECT_EQ(c.fixups.weights_renormalised, 2u);
  expect_near(c.mesh.weights[0], {1, 0, 0, 0});
  expect_near(c.mesh.weights[2], {0.8f, 0.2f, 0, 0});
}

TEST(Loader, MissingNormalsAreComputed) {
  SkinnedFixture f;
  f.json["meshes"][0]["primitives"][0]["attributes"].erase("NORMAL");
  Character c = load_one(f, "no_normals");
  EXPECT_EQ(c.fixups.normals_computed, 6u);
  for (const glm::vec3& n : c.mesh.normals) EXPECT_NEAR(n.z, 1.0f, 1e-6f);
}

TEST(Loader, AnActionWithNothingForTheSkinIsDroppedAndCounted) {
  SkinnedFixture f;
  // "spin" moves only the mesh's node, which is not a joint: nothing to play.
  f.json["animations"].push_back({{"name", "spin"},
                                  {"samplers", {{{"input", f.times}, {"output", f.rotations}}}},
                                  {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "rotation"}}}}}}});
  Character c = load_one(f, "action_dropped");
  ASSERT_EQ(c.actions.size(), 1u);
  EXPECT_EQ(c.actions[0].name, "bend");
  EXPECT_EQ(c.fixups.channels_dropped, 1u);
  EXPECT_EQ(c.fixups.actions_dropped, 1u);
}

TEST(Loader, DracoAgreesWithPlain) {
  Character plain = load_one(SkinnedFixture(), "draco_plain");
  Character draco = load_one(DracoFixture(), "draco_decoded");
  EXPECT_TRUE(draco.draco_decoded);
  EXPECT_EQ(draco.mesh.positions, plain.mesh.positions);
  EXPECT_EQ(draco.mesh.joints, plain.mesh.joints);
  EXPECT_EQ(draco.mesh.weights, plain.mesh.weights);
  EXPECT_EQ(draco.mesh.indices, plain.mesh.indices);
}

// The fixture plus a second skin "tail" (spine and head) driving a second mesh.
std::string two_skins(const std::string& test) {
  SkinnedFixture f;
  std::vector<float> ibm;
  for (int k = 1; k < 3; ++k) ibm.insert(ibm.end(), {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -float(k), 0, 1});
  std::vector<uint16_t> joints(24, 0);
  std::vector<float> weights(24, 0.0f);
  for (size_t v = 0; v < 6; ++v) weights[4 * v] = 1.0f;
  nlohmann::json primitive = f.json["meshes"][0]["primitives"][0];
  primitive["attributes"]["JOINTS_0"] = f.add_accessor(joints, kUShort, "VEC4", 4);
  primitive["attributes"]["WEIGHTS_0"] = f.add_accessor(weights, kFloat, "VEC4", 4);
  f.json["meshes"].push_back({{"name", "tail"}, {"primitives", {primitive}}});
  f.json["skins"].push_back(
      {{"name", "tail"}, {"joints", {2, 3}}, {"inverseBindMatrices", f.add_accessor(ibm, kFloat, "MAT4", 16)}});
  f.json["nodes"].push_back({{"name", "tail"}, {"mesh", 1}, {"skin", 1}});
  f.json["scenes"][0]["nodes"].push_back(4);
  std::string file = (scratch_dir(test) / "pair.glb").string();
  f.write_glb(file);
  return file;
}

TEST(Loader, SeveralSkinsAreNeverPickedSilently) {
  std::string file = two_skins("two_skins");
  try {
    load_character(file);
    ADD_FAILURE() << "a file with two skins loaded without #skin=N";
  } catch (const InputError& e) {
    std::string message = e.what();
    EXPECT_NE(message.find("2 skins"), std::string::npos) << message;
    EXPECT_NE(message.find("0 \"rig\""), std::string::npos) << message;
    EXPECT_NE(message.find("1 \"tail\""), std::string::npos) << message;
    EXPECT_NE(message.find("#skin=N"), std::string::npos) << message;
  }
  Character tail = load_character(file + "#skin=1");
  EXPECT_EQ(tail.name, "tail");
  EXPECT_EQ(tail.skeleton.names, (std::vector<std::string>{"spine", "head"}));
  EXPECT_EQ(tail.actions.size(), 1u);  // "bend" rotates the spine; its hip channel is dropped
  EXPECT_EQ(tail.fixups.channels_dropped, 1u);
  EXPECT_EQ(load_character(file + "#skin=0").name, "rig");
  EXPECT_THROW(load_character(file + "#skin=9"), InputError);
  EXPECT_THROW(load_character(file + "#skin=x"), UsageError);
  EXPECT_THROW(load_character(file + "#skin=-1"), UsageError);
}

TEST(Loader, InfoListsEverySkin) {
  std::string file = two_skins("two_skins_info");
  CliResult text = run_cli("info '" + file + "'");
  EXPECT_EQ(text.status, 0) << text.err;
  EXPECT_NE(text.out.find("rig"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("tail"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("#skin=1"), std::string::npos) << text.out;
  CliResult as_json = run_cli("info --json '" + file + "'");
  ASSERT_EQ(as_json.status, 0) << as_json.err;
  nlohmann::json doc = nlohmann::json::parse(as_json.out);
  ASSERT_EQ(doc["characters"].size(), 2u);
  EXPECT_EQ(doc["characters"][1]["name"], "tail");
  EXPECT_EQ(doc["characters"][1]["joints"], 2);
  // The selector info suggests works on info too.
  CliResult one = run_cli("info --json '" + file + "#skin=1'");
  ASSERT_EQ(one.status, 0) << one.err;
  doc = nlohmann::json::parse(one.out);
  ASSERT_EQ(doc["characters"].size(), 1u);
  EXPECT_EQ(doc["characters"][0]["skin"], 1);
  EXPECT_EQ(doc["characters"][0]["name"], "tail");
  CliResult past = run_cli("info '" + file + "#skin=2'");
  EXPECT_EQ(past.status, 3);
  EXPECT_EQ(past.err, "crowdprof: " + file + ": has no skin 2 (it holds 2)\n");
}

}  // namespace
}  // namespace crowdprof::test
