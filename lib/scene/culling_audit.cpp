#include "scene/culling_audit.h"
#include "animation/run_job.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "animation/binding.h"
#include "animation/exact_palette.h"
#include "skinning/skinning.h"

namespace crowdprof {

std::string_view cull_box_name(CullBox box) {
  switch (box) {
    case CullBox::BindPose:
      return "bind_pose";
    case CullBox::EveryAction:
      return "every_action";
    case CullBox::OwnAction:
      return "own_action";
    case CullBox::Tight:
      return "tight";
  }
  return "?";
}

// Immutable once made: what posing and skinning one character needs, and its boxes.
struct CullingAuditor::CharacterData {
  const Character* character = nullptr;
  SkinningPlan plan;
  std::vector<ActionBindings> bindings;  // per action
  Aabb bind_pose;
  std::vector<Aabb> own_action;  // per action (one, the rest pose's, without actions)
};

struct CullingAuditor::Scratch {
  ExactPalette reference;
  std::vector<glm::vec3> positions, normals;
};

// One audited copy in one frame.
struct CullingAuditor::Verdict {
  enum Truth : uint8_t { InView, Outside, Undecided, NoMesh } truth = NoMesh;
  std::array<bool, kCullBoxes> drawn{};
  std::array<double, kCullBoxes> slack{};  // < 0: no tight volume to compare with
};

namespace {

double volume(const Aabb& box) {
  const glm::vec3 s = glm::max(box.size(), glm::vec3(0.0f));
  return static_cast<double>(s.x) * s.y * s.z;
}

Aabb empty_box() {
  return Aabb{glm::vec3(std::numeric_limits<float>::max()), glm::vec3(std::numeric_limits<float>::lowest())};
}

}  // namespace

CullingAuditor::CullingAuditor(std::span<const Character* const> characters, const Crowd& crowd, const Frustum& frustum,
                               size_t copy_stride)
    : crowd_(crowd), frustum_(frustum) {
  for (const Character* c : characters) {
    auto data = std::make_unique<CharacterData>();
    data->character = c;
    if (c->mesh.vertex_count() > 0) {
      if (std::string why = build_skinning_plan(c->mesh, c->skeleton.joint_count(), &data->plan); !why.empty())
        throw std::runtime_error("skinning plan: " + why);  // the loader checked the same: a bug if reached
    }
    for (const Action& action : c->actions) data->bindings.push_back(bind_action(c->skeleton, action));
    data->bind_pose = bind_pose_bounds(*c);
    for (size_t a = 0; a < std::max<size_t>(1, c->actions.size()); ++a)
      data->own_action.push_back(action_bounds(*c, a));
    characters_.push_back(std::move(data));
  }
  audit_.copy_stride = std::max<size_t>(1, copy_stride);
  for (size_t i = 0; i < crowd.size(); i += audit_.copy_stride) {
    const CharacterData& data = *characters_[crowd.kind[i]];
    audited_.push_back(i);
    const size_t action = data.character->actions.empty() ? 0 : crowd.action[i];
    fixed_boxes_.push_back({transform_aabb(data.bind_pose, crowd.world[i]), crowd.world_boxes[i],
                            transform_aabb(data.own_action[action], crowd.world[i])});
  }
  audit_.copies = audited_.size();
  verdicts_.resize(audited_.size());
}

CullingAuditor::~CullingAuditor() = default;

void CullingAuditor::add_frame(std::span<const float> action_times, tbb::task_arena* arena) {
  if (action_times.size() != crowd_.size()) throw std::invalid_argument("culling audit: one time per copy");
  tbb::enumerable_thread_specific<Scratch> scratches;
  auto audit_copies = [&](const tbb::blocked_range<size_t>& range) {
    Scratch& s = scratches.local();
    for (size_t n = range.begin(); n != range.end(); ++n) {
      const size_t i = audited_[n];
      const CharacterData& data = *characters_[crowd_.kind[i]];
      const Character& c = *data.character;
      Verdict& verdict = verdicts_[n];
      verdict = Verdict{};
      const size_t vertices = c.mesh.vertex_count();
      if (vertices == 0) continue;
      s.positions.resize(vertices);
      s.normals.resize(vertices);
      const Action* action = c.actions.empty() ? nullptr : &c.actions[crowd_.action[i]];
      std::span<const int32_t> targets;
      if (action) targets = data.bindings[crowd_.action[i]].targets;
      const std::span<const SkinMatrix> palette = s.reference.at(c.skeleton, action, targets, action_times[i]);
      run_job(SkinningJob{palette, &data.plan, 0, vertices, s.positions, s.normals}, "SkinningJob");
      // The truth from the vertices: one inside every plane, or all outside one plane.
      Aabb tight = empty_box();
      bool any_inside = false;
      std::array<bool, 6> all_outside;
      all_outside.fill(true);
      const glm::mat4& world = crowd_.world[i];
      for (const glm::vec3& local : s.positions) {
        const glm::vec3 p = glm::vec3(world * glm::vec4(local, 1.0f));
        tight.min = glm::min(tight.min, p);
        tight.max = glm::max(tight.max, p);
        bool inside = true;
        for (size_t k = 0; k < 6; ++k) {
          const glm::vec4& plane = frustum_.planes[k];
          if (glm::dot(glm::vec3(plane), p) + plane.w < 0.0f)
            inside = false;
          else
            all_outside[k] = false;
        }
        any_inside = any_inside || inside;
      }
      const bool outside = std::find(all_outside.begin(), all_outside.end(), true) != all_outside.end();
      verdict.truth = any_inside ? Verdict::InView : outside ? Verdict::Outside : Verdict::Undecided;
      const double tight_volume = volume(tight);
      for (size_t b = 0; b < kCullBoxes; ++b) {
        const Aabb& box = b == static_cast<size_t>(CullBox::Tight) ? tight : fixed_boxes_[n][b];
        verdict.drawn[b] = intersects(frustum_, box);
        verdict.slack[b] = tight_volume > 0 ? volume(box) / tight_volume : -1.0;
      }
    }
  };
  auto run = [&] { tbb::parallel_for(tbb::blocked_range<size_t>(0, audited_.size(), 16), audit_copies); };
  if (arena)
    arena->execute(run);
  else
    run();
  // Sums in copy order, so the figures do not depend on the threads.
  std::array<uint64_t, kCullBoxes> false_culls{}, missed_culls{};
  for (const Verdict& v : verdicts_) {
    if (v.truth == Verdict::NoMesh) continue;
    audit_.in_view += v.truth == Verdict::InView;
    audit_.outside += v.truth == Verdict::Outside;
    audit_.undecided += v.truth == Verdict::Undecided;
    for (size_t b = 0; b < kCullBoxes; ++b) {
      CullBoxAudit& a = audit_.boxes[b];
      a.drawn += v.drawn[b];
      false_culls[b] += !v.drawn[b] && v.truth == Verdict::InView;
      missed_culls[b] += v.drawn[b] && v.truth == Verdict::Outside;
      if (v.slack[b] >= 0) {
        slack_sum_[b] += v.slack[b];
        ++slack_count_[b];
        a.slack_max = std::max(a.slack_max, v.slack[b]);
      }
    }
  }
  for (size_t b = 0; b < kCullBoxes; ++b) {
    CullBoxAudit& a = audit_.boxes[b];
    a.false_culls += false_culls[b];
    a.missed_culls += missed_culls[b];
    a.worst_frame_false_culls = std::max(a.worst_frame_false_culls, false_culls[b]);
    a.worst_frame_missed_culls = std::max(a.worst_frame_missed_culls, missed_culls[b]);
    a.slack_mean = slack_count_[b] ? slack_sum_[b] / static_cast<double>(slack_count_[b]) : 0.0;
  }
  ++audit_.frames;
}

}  // namespace crowdprof
