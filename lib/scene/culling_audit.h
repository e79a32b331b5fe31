// How honest a culling box is (issue 29): each copy posed exactly, skinned, and
// its vertices tested against the frustum, beside what each box strategy
// decides for it. Outside the timed frame; in parallel over copies.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include <tbb/task_arena.h>

#include "asset/character.h"
#include "scene/bounds.h"
#include "scene/camera.h"
#include "scene/cull_audit.h"
#include "scene/crowd.h"

namespace crowdprof {

// The characters' boxes and skinning plans, made once; then one add_frame per
// audited pose of the crowd. Not thread-safe itself; add_frame runs its copies
// in parallel in `arena` (null: the calling thread's default arena).
class CullingAuditor {
 public:
  // `crowd.world_boxes` are taken as the EveryAction boxes, so the audit
  // checks exactly the boxes the frames cull with. Audits every
  // `copy_stride`-th copy (at least 1).
  CullingAuditor(std::span<const Character* const> characters, const Crowd& crowd, const Frustum& frustum,
                 size_t copy_stride = 1);
  ~CullingAuditor();
  CullingAuditor(const CullingAuditor&) = delete;
  CullingAuditor& operator=(const CullingAuditor&) = delete;

  // One frame: copy i posed at `action_times[i]` (seconds on its action's clock).
  void add_frame(std::span<const float> action_times, tbb::task_arena* arena = nullptr);
  const CullingAudit& audit() const { return audit_; }

 private:
  struct CharacterData;
  struct Scratch;
  struct Verdict;
  std::vector<std::unique_ptr<CharacterData>> characters_;
  const Crowd& crowd_;
  Frustum frustum_;
  std::vector<size_t> audited_;                                // copy indices
  std::vector<std::array<Aabb, kCullBoxes - 1>> fixed_boxes_;  // per audited copy, world: all but Tight
  std::vector<Verdict> verdicts_;                              // per audited copy, this frame
  double slack_sum_[kCullBoxes] = {};
  uint64_t slack_count_[kCullBoxes] = {};
  CullingAudit audit_;
};

}  // namespace crowdprof
