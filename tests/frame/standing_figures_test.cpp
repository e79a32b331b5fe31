// Heights and distances as the character stands in its scene (issue 50): a
// character modelled Z-up in centimetres and turned upright and scaled by a
// node (a common export) is measured by its skinned rest pose, so `info`'s
// mesh LOD figures, the budget's drawn error and mesh LOD's levels come out in
// metres and as a share of the height it stands, as for the same character
// modelled Y-up in metres. Each figure is held against one worked out here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "asset/asset_report.h"
#include "asset/gltf_loader.h"
#include "asset/mesh_lod.h"
#include "asset/standing.h"
#include "asset/vertex_order.h"
#include "characters.h"
#include "frame/crowd_bench.h"
#include "base/modes.h"
#include "gen/gltf_writer.h"
#include "test_support.h"

using namespace crowdprof;

namespace {

// The mesh's space to the world's: turned from Z-up to Y-up (-90 degrees about
// X) and scaled from centimetres to metres.
constexpr float kCentimetre = 0.01f;
const glm::quat kUpright = glm::angleAxis(glm::radians(-90.0f), glm::vec3(1, 0, 0));
glm::mat4 to_world() {
  return glm::mat4_cast(kUpright) * glm::scale(glm::mat4(1.0f), glm::vec3(kCentimetre));
}

// `c` (Y-up, metres) as an exporter writes it from a Z-up scene in
// centimetres: every joint, key and vertex in that space, and one node above
// the root turning and scaling it back. Skinned, it stands exactly where `c` does.
Character z_up_centimetres(const Character& c) {
  const glm::mat4 w = to_world(), w_inverse = glm::inverse(w);
  const glm::quat turn_back = glm::inverse(kUpright);
  auto point = [&](const glm::vec3& p) { return glm::vec3(w_inverse * glm::vec4(p, 1.0f)); };
  auto rotation = [&](const glm::quat& q) { return turn_back * q * kUpright; };
  auto scale = [](const glm::vec3& s) { return glm::vec3(s.x, s.z, s.y); };  // axes y and z swap
  Character z = c;
  Skeleton& s = z.skeleton;
  for (size_t j = 0; j < s.joint_count(); ++j) {
    s.rest_translations[j] = point(s.rest_translations[j]);
    s.rest_rotations[j] = rotation(s.rest_rotations[j]);
    s.rest_scales[j] = scale(s.rest_scales[j]);
    s.inverse_binds[j] = w_inverse * s.inverse_binds[j] * w;
    s.parent_offsets[j] = s.parents[j] < 0 ? s.parent_offsets[j] * w : w_inverse * s.parent_offsets[j] * w;
  }
  for (glm::vec3& p : z.mesh.positions) p = point(p);
  for (glm::vec3& n : z.mesh.normals) n = turn_back * n;
  for (Action& action : z.actions)
    for (Channel& channel : action.channels)
      for (size_t k = 0; k + static_cast<size_t>(channel.components()) <= channel.values.size();
           k += static_cast<size_t>(channel.components())) {
        float* v = &channel.values[k];
        if (channel.path == ChannelPath::Rotation) {
          const glm::quat q = rotation(glm::quat(v[3], v[0], v[1], v[2]));
          v[0] = q.x, v[1] = q.y, v[2] = q.z, v[3] = q.w;
        } else {
          const glm::vec3 turned =
              channel.path == ChannelPath::Translation ? point({v[0], v[1], v[2]}) : scale({v[0], v[1], v[2]});
          v[0] = turned.x, v[1] = turned.y, v[2] = turned.z;
        }
      }
  return z;
}

float y_extent(const SkinnedMesh& mesh) {
  auto [low, high] = std::minmax_element(mesh.positions.begin(), mesh.positions.end(),
                                         [](const glm::vec3& a, const glm::vec3& b) { return a.y < b.y; });
  return high->y - low->y;
}

// The generated humanoid, written Z-up in centimetres and loaded back as any file.
const Character& z_up_humanoid() {
  static const Character loaded = [] {
    const std::string path = (test::scratch_dir("standing") / "z-up-cm.glb").string();
    write_gltf(z_up_centimetres(test::small_humanoid()), path);
    return load_character(path);
  }();
  return loaded;
}

bool within_percent(double value, double expected) {
  return std::abs(value - expected) <= 0.01 * std::abs(expected);
}

BenchConfig config_of(const std::string& mode, size_t copies) {
  BenchConfig config;
  config.mode = find_mode(mode)->switches;
  config.mode_name = mode;
  config.threads = 1;
  config.crowd.copies = copies;
  config.crowd.actions = ActionChoice::Random;
  return config;
}

}  // namespace

TEST(Standing, AZUpCentimetreExportStandsAsTheSameCharacterInMetres) {
  const Character& original = test::small_humanoid();
  const float height = y_extent(original.mesh);  // Y-up in metres: its mesh is how it stands
  const Standing z = standing_of(z_up_humanoid());
  EXPECT_PRED2(within_percent, z.height, height);
  EXPECT_PRED2(within_percent, z.world_per_mesh_unit, kCentimetre);
  EXPECT_GT(y_extent(z_up_humanoid().mesh), 2 * height) << "the mesh's own Y is its depth in centimetres";
  const Standing y = standing_of(original);
  EXPECT_PRED2(within_percent, y.height, height);
  EXPECT_PRED2(within_percent, y.world_per_mesh_unit, 1.0f);
}

TEST(Standing, CesiumManStandsAsItsZUpNodeTurnsIt) {
  CROWDPROF_REQUIRE_SAMPLES();
  const Character man = load_character(test::sample("CesiumMan/glTF-Binary/CesiumMan.glb"));
  // Its Z_UP node turns the mesh's Z into the world's Y, unscaled.
  auto [low, high] = std::minmax_element(man.mesh.positions.begin(), man.mesh.positions.end(),
                                         [](const glm::vec3& a, const glm::vec3& b) { return a.z < b.z; });
  const float by_hand = high->z - low->z;
  EXPECT_PRED2(within_percent, standing_of(man).height, by_hand);
  EXPECT_NEAR(standing_of(man).height, 1.507, 0.01);
  const nlohmann::json info = describe_asset(load_gltf(test::sample("CesiumMan/glTF-Binary/CesiumMan.glb")));
  const nlohmann::json& lods = info["characters"][0]["mesh_lods"];
  ASSERT_FALSE(lods.empty());
  for (const nlohmann::json& level : lods)
    EXPECT_PRED2(within_percent, level["error_fraction"].get<double>(), level["error"].get<double>() / by_hand);
}

// info's mesh LOD errors: meshoptimizer's, in the file's centimetres, given in
// metres and as a share of the height it stands.
TEST(Standing, InfoGivesMeshLodErrorsInMetresOfTheStandingHeight) {
  const Character& z = z_up_humanoid();
  SkinnedMesh ordered = z.mesh;
  order_vertices_by_joints(ordered);
  const std::vector<MeshLod> in_centimetres = build_mesh_lods(ordered);
  ASSERT_FALSE(in_centimetres.empty());
  const std::string path = (test::scratch_dir("standing") / "z-up-cm.glb").string();
  write_gltf(z, path);
  const nlohmann::json info = describe_asset(load_gltf(path))["characters"][0];
  const double height = y_extent(test::small_humanoid().mesh);
  EXPECT_PRED2(within_percent, info["height"].get<double>(), height);
  ASSERT_EQ(info["mesh_lods"].size(), in_centimetres.size());
  for (size_t l = 0; l < in_centimetres.size(); ++l) {
    const double metres = in_centimetres[l].error * kCentimetre;
    EXPECT_PRED2(within_percent, info["mesh_lods"][l]["error"].get<double>(), metres) << l;
    EXPECT_PRED2(within_percent, info["mesh_lods"][l]["error_fraction"].get<double>(), metres / height) << l;
  }
}

// The budget's drawn error (shared poses at times snapped to 1/30 s): the same
// millimetres and pixels as the Y-up character's in the same scene, and the same
// share of the height.
TEST(Standing, TheBudgetsDrawnErrorIsInMetresOfTheStandingHeight) {
  const Character& original = test::small_humanoid();
  const double height = y_extent(original.mesh);
  auto measure = [](const Character& c) {
    CrowdBench bench(c, config_of("budget", 60));
    for (int f = 0; f < 5; ++f) bench.step();
    return bench.measure_drawn_error(900);
  };
  const DrawnErrorRecord y = measure(original), z = measure(z_up_humanoid());
  ASSERT_GT(y.max, 0.0) << "snapped times stray";
  EXPECT_EQ(z.copies_checked, y.copies_checked);
  EXPECT_PRED2(within_percent, z.max, y.max);
  EXPECT_PRED2(within_percent, z.rms, y.rms);
  EXPECT_PRED2(within_percent, z.max_px, y.max_px);
  EXPECT_PRED2(within_percent, z.max_fraction, z.max / height);
  EXPECT_PRED2(within_percent, z.rms_fraction, z.rms / height);
}

// Mesh LOD's levels in a run: each level's error in metres, as a share of the
// height, and in pixels as the Y-up character's levels are per metre.
TEST(Standing, MeshLodLevelsInARunAreInMetresOfTheStandingHeight) {
  const Character& original = test::small_humanoid();
  const double height = y_extent(original.mesh);
  auto levels = [](const Character& c) {
    BenchConfig config = config_of("threaded", 400);
    config.mode.mesh_lod = true;
    CrowdBench bench(c, config);
    bench.step();
    return bench.mesh_lod_fidelity(900).levels;
  };
  const auto y = levels(original), z = levels(z_up_humanoid());
  SkinnedMesh ordered = z_up_humanoid().mesh;
  order_vertices_by_joints(ordered);
  const std::vector<MeshLod> in_centimetres = build_mesh_lods(ordered);
  size_t compared = 0;
  for (size_t l = 1; l < kMeshLevels && l <= in_centimetres.size(); ++l) {
    const double metres = in_centimetres[l - 1].error * kCentimetre;
    EXPECT_PRED2(within_percent, z[l].error, metres) << l;
    EXPECT_PRED2(within_percent, z[l].error_fraction, metres / height) << l;
    EXPECT_EQ(z[l].copies, y[l].copies) << l;
    if (z[l].error_px > 0 && y[l].error_px > 0) {
      EXPECT_PRED2(within_percent, z[l].error_px / z[l].error, y[l].error_px / y[l].error) << l;
      ++compared;
    }
  }
  EXPECT_GT(compared, 0u) << "no level drawn at any distance";
}
