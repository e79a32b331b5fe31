// crowdprof's CPU work done by ozz-animation, for bench/ozz/compare_ozz.sh
// (issue 31): N copies of a character, every copy posed (ozz SamplingJob,
// LocalToModelJob, model x inverse bind) and skinned (ozz SkinningJob, one
// job per influence count, positions and normals) every frame, on one thread,
// as `crowdprof bench FILE -n N --mode threaded --threads 1 --culling off
// --actions shared` does. The character is crowdprof's (its loader), handed
// to ozz's offline builders, so both run on the same skeleton, keys and mesh.
// Prints one JSON line: the median frame, the work counted as crowdprof
// counts it, and how far ozz's skinned vertices are from crowdprof's at the
// last frame (ozz quantises keys: not bit for bit).
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
#include <map>
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

#include "ozz/animation/offline/animation_builder.h"
#include "ozz/animation/offline/raw_animation.h"
#include "ozz/animation/offline/raw_skeleton.h"
#include "ozz/animation/offline/skeleton_builder.h"
#include "ozz/animation/runtime/animation.h"
#include "ozz/animation/runtime/local_to_model_job.h"
#include "ozz/animation/runtime/sampling_job.h"
#include "ozz/animation/runtime/skeleton.h"
#include "ozz/base/maths/simd_math.h"
#include "ozz/base/maths/soa_transform.h"
#include "ozz/geometry/runtime/skinning_job.h"

namespace {

using crowdprof::Character;

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
namespace oa = ozz::animation;

[[noreturn]] void fail(const std::string& why) {
  std::fprintf(stderr, "ozz_driver: %s\n", why.c_str());
  std::exit(1);
}

// The skeleton as ozz's raw hierarchy (joint j's children in joint order).
void add_children(const Character& c, int parent, oa::offline::RawSkeleton::Joint::Children& into) {
  const crowdprof::Skeleton& s = c.skeleton;
  for (size_t j = 0; j < s.joint_count(); ++j) {
    if (s.parents[j] != parent) continue;
    oa::offline::RawSkeleton::Joint joint;
    joint.name = s.names[j].c_str();
    const glm::vec3 t = s.rest_translations[j], sc = s.rest_scales[j];
    const glm::quat r = s.rest_rotations[j];
    joint.transform.translation = ozz::math::Float3(t.x, t.y, t.z);
    joint.transform.rotation = ozz::math::Quaternion(r.x, r.y, r.z, r.w);
    joint.transform.scale = ozz::math::Float3(sc.x, sc.y, sc.z);
    add_children(c, static_cast<int>(j), joint.children);
    into.push_back(std::move(joint));
  }
}

// One action as ozz's raw animation, keys shifted to start at 0 (LINEAR only).
oa::offline::RawAnimation raw_animation(const Character& c, const crowdprof::Action& action,
                                        const std::vector<int>& ozz_of_joint, int ozz_joints) {
  oa::offline::RawAnimation raw;
  raw.duration = std::max(action.duration(), 1e-3f);
  raw.tracks.resize(static_cast<size_t>(ozz_joints));
  const crowdprof::Skeleton& s = c.skeleton;
  // Joints no channel drives hold their rest pose, as crowdprof's do.
  for (size_t j = 0; j < s.joint_count(); ++j) {
    auto& track = raw.tracks[static_cast<size_t>(ozz_of_joint[j])];
    const glm::vec3 t = s.rest_translations[j], sc = s.rest_scales[j];
    const glm::quat r = s.rest_rotations[j];
    track.translations.push_back({0.0f, ozz::math::Float3(t.x, t.y, t.z)});
    track.rotations.push_back({0.0f, ozz::math::Quaternion(r.x, r.y, r.z, r.w)});
    track.scales.push_back({0.0f, ozz::math::Float3(sc.x, sc.y, sc.z)});
  }
  std::vector<bool> driven(3 * s.joint_count(), false);
  for (const crowdprof::Channel& ch : action.channels) {
    if (ch.interpolation != crowdprof::Interpolation::Linear) fail("only LINEAR channels are compared");
    auto& track = raw.tracks[static_cast<size_t>(ozz_of_joint[static_cast<size_t>(ch.joint)])];
    const size_t slot = 3 * static_cast<size_t>(ch.joint) + static_cast<size_t>(ch.path);
    if (!driven[slot]) {  // the rest key gives way to the channel's keys
      driven[slot] = true;
      if (ch.path == crowdprof::ChannelPath::Translation) track.translations.clear();
      if (ch.path == crowdprof::ChannelPath::Rotation) track.rotations.clear();
      if (ch.path == crowdprof::ChannelPath::Scale) track.scales.clear();
    }
    for (size_t k = 0; k < ch.key_count(); ++k) {
      const float time = ch.times[k] - action.start;
      const float* v = &ch.values[k * static_cast<size_t>(ch.components())];
      if (ch.path == crowdprof::ChannelPath::Translation)
        track.translations.push_back({time, ozz::math::Float3(v[0], v[1], v[2])});
      else if (ch.path == crowdprof::ChannelPath::Rotation)
        track.rotations.push_back({time, ozz::math::Quaternion(v[0], v[1], v[2], v[3])});
      else
        track.scales.push_back({time, ozz::math::Float3(v[0], v[1], v[2])});
    }
  }
  return raw;
}

ozz::math::Float4x4 to_ozz(const glm::mat4& m) {
  ozz::math::Float4x4 out;
  for (int c = 0; c < 4; ++c) out.cols[c] = ozz::math::simd_float4::Load(m[c][0], m[c][1], m[c][2], m[c][3]);
  return out;
}

// The mesh cut into parts of equal influence count (ozz's layout): per part,
// its vertices' positions, normals, joint indices (ozz's joint order) and
// all weights but the last.
struct Part {
  int influences = 1;
  std::vector<uint32_t> vertex;  // the crowdprof vertex each one is
  std::vector<float> positions, normals, weights;
  std::vector<uint16_t> joints;
};

std::vector<Part> parts_of(const crowdprof::SkinnedMesh& mesh, const std::vector<int>& ozz_of_joint) {
  std::vector<Part> parts(4);
  for (int k = 0; k < 4; ++k) parts[static_cast<size_t>(k)].influences = k + 1;
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const glm::vec4 w = mesh.weights[v];
    const int n = std::max(1, (w.x != 0) + (w.y != 0) + (w.z != 0) + (w.w != 0));
    Part& p = parts[static_cast<size_t>(n - 1)];
    p.vertex.push_back(static_cast<uint32_t>(v));
    for (int a = 0; a < 3; ++a) {
      p.positions.push_back(mesh.positions[v][a]);
      p.normals.push_back(mesh.normals[v][a]);
    }
    for (int i = 0; i < n; ++i) p.joints.push_back(static_cast<uint16_t>(ozz_of_joint[mesh.joints[v][i]]));
    for (int i = 0; i + 1 < n; ++i) p.weights.push_back(w[i]);
  }
  std::erase_if(parts, [](const Part& p) { return p.vertex.empty(); });
  return parts;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: ozz_driver CHARACTER.glb [COPIES [FRAMES [WARMUP [RENORMALISE [INTERLEAVE]]]]]\n");
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
  if (copies == 0 || frames == 0) fail("COPIES and FRAMES must be at least 1");
  if (const char* simd = std::getenv(crowdprof::kSimdEnvironmentVariable); simd && *simd)
    if (std::string why = crowdprof::force_simd_target(simd); !why.empty()) fail(why);
  // Vertices in the order crowdprof's bench skins them; both sides get this mesh.
  Character c = crowdprof::load_character(argv[1]);
  crowdprof::order_vertices_for_skinning(c);
  if (c.actions.empty()) fail("the character has no action");
  const crowdprof::Skeleton& s = c.skeleton;
  for (const glm::mat4& offset : s.parent_offsets)
    if (offset != glm::mat4(1.0f)) fail("joints with non-joint nodes between them are not compared");

  oa::offline::RawSkeleton raw_skeleton;
  add_children(c, -1, raw_skeleton.roots);
  ozz::unique_ptr<oa::Skeleton> skeleton = oa::offline::SkeletonBuilder()(raw_skeleton);
  if (!skeleton) fail("ozz's SkeletonBuilder refused the skeleton");
  // ozz orders joints its own way: match them by name.
  std::map<std::string, int> ozz_index;
  for (int j = 0; j < skeleton->num_joints(); ++j) ozz_index[skeleton->joint_names()[static_cast<size_t>(j)]] = j;
  std::vector<int> ozz_of_joint(s.joint_count());
  for (size_t j = 0; j < s.joint_count(); ++j) {
    auto it = ozz_index.find(s.names[j]);
    if (it == ozz_index.end()) fail("joint names are not unique");
    ozz_of_joint[j] = it->second;
  }
  const crowdprof::Action& action = c.actions.front();  // --actions shared plays the first
  ozz::unique_ptr<oa::Animation> animation =
      oa::offline::AnimationBuilder()(raw_animation(c, action, ozz_of_joint, skeleton->num_joints()));
  if (!animation) fail("ozz's AnimationBuilder refused the action");

  const int joints = skeleton->num_joints();
  std::vector<ozz::math::Float4x4> inverse_binds(static_cast<size_t>(joints));
  for (size_t j = 0; j < s.joint_count(); ++j)
    inverse_binds[static_cast<size_t>(ozz_of_joint[j])] = to_ozz(s.inverse_binds[j]);
  const std::vector<Part> parts = parts_of(c.mesh, ozz_of_joint);

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
  auto ms_since = [](std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
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
      ltm.skeleton = skeleton.get();
      ltm.input = ozz::make_span(cs.locals);
      ltm.output = ozz::make_span(cs.models);
      if (!ltm.Run()) fail("LocalToModelJob");
      for (size_t j = 0; j < cs.models.size(); ++j) cs.skinning[j] = cs.models[j] * inverse_binds[j];
      for (size_t p = 0; p < parts.size(); ++p) {
        const Part& part = parts[p];
        ozz::geometry::SkinningJob skin;
        skin.vertex_count = static_cast<int>(part.vertex.size());
        skin.influences_count = part.influences;
        skin.joint_matrices = ozz::make_span(cs.skinning);
        skin.joint_indices = ozz::make_span(part.joints);
        skin.joint_indices_stride = sizeof(uint16_t) * static_cast<size_t>(part.influences);
        if (part.influences > 1) {
          skin.joint_weights = ozz::make_span(part.weights);
          skin.joint_weights_stride = sizeof(float) * static_cast<size_t>(part.influences - 1);
        }
        skin.in_positions = ozz::make_span(part.positions);
        skin.in_positions_stride = 3 * sizeof(float);
        skin.in_normals = ozz::make_span(part.normals);
        skin.in_normals_stride = 3 * sizeof(float);
        skin.out_positions = ozz::make_span(cs.positions[p]);
        skin.out_positions_stride = 3 * sizeof(float);
        skin.out_normals = ozz::make_span(cs.normals[p]);
        skin.out_normals_stride = 3 * sizeof(float);
        if (!skin.Run()) fail("SkinningJob");
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
      if (f >= warmup) frame_ms.push_back(ms_since(start));
    }
  } else {
    // Blocks of 10 frames, ozz's then crowdprof's over the same frame times,
    // which goes first alternating: one block's ratio is the two sums'.
    // Alternating every frame cost crowdprof's side about 1.2x (ratio 0.49
    // against 0.36-0.41 in blocks of 10 or 40): the switch, not the work.
    constexpr size_t kBlock = 10;
    for (size_t f = 0; f < warmup; ++f) {
      ozz_frame(time_of(f));
      crowdprof_frame(action.start + static_cast<float>(time_of(f)));
    }
    for (size_t first = warmup, block = 0; first < warmup + frames; first += kBlock, ++block) {
      const size_t end = std::min(first + kBlock, warmup + frames);
      double sums[2] = {0, 0};  // ozz, crowdprof
      for (int side : {static_cast<int>(block % 2), static_cast<int>(1 - block % 2)})
        for (size_t f = first; f < end; ++f) {
          const auto start = std::chrono::steady_clock::now();
          if (side == 0)
            ozz_frame(time_of(f));
          else
            crowdprof_frame(action.start + static_cast<float>(time_of(f)));
          const double ms = ms_since(start);
          sums[side] += ms;
          (side == 0 ? frame_ms : crowdprof_ms).push_back(ms);
        }
      if (sums[0] > 0) ratios.push_back(sums[1] / sums[0]);
    }
  }
  const float last_time = action.start + static_cast<float>(time_of(warmup + frames - 1));
  // Interpolated between order statistics, as crowdprof's medians are.
  auto quantile = [](std::vector<double> v, size_t num, size_t den) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const double at = static_cast<double>((v.size() - 1) * num) / static_cast<double>(den);
    const size_t below = static_cast<size_t>(at);
    const double above = below + 1 < v.size() ? v[below + 1] : v[below];
    return v[below] + (above - v[below]) * (at - static_cast<double>(below));
  };
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
