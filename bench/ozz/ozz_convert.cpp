#include "ozz_convert.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>

#include "ozz/animation/offline/animation_builder.h"
#include "ozz/animation/offline/raw_animation.h"
#include "ozz/animation/offline/raw_skeleton.h"
#include "ozz/animation/offline/skeleton_builder.h"
#include "ozz/animation/runtime/sampling_job.h"
#include "ozz/base/maths/soa_transform.h"
#include "ozz/geometry/runtime/skinning_job.h"

namespace ozz_bench {

using crowdprof::Character;
namespace oa = ozz::animation;

void fail(const std::string& why) {
  std::fprintf(stderr, "ozz_driver: %s\n", why.c_str());
  std::exit(1);
}

namespace {

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

OzzCharacter make_ozz_character(const Character& c) {
  const crowdprof::Skeleton& s = c.skeleton;
  for (const glm::mat4& offset : s.parent_offsets)
    if (offset != glm::mat4(1.0f)) fail("joints with non-joint nodes between them are not compared");
  OzzCharacter out;
  oa::offline::RawSkeleton raw_skeleton;
  add_children(c, -1, raw_skeleton.roots);
  out.skeleton = oa::offline::SkeletonBuilder()(raw_skeleton);
  if (!out.skeleton) fail("ozz's SkeletonBuilder refused the skeleton");
  // ozz orders joints its own way: match them by name.
  std::map<std::string, int> ozz_index;
  for (int j = 0; j < out.skeleton->num_joints(); ++j)
    ozz_index[out.skeleton->joint_names()[static_cast<size_t>(j)]] = j;
  out.ozz_of_joint.resize(s.joint_count());
  for (size_t j = 0; j < s.joint_count(); ++j) {
    auto it = ozz_index.find(s.names[j]);
    if (it == ozz_index.end()) fail("joint names are not unique");
    out.ozz_of_joint[j] = it->second;
  }
  out.inverse_binds.resize(static_cast<size_t>(out.skeleton->num_joints()));
  for (size_t j = 0; j < s.joint_count(); ++j)
    out.inverse_binds[static_cast<size_t>(out.ozz_of_joint[j])] = to_ozz(s.inverse_binds[j]);
  out.parts = parts_of(c.mesh, out.ozz_of_joint);
  return out;
}

void round_like_ozz_storage(Character& c) {
  auto half = [](glm::vec3& v) {
    for (int k = 0; k < 3; ++k) v[k] = ozz::math::HalfToFloat(ozz::math::FloatToHalf(v[k]));
  };
  for (glm::vec3& t : c.skeleton.rest_translations) half(t);
  for (glm::vec3& s : c.skeleton.rest_scales) half(s);
  for (crowdprof::Action& action : c.actions)
    for (crowdprof::Channel& channel : action.channels)
      if (channel.path != crowdprof::ChannelPath::Rotation)
        for (float& v : channel.values) v = ozz::math::HalfToFloat(ozz::math::FloatToHalf(v));
}

void take_ozz_rotation_keys(crowdprof::Action& action, const oa::Animation& animation,
                            const OzzCharacter& ozz_character) {
  const oa::Skeleton& skeleton = *ozz_character.skeleton;
  oa::SamplingJob::Context context(skeleton.num_joints());
  std::vector<ozz::math::SoaTransform> locals(static_cast<size_t>(skeleton.num_soa_joints()));
  for (crowdprof::Channel& channel : action.channels) {
    if (channel.path != crowdprof::ChannelPath::Rotation) continue;
    const size_t ozz_joint = static_cast<size_t>(ozz_character.ozz_of_joint[static_cast<size_t>(channel.joint)]);
    for (size_t k = 0; k < channel.key_count(); ++k) {
      oa::SamplingJob sampling;
      sampling.animation = &animation;
      sampling.context = &context;
      sampling.ratio = (channel.times[k] - action.start) / animation.duration();
      sampling.output = ozz::make_span(locals);
      if (!sampling.Run()) fail("SamplingJob");
      const ozz::math::SoaQuaternion& r = locals[ozz_joint / 4].rotation;
      alignas(16) float lanes[4][4];
      ozz::math::StorePtr(r.x, lanes[0]);
      ozz::math::StorePtr(r.y, lanes[1]);
      ozz::math::StorePtr(r.z, lanes[2]);
      ozz::math::StorePtr(r.w, lanes[3]);
      for (size_t c = 0; c < 4; ++c) channel.values[4 * k + c] = lanes[c][ozz_joint % 4];
    }
  }
}

ozz::unique_ptr<oa::Animation> make_ozz_animation(const Character& c, const crowdprof::Action& action,
                                                  const OzzCharacter& ozz_character) {
  ozz::unique_ptr<oa::Animation> animation = oa::offline::AnimationBuilder()(
      raw_animation(c, action, ozz_character.ozz_of_joint, ozz_character.skeleton->num_joints()));
  if (!animation) fail("ozz's AnimationBuilder refused the action " + action.name);
  return animation;
}

void skin_part_with_ozz(const Part& part, const std::vector<ozz::math::Float4x4>& skinning, float* positions,
                        float* normals) {
  const size_t floats = 3 * part.vertex.size();
  ozz::geometry::SkinningJob skin;
  skin.vertex_count = static_cast<int>(part.vertex.size());
  skin.influences_count = part.influences;
  skin.joint_matrices = ozz::make_span(skinning);
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
  skin.out_positions = {positions, floats};
  skin.out_positions_stride = 3 * sizeof(float);
  skin.out_normals = {normals, floats};
  skin.out_normals_stride = 3 * sizeof(float);
  if (!skin.Run()) fail("SkinningJob");
}

}  // namespace ozz_bench
