// A glTF file's own levels of detail (MSFT_lod, issue 29): the generator writes
// them (crowdprof gen --lods), the loader reads them apart from the full mesh,
// mesh LOD draws them instead of simplifying, and a broken MSFT_lod is refused
// with a line that says what is wrong.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "asset/standing.h"
#include "base/errors.h"
#include "asset/gltf_loader.h"
#include "asset/mesh_lod.h"
#include "frame/crowd_bench.h"
#include "gen/gltf_writer.h"
#include "gen/humanoid.h"

using namespace crowdprof;

namespace {

Character humanoid_with_levels(int levels = 3) {
  HumanoidOptions options;
  options.lod_levels = levels;
  return generate_humanoid(options);
}

Character load(const std::vector<uint8_t>& bytes, const std::string& name = "lods.glb") {
  GltfAsset asset = load_gltf_from_memory(std::vector<unsigned char>(bytes.begin(), bytes.end()), name);
  EXPECT_EQ(asset.characters.size(), 1u);
  return asset.characters.front();
}

// The humanoid with levels as JSON glTF, for editing its MSFT_lod.
nlohmann::json as_json(const Character& c) {
  GltfWriteOptions options;
  options.binary = false;
  std::vector<uint8_t> bytes = encode_gltf(c, options);
  return nlohmann::json::parse(bytes.begin(), bytes.end());
}

std::string refusal(const nlohmann::json& doc) {
  const std::string text = doc.dump();
  try {
    load(std::vector<uint8_t>(text.begin(), text.end()), "bad.gltf");
  } catch (const InputError& e) {
    return e.what();
  }
  return "loaded";
}

}  // namespace

TEST(MsftLod, TheGeneratorsLevelsComeBackApartFromTheFullMesh) {
  const Character written = humanoid_with_levels();
  ASSERT_EQ(written.file_lods.size(), 3u);
  for (bool draco : {false, true}) {
    SCOPED_TRACE(draco ? "Draco" : "plain");
    GltfWriteOptions options;
    options.draco = draco;
    const Character read = load(encode_gltf(written, options));
    EXPECT_EQ(read.mesh.vertex_count(), written.mesh.vertex_count()) << "the levels are not drawn with the full mesh";
    EXPECT_EQ(read.mesh.triangle_count(), written.mesh.triangle_count());
    ASSERT_EQ(read.file_lods.size(), 3u);
    size_t vertices = read.mesh.vertex_count();
    for (size_t l = 0; l < 3; ++l) {
      EXPECT_EQ(read.file_lods[l].triangle_count(), written.file_lods[l].triangle_count());
      EXPECT_LT(read.file_lods[l].vertex_count(), vertices);
      vertices = read.file_lods[l].vertex_count();
    }
    EXPECT_EQ(read.file_lods[2].vertex_count(), 500u);
  }
  // A file without the extension has no levels of its own.
  EXPECT_TRUE(load(encode_gltf(generate_humanoid())).file_lods.empty());
}

TEST(MsftLod, MeshLodDrawsTheFilesLevelsWithTheirSurfaceDistance) {
  const Character c = load(encode_gltf(humanoid_with_levels()));
  EXPECT_STREQ(mesh_lods_source(c), "MSFT_lod");
  const std::vector<MeshLod> lods = mesh_lods_of(c);
  ASSERT_EQ(lods.size(), 3u);
  for (size_t l = 0; l < lods.size(); ++l) {
    EXPECT_EQ(lods[l].mesh.vertex_count(), c.file_lods[l].vertex_count());
    EXPECT_GT(lods[l].error, 0.0f) << "a coarser tessellation strays from the full surface";
    EXPECT_LT(lods[l].error, 0.05f * standing_of(c).height);
  }
  // In a bench: the copies at level 2 skin the file's level 2, not a simplification.
  BenchConfig config;
  config.mode = find_mode("threaded")->switches;
  config.mode.mesh_lod = true;
  config.mode_name = "threaded";
  config.crowd.copies = 1000;
  CrowdBench bench(c, config);
  const Counters counters = bench.step().counters;
  ASSERT_GT(counters.lod2_copies, 0u);
  EXPECT_EQ(counters.lod2_vertices, counters.lod2_copies * c.file_lods[1].vertex_count());
  EXPECT_EQ(counters.lod3_vertices, counters.lod3_copies * c.file_lods[2].vertex_count());
}

TEST(MsftLod, SurfaceDistanceOfTwoParallelTriangles) {
  SkinnedMesh a, b;
  a.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  a.indices = {0, 1, 2};
  b = a;
  EXPECT_EQ(surface_distance(a, b), 0.0f);
  for (glm::vec3& p : b.positions) p.z += 0.25f;
  EXPECT_NEAR(surface_distance(a, b), 0.25f, 1e-6f);
  b.positions[2] = {0, 3, 0.25f};  // b reaches further: its far corner is 2 + from a's
  EXPECT_NEAR(surface_distance(a, b), std::sqrt(2.0f * 2.0f + 0.25f * 0.25f), 1e-5f);
}

TEST(MsftLod, ABrokenExtensionIsRefusedSayingWhy) {
  const nlohmann::json good = as_json(humanoid_with_levels(2));
  // The full mesh's node carries the extension; find it.
  size_t main = 0;
  for (size_t n = 0; n < good["nodes"].size(); ++n)
    if (good["nodes"][n].contains("extensions")) main = n;
  ASSERT_TRUE(good["nodes"][main]["extensions"].contains("MSFT_lod"));
  const nlohmann::json ids = good["nodes"][main]["extensions"]["MSFT_lod"]["ids"];
  struct Case {
    nlohmann::json ids;
    std::string words;
  };
  const Case cases[] = {
      {nlohmann::json{ids[0], 9999}, "names a node that is not there (ids[1])"},
      {nlohmann::json{ids[0], main}, "which is not another node with a mesh bound to skin 0"},
      {nlohmann::json{ids[0], 0}, "names node 0, which is not another node with a mesh"},
      {nlohmann::json{ids[0], ids[0]}, "a second time"},
      {nlohmann::json{ids[0], "one"}, "ids[1] is not a node index"},
      {nlohmann::json("all"), "has no \"ids\" array"},
  };
  for (const Case& c : cases) {
    nlohmann::json bad = good;
    bad["nodes"][main]["extensions"]["MSFT_lod"]["ids"] = c.ids;
    const std::string why = refusal(bad);
    EXPECT_NE(why.find("bad.gltf: node " + std::to_string(main) + "'s MSFT_lod"), std::string::npos) << why;
    EXPECT_NE(why.find(c.words), std::string::npos) << why;
  }
  // A level with levels of its own.
  nlohmann::json nested = good;
  nested["nodes"][ids[0].get<size_t>()]["extensions"] = {{"MSFT_lod", {{"ids", {ids[1]}}}}};
  EXPECT_NE(refusal(nested).find("which has levels of its own"), std::string::npos) << refusal(nested);
  EXPECT_EQ(refusal(good), "loaded");
}

TEST(MsftLod, LevelsNoCoarserThanTheOneBeforeAreSkipped) {
  nlohmann::json doc = as_json(humanoid_with_levels(2));
  size_t main = 0;
  for (size_t n = 0; n < doc["nodes"].size(); ++n)
    if (doc["nodes"][n].contains("extensions")) main = n;
  const nlohmann::json ids = doc["nodes"][main]["extensions"]["MSFT_lod"]["ids"];
  auto read = [](const nlohmann::json& d) {
    const std::string text = d.dump();
    return load(std::vector<uint8_t>(text.begin(), text.end()), "skip.gltf");
  };
  // Level 1 drawn with the full mesh: as many vertices as level 0, skipped
  // (a copy has room for the full mesh's vertices, no more).
  nlohmann::json same = doc;
  same["nodes"][ids[0].get<size_t>()]["mesh"] = doc["nodes"][main]["mesh"];
  Character c = read(same);
  ASSERT_EQ(c.file_lods.size(), 1u);
  EXPECT_LT(c.file_lods[0].vertex_count(), c.mesh.vertex_count());
  EXPECT_EQ(c.file_lod_errors.size(), 1u);
  // A level with nothing to draw: skipped, not counted as exact.
  nlohmann::json empty = doc;
  empty["meshes"].push_back({{"name", "nothing"}, {"primitives", nlohmann::json::array()}});
  empty["nodes"][ids[1].get<size_t>()]["mesh"] = empty["meshes"].size() - 1;
  c = read(empty);
  ASSERT_EQ(c.file_lods.size(), 1u);
  EXPECT_GT(c.file_lods[0].triangle_count(), 0u);
}
