#include "ozz_fades.h"

#include <cmath>
#include <cstdio>
#include <span>
#include <vector>

#include "animation/binding.h"
#include "animation/blending.h"
#include "animation/joint_mask.h"
#include "animation/local_pose.h"
#include "animation/pose.h"
#include "animation/run_job.h"
#include "animation/sampling.h"
#include "asset/standing.h"
#include "ozz_timing.h"
#include "skinning/simd_target.h"
#include "skinning/skinning.h"
#include "skinning/skinning_plan.h"

#include "ozz/animation/runtime/blending_job.h"
#include "ozz/animation/runtime/local_to_model_job.h"
#include "ozz/animation/runtime/sampling_job.h"
#include "ozz/base/maths/soa_transform.h"

namespace ozz_bench {
namespace {

namespace oa = ozz::animation;
using crowdprof::Character;

constexpr double kFadeFps = 60.0;
// Each copy's weight sweeps from 0.01 to 0.99 and back over this many
// seconds, copies spread over the sweep: every copy fades every frame, both
// actions always count.
constexpr double kWeightSweepSeconds = 0.5;
constexpr float kFadeThreshold = 0.1f;  // both jobs' default

// What copy `copy` plays at time t: from one action to the next of its
// character (the same action at another phase for a one-action character),
// each at its own time, and the weight of the second.
struct FadeAt {
  size_t from = 0, to = 0, over = 0;                 // over: the layered action
  double from_time = 0, to_time = 0, over_time = 0;  // seconds into each action
  float weight = 0;
};

FadeAt fade_at(const Character& c, size_t copy, size_t copies, double t) {
  const size_t actions = c.actions.size();
  auto local = [&](size_t a, double at) {
    const double d = c.actions[a].duration();
    return d > 0 ? std::fmod(at, d) : 0.0;
  };
  FadeAt f;
  f.from = copy % actions;
  f.to = (copy + 1) % actions;
  const double phase = 0.37 * static_cast<double>(copy);
  f.from_time = local(f.from, t + phase);
  f.to_time = local(f.to, t + 0.5 * phase);
  f.over = (copy + 2) % actions;
  f.over_time = local(f.over, t + 0.2 * phase);
  const double sweep = t / kWeightSweepSeconds + static_cast<double>(copy) / static_cast<double>(copies);
  f.weight = static_cast<float>(0.5 + 0.49 * std::sin(2.0 * 3.141592653589793 * sweep));
  return f;
}

// ozz's side of one copy: a sampling context per action it samples.
struct OzzFadeCopy {
  oa::SamplingJob::Context from_context, to_context, over_context;
  std::vector<ozz::math::SoaTransform> from, to, over, blended;
  std::vector<ozz::math::Float4x4> models;
};

// crowdprof's side of one copy: a pose and a cursor per action it samples.
struct CrowdprofFadeCopy {
  crowdprof::LocalPose from, to, over;
  crowdprof::SamplingCursor from_cursor, to_cursor, over_cursor;
};

// The joint, not the root, whose subtree holds closest to half the joints:
// an upper body on a humanoid, the front half on a quadruped.
size_t half_body_joint(const crowdprof::Skeleton& s) {
  std::vector<size_t> subtree(s.joint_count(), 1);
  for (size_t j = s.joint_count(); j-- > 1;)
    if (s.parents[j] >= 0) subtree[static_cast<size_t>(s.parents[j])] += subtree[j];
  size_t best = 0;
  auto off_half = [&](size_t j) {
    return std::abs(2.0 * static_cast<double>(subtree[j]) - static_cast<double>(s.joint_count()));
  };
  for (size_t j = 1; j < s.joint_count(); ++j)
    if (best == 0 || off_half(j) < off_half(best)) best = j;
  return best;
}

}  // namespace

void run_sampled_fades(Character& c, const OzzCharacter& ozz_character, const FadeRun& run) {
  const crowdprof::Skeleton& s = c.skeleton;
  const oa::Skeleton& skeleton = *ozz_character.skeleton;
  std::vector<ozz::unique_ptr<oa::Animation>> animations;
  std::vector<crowdprof::ActionBindings> bindings;
  for (crowdprof::Action& action : c.actions) {
    animations.push_back(make_ozz_animation(c, action, ozz_character));
    take_ozz_rotation_keys(action, *animations.back(), ozz_character);
    bindings.push_back(crowdprof::bind_action(s, action));
  }

  std::vector<OzzFadeCopy> theirs(run.copies);
  const size_t soa_joints = static_cast<size_t>(skeleton.num_soa_joints());
  for (OzzFadeCopy& copy : theirs) {
    copy.from_context.Resize(skeleton.num_joints());
    copy.to_context.Resize(skeleton.num_joints());
    copy.over_context.Resize(skeleton.num_joints());
    copy.from.resize(soa_joints);
    copy.to.resize(soa_joints);
    copy.over.resize(soa_joints);
    copy.blended.resize(soa_joints);
    copy.models.resize(static_cast<size_t>(skeleton.num_joints()));
  }
  // The layer's mask and its complement, per joint for crowdprof and per
  // four joints in ozz's order for ozz.
  std::vector<float> upper, lower;
  std::vector<ozz::math::SimdFloat4> ozz_upper, ozz_lower;
  std::string mask_joint;
  if (run.layered) {
    mask_joint = s.names[half_body_joint(s)];
    if (std::string why = crowdprof::joint_mask(s, mask_joint, 0, &upper); !why.empty()) fail(why);
    for (float w : upper) lower.push_back(1.0f - w);
    std::vector<float> by_ozz_upper(4 * soa_joints, 0.0f), by_ozz_lower(4 * soa_joints, 0.0f);
    for (size_t j = 0; j < s.joint_count(); ++j) {
      const size_t o = static_cast<size_t>(ozz_character.ozz_of_joint[j]);
      by_ozz_upper[o] = upper[j];
      by_ozz_lower[o] = lower[j];
    }
    for (size_t i = 0; i < soa_joints; ++i) {
      ozz_upper.push_back(ozz::math::simd_float4::LoadPtrU(&by_ozz_upper[4 * i]));
      ozz_lower.push_back(ozz::math::simd_float4::LoadPtrU(&by_ozz_lower[4 * i]));
    }
  }
  auto ozz_sample = [&](size_t action, double time, oa::SamplingJob::Context* context,
                        std::vector<ozz::math::SoaTransform>& out) {
    const double duration = c.actions[action].duration();
    oa::SamplingJob sampling;
    sampling.animation = animations[action].get();
    sampling.context = context;
    sampling.ratio = duration > 0 ? static_cast<float>(time / duration) : 0.0f;
    sampling.output = ozz::make_span(out);
    if (!sampling.Run()) fail("SamplingJob");
  };
  auto ozz_copy = [&](size_t i, double t) {
    OzzFadeCopy& copy = theirs[i];
    const FadeAt f = fade_at(c, i, run.copies, t);
    ozz_sample(f.from, f.from_time, &copy.from_context, copy.from);
    ozz_sample(f.to, f.to_time, &copy.to_context, copy.to);
    oa::BlendingJob::Layer layers[3];
    layers[0].weight = 1.0f - f.weight;
    layers[0].transform = ozz::make_span(copy.from);
    layers[1].weight = f.weight;
    layers[1].transform = ozz::make_span(copy.to);
    if (run.layered) {
      ozz_sample(f.over, f.over_time, &copy.over_context, copy.over);
      layers[0].joint_weights = ozz::make_span(ozz_lower);
      layers[1].joint_weights = ozz::make_span(ozz_lower);
      layers[2].weight = 1.0f;
      layers[2].transform = ozz::make_span(copy.over);
      layers[2].joint_weights = ozz::make_span(ozz_upper);
    }
    oa::BlendingJob blend;
    blend.threshold = kFadeThreshold;
    blend.layers = ozz::span<const oa::BlendingJob::Layer>(layers, run.layered ? 3 : 2);
    blend.rest_pose = skeleton.joint_rest_poses();
    blend.output = ozz::make_span(copy.blended);
    if (!blend.Run()) fail("BlendingJob");
    oa::LocalToModelJob ltm;
    ltm.skeleton = &skeleton;
    ltm.input = ozz::make_span(copy.blended);
    ltm.output = ozz::make_span(copy.models);
    if (!ltm.Run()) fail("LocalToModelJob");
  };

  // crowdprof's side: one blend and one model-space scratch for every copy,
  // as the frame keeps one a thread.
  std::vector<CrowdprofFadeCopy> ours(run.copies);
  crowdprof::LocalPose rest, blended;
  crowdprof::reset_to_rest(s, &rest);
  crowdprof::reset_to_rest(s, &blended);
  for (size_t i = 0; i < run.copies; ++i) {
    const FadeAt f = fade_at(c, i, run.copies, 0.0);
    crowdprof::reset_to_rest(s, &ours[i].from);
    crowdprof::reset_to_rest(s, &ours[i].to);
    crowdprof::reset_to_rest(s, &ours[i].over);
    crowdprof::reset_cursor(c.actions[f.from], &ours[i].from_cursor);
    crowdprof::reset_cursor(c.actions[f.to], &ours[i].to_cursor);
    crowdprof::reset_cursor(c.actions[f.over], &ours[i].over_cursor);
  }
  std::vector<glm::mat4> model(s.joint_count());
  auto our_copy = [&](size_t i, double t, std::span<glm::mat4> model_out) {
    CrowdprofFadeCopy& copy = ours[i];
    const FadeAt f = fade_at(c, i, run.copies, t);
    const crowdprof::Action& from = c.actions[f.from];
    const crowdprof::Action& to = c.actions[f.to];
    crowdprof::run_job(crowdprof::SamplingJob{&from, from.start + static_cast<float>(f.from_time),
                                              bindings[f.from].targets, &copy.from_cursor, &copy.from},
                       "SamplingJob");
    crowdprof::run_job(crowdprof::SamplingJob{&to, to.start + static_cast<float>(f.to_time), bindings[f.to].targets,
                                              &copy.to_cursor, &copy.to},
                       "SamplingJob");
    crowdprof::BlendLayer layers[] = {{&copy.from, 1.0f - f.weight}, {&copy.to, f.weight}, {}};
    if (run.layered) {
      const crowdprof::Action& over = c.actions[f.over];
      crowdprof::run_job(crowdprof::SamplingJob{&over, over.start + static_cast<float>(f.over_time),
                                                bindings[f.over].targets, &copy.over_cursor, &copy.over},
                         "SamplingJob");
      layers[0].joint_weights = layers[1].joint_weights = lower;
      layers[2] = {&copy.over, 1.0f, upper};
    }
    crowdprof::run_job(crowdprof::BlendingJob{std::span<const crowdprof::BlendLayer>(layers, run.layered ? 3 : 2),
                                              &rest, kFadeThreshold, &blended},
                       "BlendingJob");
    crowdprof::run_job(crowdprof::LocalToModelJob{&s, &blended, model_out}, "LocalToModelJob");
  };

  auto time_of = [](size_t f) { return static_cast<double>(f) / kFadeFps; };
  const InterleavedTimes times = time_interleaved(
      run.warmup, run.frames,
      [&](size_t f) {
        for (size_t i = 0; i < run.copies; ++i) ozz_copy(i, time_of(f));
      },
      [&](size_t f) {
        for (size_t i = 0; i < run.copies; ++i) our_copy(i, time_of(f), model);
      });

  // Every copy at the last frame, skinned by each side: how far ozz's vertices are.
  crowdprof::SkinningPlan plan;
  if (std::string why = crowdprof::build_skinning_plan(c.mesh, s.joint_count(), &plan); !why.empty()) fail(why);
  const size_t n = c.mesh.vertex_count();
  std::vector<crowdprof::SkinMatrix> palette(s.joint_count());
  std::vector<glm::vec3> positions(n), normals(n);
  std::vector<ozz::math::Float4x4> ozz_skinning(static_cast<size_t>(skeleton.num_joints()));
  const double last = time_of(run.warmup + run.frames - 1);
  double max_delta = 0;
  for (size_t i = 0; i < run.copies; ++i) {
    ozz_copy(i, last);
    our_copy(i, last, model);
    crowdprof::run_job(crowdprof::SkinningMatricesJob{&s, model, palette}, "SkinningMatricesJob");
    crowdprof::run_job(crowdprof::SkinningJob{palette, &plan, 0, n, positions, normals}, "SkinningJob");
    for (size_t j = 0; j < ozz_skinning.size(); ++j)
      ozz_skinning[j] = theirs[i].models[j] * ozz_character.inverse_binds[j];
    for (const Part& part : ozz_character.parts) {
      std::vector<float> ozz_positions(3 * part.vertex.size()), ozz_normals(3 * part.vertex.size());
      skin_part_with_ozz(part, ozz_skinning, ozz_positions.data(), ozz_normals.data());
      for (size_t v = 0; v < part.vertex.size(); ++v) {
        const glm::vec3 theirs_at(ozz_positions[3 * v], ozz_positions[3 * v + 1], ozz_positions[3 * v + 2]);
        max_delta = std::max(max_delta, static_cast<double>(glm::distance(theirs_at, positions[part.vertex[v]])));
      }
    }
  }
  const double height = crowdprof::standing_of(c).height;
  std::printf(
      "{\"fade\": \"%s\", \"mask\": \"%s\", \"copies\": %zu, \"frames\": %zu, \"actions\": %zu, \"poses_sampled\": "
      "%zu, "
      "\"joints_blended\": %zu, \"median_ms\": %.4f, \"crowdprof_median_ms\": %.4f, \"ratio_q1\": %.4f, "
      "\"ratio_median\": %.4f, \"ratio_q3\": %.4f, \"max_delta\": %.3g, \"max_delta_of_height\": %.3g, "
      "\"simd\": \"%s\"}\n",
      run.layered ? "layered" : "sampled", mask_joint.c_str(), run.copies, times.ozz_ms.size(), c.actions.size(),
      (run.layered ? 3 : 2) * run.copies, run.copies * s.joint_count(), quantile(times.ozz_ms, 1, 2),
      quantile(times.crowdprof_ms, 1, 2), quantile(times.ratios, 1, 4), quantile(times.ratios, 1, 2),
      quantile(times.ratios, 3, 4), max_delta, height > 0 ? max_delta / height : 0.0,
      crowdprof::active_simd_target().c_str());
}

}  // namespace ozz_bench
