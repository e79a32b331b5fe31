// What the culling audit (scene/culling_audit.h) finds: the record a bench
// result stores as it is (result/result.h), so this header stays light.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace crowdprof {

// The boxes a copy can be culled with, loosest first as engines meet them.
enum class CullBox : uint8_t {
  BindPose,     // the mesh's stored box, unposed (bind_pose_bounds): misses limbs that move out of it
  EveryAction,  // every action's poses, padded (animated_bounds): crowdprof's own culling box
  OwnAction,    // the poses of the action the copy plays, padded (action_bounds)
  Tight,        // this frame's skinned vertices: the tightest a box can be, known only after skinning
};
inline constexpr size_t kCullBoxes = 4;
std::string_view cull_box_name(CullBox box);  // "bind_pose", "every_action", "own_action", "tight"

// One strategy over the audited frames (counts are of copy-frames).
struct CullBoxAudit {
  uint64_t drawn = 0;         // kept by the box (it intersects the frustum)
  uint64_t false_culls = 0;   // culled while a skinned vertex is inside the frustum: the copy pops out
  uint64_t missed_culls = 0;  // drawn while every vertex lies outside one plane: work for nothing
  uint64_t worst_frame_false_culls = 0, worst_frame_missed_culls = 0;  // in any one frame
  // The box's volume over the tight box's (both world-axis boxes), mean and
  // largest over the copy-frames whose tight box has a volume.
  double slack_mean = 0, slack_max = 0;
};

struct CullingAudit {
  size_t frames = 0;       // poses audited per copy
  size_t copies = 0;       // copies audited per frame
  size_t copy_stride = 1;  // every copy_stride-th copy of the crowd (1: all)
  uint64_t in_view = 0;    // copy-frames with a skinned vertex inside the frustum
  uint64_t outside = 0;    // copy-frames with every vertex outside one plane
  // Neither: no vertex inside, yet no one plane has them all outside (a
  // triangle may cross a corner of the view); counted as no strategy's error.
  uint64_t undecided = 0;
  std::array<CullBoxAudit, kCullBoxes> boxes{};
  double ms = 0;  // what the audit took, wall clock (CrowdBench::audit_culling)
};

}  // namespace crowdprof
