// Every Khronos sample in ../shared/samples loads with the counts SAMPLES.md lists,
// and Draco variants agree with the plain files. Skips when the folder is absent.
#include <gtest/gtest.h>

#include <cmath>

#include "asset/asset_report.h"
#include "asset/gltf_loader.h"
#include "test_support.h"

using namespace crowdprof;
using crowdprof::test::sample;

namespace {

struct Expected {
  const char* file;
  size_t joints, primitives, vertices;
  int max_influences;  // 0: not checked (Draco rows in SAMPLES.md say "None")
  bool draco;
  std::vector<std::pair<std::string, float>> actions;  // name ("" = unnamed), duration
};

const std::vector<Expected>& expectations() {
  static const std::vector<Expected> rows = {
      {"CesiumMan/glTF-Binary/CesiumMan.glb", 19, 1, 3273, 4, false, {{"", 2.0f - 0.0417f}}},
      {"CesiumMan/glTF-Draco/CesiumMan.gltf", 19, 1, 3572, 0, true, {{"", 2.0f - 0.0417f}}},
      {"Fox/glTF-Binary/Fox.glb", 24, 1, 1728, 4, false, {{"Survey", 3.417f}, {"Walk", 0.7083f}, {"Run", 1.158f}}},
      {"Fox/glTF/Fox.gltf", 24, 1, 1728, 4, false, {{"Survey", 3.417f}, {"Walk", 0.7083f}, {"Run", 1.158f}}},
      {"RiggedFigure/glTF-Binary/RiggedFigure.glb", 19, 1, 370, 4, false, {{"", 1.25f}}},
      {"RiggedFigure/glTF-Draco/RiggedFigure.gltf", 19, 1, 367, 0, true, {{"", 1.25f}}},
      {"RiggedSimple/glTF-Binary/RiggedSimple.glb", 2, 1, 160, 2, false, {{"", 2.083f - 0.0417f}}},
      {"RiggedSimple/glTF-Draco/RiggedSimple.gltf", 2, 1, 160, 0, true, {{"", 2.083f - 0.0417f}}},
      {"SimpleSkin/glTF/SimpleSkin.gltf", 2, 1, 10, 2, false, {{"", 5.5f}}},
  };
  return rows;
}

int max_influences(const SkinnedMesh& mesh) {
  auto h = influence_histogram(mesh);
  for (int k = 3; k >= 0; --k)
    if (h[static_cast<size_t>(k)]) return k + 1;
  return 0;
}

}  // namespace

TEST(Samples, LoadWithListedCounts) {
  CROWDPROF_REQUIRE_SAMPLES();
  for (const Expected& e : expectations()) {
    SCOPED_TRACE(e.file);
    GltfAsset asset = load_gltf(sample(e.file));
    ASSERT_EQ(asset.characters.size(), 1u);
    const Character& c = asset.characters[0];
    EXPECT_EQ(c.skeleton.joint_count(), e.joints);
    EXPECT_EQ(c.mesh.primitives.size(), e.primitives);
    EXPECT_EQ(c.mesh.vertex_count(), e.vertices);
    if (e.max_influences) {
      EXPECT_EQ(max_influences(c.mesh), e.max_influences);
    }
    EXPECT_EQ(c.draco_decoded, e.draco);
    ASSERT_EQ(c.actions.size(), e.actions.size());
    for (size_t a = 0; a < e.actions.size(); ++a) {
      if (!e.actions[a].first.empty()) {
        EXPECT_EQ(c.actions[a].name, e.actions[a].first);
      }
      EXPECT_NEAR(c.actions[a].duration(), e.actions[a].second, 2e-3);
    }
    for (size_t j = 0; j < c.skeleton.joint_count(); ++j) EXPECT_LT(c.skeleton.parents[j], static_cast<int>(j));
    for (const glm::vec4& w : c.mesh.weights) EXPECT_NEAR(w.x + w.y + w.z + w.w, 1.0f, 1e-5f);
    EXPECT_EQ(c.mesh.normals.size(), c.mesh.vertex_count());
  }
}

TEST(Samples, AnimationsThatStartLate) {
  CROWDPROF_REQUIRE_SAMPLES();
  Character man = load_character(sample("CesiumMan/glTF-Binary/CesiumMan.glb"));
  EXPECT_NEAR(man.actions[0].start, 0.0417f, 1e-3f);
  Character simple = load_character(sample("RiggedSimple/glTF-Binary/RiggedSimple.glb"));
  EXPECT_NEAR(simple.actions[0].start, 0.0417f, 1e-3f);
}

TEST(Samples, FoxIsNonIndexedWithThreeActions) {
  CROWDPROF_REQUIRE_SAMPLES();
  Character fox = load_character(sample("Fox/glTF-Binary/Fox.glb"));
  ASSERT_EQ(fox.mesh.indices.size(), fox.mesh.vertex_count());
  for (size_t i = 0; i < fox.mesh.indices.size(); ++i) ASSERT_EQ(fox.mesh.indices[i], i);
  Character fox_text = load_character(sample("Fox/glTF/Fox.gltf"));
  EXPECT_EQ(fox.mesh.positions, fox_text.mesh.positions);
  EXPECT_EQ(fox.mesh.weights, fox_text.mesh.weights);
}

TEST(Samples, InterpolationTestHasNoSkinButNineNodeAnimations) {
  CROWDPROF_REQUIRE_SAMPLES();
  GltfAsset asset = load_gltf(sample("InterpolationTest/glTF-Binary/InterpolationTest.glb"));
  EXPECT_TRUE(asset.characters.empty());
  EXPECT_EQ(asset.node_actions.size(), 9u);
  try {
    load_character(sample("InterpolationTest/glTF-Binary/InterpolationTest.glb"));
    ADD_FAILURE() << "a file with no skin must be refused as a character";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("has no skin"), std::string::npos) << e.what();
  }
}

// Draco re-indexes vertices: match each decoded vertex to the plain vertex at the
// same position, then compare what skinning reads.
TEST(Samples, DracoVariantsAgreeWithPlainWithin1e3) {
  CROWDPROF_REQUIRE_SAMPLES();
  const std::pair<const char*, const char*> pairs[] = {
      {"CesiumMan/glTF-Binary/CesiumMan.glb", "CesiumMan/glTF-Draco/CesiumMan.gltf"},
      {"RiggedFigure/glTF-Binary/RiggedFigure.glb", "RiggedFigure/glTF-Draco/RiggedFigure.gltf"},
      {"RiggedSimple/glTF-Binary/RiggedSimple.glb", "RiggedSimple/glTF-Draco/RiggedSimple.gltf"},
  };
  for (auto [plain_file, draco_file] : pairs) {
    SCOPED_TRACE(draco_file);
    Character plain = load_character(sample(plain_file));
    Character draco = load_character(sample(draco_file));
    ASSERT_EQ(plain.skeleton.joint_count(), draco.skeleton.joint_count());
    EXPECT_EQ(plain.skeleton.names, draco.skeleton.names);
    EXPECT_EQ(plain.skeleton.parents, draco.skeleton.parents);
    ASSERT_EQ(plain.actions.size(), draco.actions.size());
    EXPECT_EQ(plain.actions[0].channels.size(), draco.actions[0].channels.size());
    // Draco quantises positions over the model's extent: allow 1e-3 of it.
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const glm::vec3& p : plain.mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    float tolerance = 1e-3f * glm::length(hi - lo);
    size_t unmatched = 0;
    for (size_t v = 0; v < draco.mesh.vertex_count(); ++v) {
      const glm::vec3& p = draco.mesh.positions[v];
      size_t best = 0;
      float best_distance = INFINITY;
      for (size_t u = 0; u < plain.mesh.vertex_count(); ++u) {
        float d = glm::length(plain.mesh.positions[u] - p);
        if (d < best_distance) best_distance = d, best = u;
      }
      if (best_distance > tolerance) {
        ++unmatched;
        continue;
      }
      // Skinning reads (joint, weight) pairs: compare the weight each joint gets.
      for (int k = 0; k < 4; ++k) {
        float wd = 0, wp = 0;
        for (int i = 0; i < 4; ++i) {
          if (draco.mesh.joints[v][i] == draco.mesh.joints[v][k]) wd += draco.mesh.weights[v][i];
          if (plain.mesh.joints[best][i] == draco.mesh.joints[v][k]) wp += plain.mesh.weights[best][i];
        }
        if (draco.mesh.weights[v][k] > 0) {
          EXPECT_NEAR(wd, wp, 1e-3f) << "vertex " << v;
        }
      }
    }
    EXPECT_EQ(unmatched, 0u);
  }
}
