// The generator's own description of the humanoid, shared by its three parts:
// the rig (humanoid.cpp), the skinned mesh (humanoid_mesh.cpp) and the actions
// (humanoid_actions.cpp). Internal to the generator: everyone else reads the
// Character it produces.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "asset/character.h"
#include "gen/humanoid.h"

namespace crowdprof::humanoid {

enum class Part : uint8_t {
  Hips,
  Spine,
  Neck,
  Head,
  Jaw,
  Clavicle,
  UpperArm,
  Forearm,
  Hand,
  Metacarpal,
  Finger,
  Thigh,
  Shin,
  Foot,
  Toe,
};

struct Bone {
  std::string name;
  int parent = -1;
  Part part = Part::Hips;
  int side = 0;                                // +1 the character's left (+X), -1 its right, 0 the midline
  int finger = -1;                             // 0 thumb .. 4 little finger
  int segment = 0;                             // index in its chain (a limb or the spine may be split)
  int segments = 1;                            // length of that chain
  glm::dvec3 head{0.0};                        // bind pose, model space
  glm::dvec3 tail{0.0};                        // where the bone ends: its child's head, or a tip
  glm::dquat orientation{1.0, 0.0, 0.0, 0.0};  // model space; local +Y runs head to tail
};

// Body measurements, varied a little by the seed.
struct Build {
  double height = 1.0;  // scale of every length
  double width = 1.0;   // shoulders and hips, across X
  double girth = 1.0;   // radii of the mesh
};

struct Rig {
  Build build;
  std::vector<Bone> bones;

  // Bones of one chain in order (empty when the rig lacks it).
  std::vector<int> chain(Part part, int side = 0, int finger = -1) const;
  int first(Part part, int side = 0, int finger = -1) const;  // -1 when absent
  int last(Part part, int side = 0, int finger = -1) const;   // -1 when absent
};

// Narrows a generated value to float by way of a multiple of 2^-24. The last
// bits of a double result depend on the build (FMA contraction under
// -march=native, the libm) and near-zero results are noise (1e-17 or -2e-17);
// rounding both away first (zero without its sign) makes the generated file
// the same bytes from any x86-64 build, which the committed default scene relies on.
inline float stable_float(double v) {
  double r = std::nearbyint(v * 0x1p24) * 0x1p-24;
  return r == 0.0 ? 0.0f : static_cast<float>(r);
}
inline glm::vec3 stable_float(const glm::dvec3& v) {
  return {stable_float(v.x), stable_float(v.y), stable_float(v.z)};
}

// A small, portable random source: the same seed gives the same numbers everywhere.
class Random {
 public:
  explicit Random(uint64_t seed) : state_(seed) {}
  double uniform();  // [0, 1)
  double range(double lo, double hi) { return lo + (hi - lo) * uniform(); }

 private:
  uint64_t state_;
};

// The mesh around the rig's bind pose, with exactly `vertices` vertices (at
// least kHumanoidMinVertices), normals and weights. Fills positions, normals,
// joints, weights, indices and one primitive.
SkinnedMesh build_mesh(const Rig& rig, int vertices);

// The looping actions, for the skeleton made from the rig (same joint order).
std::vector<Action> build_actions(const Rig& rig, const Skeleton& skeleton, uint32_t seed, HumanoidActions set);

inline constexpr double kPi = 3.141592653589793;

}  // namespace crowdprof::humanoid
