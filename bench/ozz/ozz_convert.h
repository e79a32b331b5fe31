// crowdprof's character handed to ozz-animation's offline builders, for
// ozz_driver (bench/ozz): the same skeleton, keys and mesh on both sides.
// The project's own code; it links ozz built from a source tree the script is
// given (none of ozz's code is in the project).
#pragma once

#include <string>
#include <vector>

#include "asset/character.h"

#include "ozz/animation/runtime/animation.h"
#include "ozz/animation/runtime/skeleton.h"
#include "ozz/base/maths/simd_math.h"
#include "ozz/base/memory/unique_ptr.h"

namespace ozz_bench {

[[noreturn]] void fail(const std::string& why);

// The mesh cut into parts of equal influence count (ozz's layout): per part,
// its vertices' positions, normals, joint indices (ozz's joint order) and
// all weights but the last.
struct Part {
  int influences = 1;
  std::vector<uint32_t> vertex;  // the crowdprof vertex each one is
  std::vector<float> positions, normals, weights;
  std::vector<uint16_t> joints;
};

struct OzzCharacter {
  ozz::unique_ptr<ozz::animation::Skeleton> skeleton;
  std::vector<int> ozz_of_joint;                   // ozz's index of each crowdprof joint
  std::vector<ozz::math::Float4x4> inverse_binds;  // in ozz's joint order
  std::vector<Part> parts;
};

// Fails (exits) for what the comparison cannot take: joints with non-joint
// nodes between them, names that are not unique.
OzzCharacter make_ozz_character(const crowdprof::Character& c);

// Rounds the skeleton's rest translations and scales and every translation
// and scale key to half precision, ozz's FloatToHalf as its AnimationBuilder
// stores them (a bone 0.3 m long moves up to 0.06 mm; ten in a chain, past
// 0.2 mm), so that both sides pose the same skeleton and a vertex check
// measures the jobs, not ozz's storage (rotations: take_ozz_rotation_keys).
void round_like_ozz_storage(crowdprof::Character& c);

// Replaces every rotation key of `action` by the one ozz holds for it (15
// bits a component: up to 4e-5 rad a joint, 0.3 mm at a fingertip after 15
// joints), read back through ozz's SamplingJob at the key's time, for the
// same reason as round_like_ozz_storage.
void take_ozz_rotation_keys(crowdprof::Action& action, const ozz::animation::Animation& animation,
                            const OzzCharacter& ozz_character);

// One action as an ozz animation, keys shifted to start at 0 (LINEAR only).
ozz::unique_ptr<ozz::animation::Animation> make_ozz_animation(const crowdprof::Character& c,
                                                              const crowdprof::Action& action,
                                                              const OzzCharacter& ozz_character);

// ozz's SkinningJob on one part: positions and normals out, 3 floats a vertex.
void skin_part_with_ozz(const Part& part, const std::vector<ozz::math::Float4x4>& skinning, float* positions,
                        float* normals);

}  // namespace ozz_bench
