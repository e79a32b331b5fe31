#include "asset/character.h"

#include <algorithm>

namespace crowdprof {

int Skeleton::depth() const {
  std::vector<int> level(parents.size(), 0);
  int deepest = 0;
  for (size_t j = 0; j < parents.size(); ++j) {
    level[j] = parents[j] < 0 ? 1 : level[static_cast<size_t>(parents[j])] + 1;
    deepest = std::max(deepest, level[j]);
  }
  return deepest;
}

const char* to_string(Interpolation interpolation) {
  switch (interpolation) {
    case Interpolation::Step:
      return "STEP";
    case Interpolation::Linear:
      return "LINEAR";
    case Interpolation::CubicSpline:
      return "CUBICSPLINE";
  }
  return "?";
}

const char* to_string(ChannelPath path) {
  switch (path) {
    case ChannelPath::Translation:
      return "translation";
    case ChannelPath::Rotation:
      return "rotation";
    case ChannelPath::Scale:
      return "scale";
  }
  return "?";
}

void prepare_slerp(Channel* channel) {
  channel->slerp.clear();
  const size_t keys = channel->times.size();
  if (channel->path != ChannelPath::Rotation || channel->interpolation != Interpolation::Linear || keys < 2 ||
      channel->values.size() != 4 * keys)
    return;
  channel->slerp.resize(keys - 1);
  const float* v = channel->values.data();
  for (size_t k = 0; k + 1 < keys; ++k)
    channel->slerp[k] = slerp_segment(quat_from_xyzw(v + 4 * k), quat_from_xyzw(v + 4 * k + 4));
}

template <typename T>
static size_t bytes_of(const std::vector<T>& v) {
  return v.size() * sizeof(T);
}

size_t Character::shared_bytes() const {
  const Skeleton& s = skeleton;
  size_t bytes = bytes_of(s.parents) + bytes_of(s.rest_translations) + bytes_of(s.rest_rotations) +
                 bytes_of(s.rest_scales) + bytes_of(s.inverse_binds) + bytes_of(s.parent_offsets);
  bytes += bytes_of(mesh.positions) + bytes_of(mesh.normals) + bytes_of(mesh.joints) + bytes_of(mesh.weights) +
           bytes_of(mesh.indices) + bytes_of(mesh.primitives);
  for (const SkinnedMesh& lod : file_lods)
    bytes += bytes_of(lod.positions) + bytes_of(lod.normals) + bytes_of(lod.joints) + bytes_of(lod.weights) +
             bytes_of(lod.indices) + bytes_of(lod.primitives);
  for (const Action& action : actions)
    for (const Channel& channel : action.channels) bytes += bytes_of(channel.times) + bytes_of(channel.values);
  return bytes;
}

}  // namespace crowdprof
