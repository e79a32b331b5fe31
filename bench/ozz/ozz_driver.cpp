// crowdprof's CPU work done by ozz-animation, for bench/ozz/compare_ozz.sh
// (issue 31): N copies of a character, every copy posed (ozz SamplingJob,
// LocalToModelJob, model x inverse bind) and skinned (ozz SkinningJob, one
// job per influence count, positions and normals) every frame, on one thread,
// as `crowdprof bench FILE -n N --mode threaded --threads 1 --culling off
// --actions shared` does. The character is crowdprof's (its loader), handed
// to ozz's offline builders, so both run on the same skeleton, keys and mesh.
// Prints one JSON line: the median frame, the work counted as crowdprof
// counts it, and how far ozz's skinned vertices are from crowdprof's at the
// last frame (ozz quantises keys: not bit for bit). With FADE sampled it
// compares crossfades instead (sampling, blending, local-to-model: ozz_fades.h).
//
// crowdprof's kernels renormalise every blended normal (a blend of rotations
// shortens it; only batches of 16 single-influence vertices on rigid joints
// keep theirs); ozz's SkinningJob does not. With RENORMALISE 1 the driver does it after each
// job, as an ozz user would, with the same guarded, correctly rounded square
// root and divide, 4 normals at a time (ozz's SIMD width), so that both do the
// same work.
//
// This file is the project's own; it links ozz-animation built from a source
// tree the script is given (none of ozz's code is in the project).
#include <immintrin.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <string>
#include <vector>

#include "animation/binding.h"
#include "animation/local_pose.h"
#include "animation/pose.h"
#include "animation/run_job.h"
#include "animation/sampling.h"
#include "asset/gltf_loader.h"
#include "asset/standing.h"
#include "asset/vertex_order.h"
#include "skinning/output_buffer.h"
#include "skinning/output_stores.h"
#include "skinning/packed_vertex.h"
#include "skinning/simd_target.h"
#include "skinning/skinning.h"
#include "skinning/skinning_plan.h"

#include "ozz_convert.h"
#include "ozz_fades.h"
#include "ozz_timing.h"

#include "ozz/animation/runtime/animation.h"
#include "ozz/animation/runtime/local_to_model_job.h"
#include "ozz/animation/runtime/sampling_job.h"
#include "ozz/animation/runtime/skeleton.h"
#include "ozz/base/maths/simd_math.h"
#include "ozz/base/maths/soa_transform.h"

namespace {

using crowdprof::Character;
using ozz_bench::fail;
using ozz_bench::Part;
namespace oa = ozz::animation;

// Renormalises `count` normals (x y z each) in place, as crowdprof's kernels
// do (a zero length stays zero): 4 at a time in SSE, the last ones one by one.
// Not inlined: callgrind counts it by name (docs/performance.md).
__attribute__((noinline)) void renormalise_normals(float* n, size_t count) {
  const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f);
  size_t i = 0;
  for (; i + 5 <= count; i += 4, n += 12) {
    // Four overlapping loads, each a normal and the next one's x; rows x, y, z
    // and the next x's once transposed, and back again. Each store rewrites
    // the next normal's x as loaded, and the next store gives it its value; the
    // last writes three floats only, so that the next group's first load does
    // not wait on a store it half overlaps.
    __m128 r0 = _mm_loadu_ps(n), r1 = _mm_loadu_ps(n + 3), r2 = _mm_loadu_ps(n + 6), r3 = _mm_loadu_ps(n + 9);
    _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
    const __m128 length2 = _mm_add_ps(_mm_add_ps(_mm_mul_ps(r0, r0), _mm_mul_ps(r1, r1)), _mm_mul_ps(r2, r2));
    const __m128 inverse = _mm_and_ps(_mm_cmpgt_ps(length2, zero), _mm_div_ps(one, _mm_sqrt_ps(length2)));
    r0 = _mm_mul_ps(r0, inverse);
    r1 = _mm_mul_ps(r1, inverse);
    r2 = _mm_mul_ps(r2, inverse);
    _MM_TRANSPOSE4_PS(r0, r1, r2, r3);
    _mm_storeu_ps(n, r0);
    _mm_storeu_ps(n + 3, r1);
    _mm_storeu_ps(n + 6, r2);
    _mm_storel_pi(reinterpret_cast<__m64*>(n + 9), r3);
    _mm_store_ss(n + 11, _mm_movehl_ps(r3, r3));
  }
  for (; i < count; ++i, n += 3) {
    const float length2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    const float inverse = length2 > 0.0f ? 1.0f / std::sqrt(length2) : 0.0f;
    n[0] *= inverse;
    n[1] *= inverse;
    n[2] *= inverse;
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: ozz_driver CHARACTER.glb [COPIES [FRAMES [WARMUP [RENORMALISE [INTERLEAVE [FADE]]]]]]\n");
    return 2;
  }
  const size_t copies = argc > 2 ? std::stoul(argv[2]) : 160;
  const size_t frames = argc > 3 ? std::stoul(argv[3]) : 120;
  const size_t warmup = argc > 4 ? std::stoul(argv[4]) : 10;
  const bool renormalise = argc > 5 && std::stoul(argv[5]) != 0;
  // INTERLEAVE 1: crowdprof's jobs do the same frames too, in this process, in
  // blocks alternating with ozz's, so that a host that changes speed between
  // processes changes both alike (docs/performance.md).
  const bool interleave = argc > 6 && std::stoul(argv[6]) != 0;
  // FADE sampled: every copy crossfading, sampling, blending and local-to-model
  // only, both sides in one process (ozz_fades.h); layered: the same with a
  // masked third action over half the body; none (the default): the
  // frame above.
  const std::string fade = argc > 7 ? argv[7] : "none";
  if (fade != "none" && fade != "sampled" && fade != "layered") fail("FADE must be none, sampled or layered");
  if (copies == 0 || frames == 0) fail("COPIES and FRAMES must be at least 1");
  if (const char* simd = std::getenv(crowdprof::kSimdEnvironmentVariable); simd && *simd)
    if (std::string why = crowdprof::force_simd_target(simd); !why.empty()) fail(why);
  // Vertices in the order crowdprof's bench skins them; both sides get this mesh.
  Character c = crowdprof::load_character(argv[1]);
  crowdprof::order_vertices_for_skinning(c);
  if (c.actions.empty()) fail("the character has no action");
  const crowdprof::Skeleton& s = c.skeleton;
  // The fades' vertex check compares the jobs on the keys ozz holds.
  if (fade != "none") ozz_bench::round_like_ozz_storage(c);
  const ozz_bench::OzzCharacter ozz_character = ozz_bench::make_ozz_character(c);
  if (fade != "none") {
    ozz_bench::run_sampled_fades(c, ozz_character, {copies, frames, warmup, fade == "layered"});
    return 0;
  }
  const oa::Skeleton* skeleton = ozz_character.skeleton.get();
  const std::vector<ozz::math::Float4x4>& inverse_binds = ozz_character.inverse_binds;
  const std::vector<Part>& parts = ozz_character.parts;
  const crowdprof::Action& action = c.actions.front();  // --actions shared plays the first
  const ozz::unique_ptr<oa::Animation> animation = ozz_bench::make_ozz_animation(c, action, ozz_character);
  const int joints = skeleton->num_joints();

  // Per copy, as crowdprof keeps it: a sampling context, local and model
  // transforms, skinning matrices and its own output.
  struct CopyState {
    oa::SamplingJob::Context context;
    std::vector<ozz::math::SoaTransform> locals;
    std::vector<ozz::math::Float4x4> models, skinning;
    std::vector<std::vector<float>> positions, normals;  // per part
  };
  std::vector<CopyState> state(copies);
  for (CopyState& cs : state) {
    cs.context.Resize(joints);
    cs.locals.resize(static_cast<size_t>(skeleton->num_soa_joints()));
    cs.models.resize(static_cast<size_t>(joints));
    cs.skinning.resize(static_cast<size_t>(joints));
    for (const Part& p : parts) {
      cs.positions.emplace_back(p.positions.size());
      cs.normals.emplace_back(p.normals.size());
    }
  }

  // crowdprof's side of an interleaved run: its jobs per copy with culling
  // off (the action's bundled bindings, one thread), with the frame's memory:
  // one model-space scratch for every copy (the frame keeps one a thread), all
  // palettes in one array, every copy's positions in one allocation and its
  // normals in another, each copy on a cache line (huge pages where Linux gives
  // them, output_buffer.h).
  struct CrowdprofCopy {
    crowdprof::LocalPose pose;
    crowdprof::SamplingCursor cursor;
  };
  const crowdprof::ActionBindings bindings = crowdprof::bind_action(s, action);
  crowdprof::SkinningPlan plan;
  crowdprof::build_skinning_plan(c.mesh, s.joint_count(), &plan);
  const size_t n = c.mesh.vertex_count();
  std::vector<CrowdprofCopy> ours(interleave ? copies : 0);
  for (CrowdprofCopy& cc : ours) {
    crowdprof::reset_to_rest(s, &cc.pose);
    crowdprof::reset_cursor(action, &cc.cursor);
  }
  const size_t joint_count = s.joint_count();
  std::vector<glm::mat4> our_model(joint_count);
  std::vector<crowdprof::SkinMatrix> our_palettes(ours.size() * joint_count);
  size_t stride = n;  // vec3s from one copy's output to the next's
  while ((stride * sizeof(glm::vec3)) % 64) ++stride;
  using Output = std::vector<glm::vec3, crowdprof::CacheLineAllocator<glm::vec3>>;
  Output our_positions(ours.size() * stride), our_normals(ours.size() * stride);
  const bool streaming = crowdprof::stream_skinned_output(ours.size() * n * crowdprof::kFloatVertexBytes);
  // One copy's frame by crowdprof's jobs: sample, pose, palette, skin.
  auto skin_copy = [&](float time, CrowdprofCopy& cc, std::span<glm::mat4> model,
                       std::span<crowdprof::SkinMatrix> palette, std::span<glm::vec3> positions,
                       std::span<glm::vec3> normals, bool streaming_stores) {
    crowdprof::run_job(crowdprof::SamplingJob{&action, time, bindings.targets, &cc.cursor, &cc.pose}, "SamplingJob");
    crowdprof::run_job(crowdprof::LocalToModelJob{&s, &cc.pose, model}, "LocalToModelJob");
    crowdprof::run_job(crowdprof::SkinningMatricesJob{&s, model, palette}, "SkinningMatricesJob");
    crowdprof::SkinningJob skin{palette, &plan, 0, n, positions, normals};
    skin.streaming_stores = streaming_stores;
    crowdprof::run_job(skin, "SkinningJob");
  };
  auto crowdprof_frame = [&](float time) {
    for (size_t i = 0; i < ours.size(); ++i)
      skin_copy(time, ours[i], our_model, std::span(our_palettes.data() + i * joint_count, joint_count),
                std::span(our_positions.data() + i * stride, n), std::span(our_normals.data() + i * stride, n),
                streaming);
  };
  const double fps = 60.0, duration = action.duration();
  auto ozz_frame = [&](double t) {
    for (CopyState& cs : state) {
      oa::SamplingJob sampling;
      sampling.animation = animation.get();
      sampling.context = &cs.context;
      sampling.ratio = duration > 0 ? static_cast<float>(t / duration) : 0.0f;
      sampling.output = ozz::make_span(cs.locals);
      if (!sampling.Run()) fail("SamplingJob");
      oa::LocalToModelJob ltm;
      ltm.skeleton = skeleton;
      ltm.input = ozz::make_span(cs.locals);
      ltm.output = ozz::make_span(cs.models);
      if (!ltm.Run()) fail("LocalToModelJob");
      for (size_t j = 0; j < cs.models.size(); ++j) cs.skinning[j] = cs.models[j] * inverse_binds[j];
      for (size_t p = 0; p < parts.size(); ++p) {
        const Part& part = parts[p];
        ozz_bench::skin_part_with_ozz(part, cs.skinning, cs.positions[p].data(), cs.normals[p].data());
        if (renormalise && part.influences > 1) renormalise_normals(cs.normals[p].data(), part.vertex.size());
      }
    }
  };
  // Frame f's time in the action, as crowdprof's --actions shared plays it.
  auto time_of = [&](size_t f) { return duration > 0 ? std::fmod(static_cast<double>(f) / fps, duration) : 0.0; };
  std::vector<double> frame_ms, crowdprof_ms, ratios;
  if (!interleave) {
    for (size_t f = 0; f < warmup + frames; ++f) {
      const auto start = std::chrono::steady_clock::now();
      ozz_frame(time_of(f));
      if (f >= warmup) frame_ms.push_back(ozz_bench::ms_since(start));
    }
  } else {
    ozz_bench::InterleavedTimes times = ozz_bench::time_interleaved(
        warmup, frames, [&](size_t f) { ozz_frame(time_of(f)); },
        [&](size_t f) { crowdprof_frame(action.start + static_cast<float>(time_of(f))); });
    frame_ms = std::move(times.ozz_ms);
    crowdprof_ms = std::move(times.crowdprof_ms);
    ratios = std::move(times.ratios);
  }
  const float last_time = action.start + static_cast<float>(time_of(warmup + frames - 1));
  using ozz_bench::quantile;
  const double median = quantile(frame_ms, 1, 2);

  // The same copy by crowdprof's jobs at the last frame's time: how far ozz's vertices are.
  CrowdprofCopy reference;
  crowdprof::reset_to_rest(s, &reference.pose);
  crowdprof::reset_cursor(action, &reference.cursor);
  std::vector<glm::mat4> model(joint_count);
  std::vector<crowdprof::SkinMatrix> palette(joint_count);
  std::vector<glm::vec3> positions(n), normals(n);
  skin_copy(last_time, reference, model, palette, positions, normals, false);
  double max_delta = 0, max_normal_delta = 0;
  for (size_t p = 0; p < parts.size(); ++p)
    for (size_t i = 0; i < parts[p].vertex.size(); ++i) {
      const std::vector<float>& op = state.back().positions[p];
      const std::vector<float>& on = state.back().normals[p];
      const glm::vec3 ozz_position(op[3 * i], op[3 * i + 1], op[3 * i + 2]);
      const glm::vec3 ozz_normal(on[3 * i], on[3 * i + 1], on[3 * i + 2]);
      max_delta = std::max(max_delta, static_cast<double>(glm::distance(ozz_position, positions[parts[p].vertex[i]])));
      max_normal_delta =
          std::max(max_normal_delta, static_cast<double>(glm::distance(ozz_normal, normals[parts[p].vertex[i]])));
    }
  const double height = crowdprof::standing_of(c).height;
  std::printf(
      "{\"median_ms\": %.4f, \"frames\": %zu, \"copies\": %zu, \"vertices_skinned\": %zu, \"poses_updated\": %zu, "
      "\"max_delta\": %.3g, \"max_delta_of_height\": %.3g, \"renormalised\": %s, \"max_normal_delta\": %.3g, "
      "\"simd\": \"%s\", \"interleaved\": %s, \"crowdprof_median_ms\": %.4f, \"ratio_q1\": %.4f, "
      "\"ratio_median\": %.4f, \"ratio_q3\": %.4f}\n",
      median, frame_ms.size(), copies, copies * n, copies, max_delta, height > 0 ? max_delta / height : 0.0,
      renormalise ? "true" : "false", max_normal_delta, crowdprof::active_simd_target().c_str(),
      interleave ? "true" : "false", quantile(crowdprof_ms, 1, 2), quantile(ratios, 1, 4), quantile(ratios, 1, 2),
      quantile(ratios, 3, 4));
  return 0;
}
