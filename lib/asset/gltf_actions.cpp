// Animations as crowdprof reads them: each glTF animation's channels on the
// nodes that matter, with every key checked (finite, increasing, non-negative
// times; outputs of the right size; unit rotations, counted when repaired).
#include <algorithm>
#include <cmath>
#include <map>

#include <tiny_gltf.h>

#include "base/errors.h"
#include "asset/gltf_accessor.h"
#include "asset/gltf_container.h"
#include "asset/gltf_convert.h"

namespace crowdprof {

namespace {

Interpolation parse_interpolation(const std::string& text, const std::string& where, const std::string& file) {
  if (text.empty() || text == "LINEAR") return Interpolation::Linear;
  if (text == "STEP") return Interpolation::Step;
  if (text == "CUBICSPLINE") return Interpolation::CubicSpline;
  throw InputError(file, where + ": unknown interpolation \"" + printable(text, 40) + "\"");
}

}  // namespace

std::vector<Action> convert_actions(const tinygltf::Model& model, const std::vector<int>& node_to_joint,
                                    const std::string& file, Fixups* fixups) {
  AccessorReader reader{model, file};
  std::vector<Action> actions;
  size_t key_floats = 0;
  for (size_t a = 0; a < model.animations.size(); ++a) {
    const tinygltf::Animation& anim = model.animations[a];
    Action action;
    action.name = anim.name.empty() ? "action" + str(a) : anim.name;
    action.start = INFINITY;
    action.end = -INFINITY;
    std::map<std::pair<int, std::string>, size_t> targets;  // (node, path) -> channel
    for (size_t c = 0; c < anim.channels.size(); ++c) {
      const tinygltf::AnimationChannel& ch = anim.channels[c];
      std::string where = "animation " + str(a) + " channel " + str(c);
      // glTF allows one channel per target; a second would silently win or lose.
      if (ch.target_node >= 0) {
        auto [it, fresh] = targets.emplace(std::make_pair(ch.target_node, ch.target_path), c);
        if (!fresh)
          throw InputError(file, "animation " + str(a) + ": channels " + str(it->second) + " and " + str(c) +
                                     " both target node " + std::to_string(ch.target_node) + " " +
                                     printable(ch.target_path, 40));
      }
      if (ch.sampler < 0 || static_cast<size_t>(ch.sampler) >= anim.samplers.size())
        throw InputError(file, where + " names sampler " + std::to_string(ch.sampler) + ", which does not exist");
      if (ch.target_node >= 0 && static_cast<size_t>(ch.target_node) >= model.nodes.size())
        throw InputError(file, where + " targets node " + std::to_string(ch.target_node) + ", which does not exist");
      Channel channel;
      if (ch.target_path == "translation")
        channel.path = ChannelPath::Translation;
      else if (ch.target_path == "rotation")
        channel.path = ChannelPath::Rotation;
      else if (ch.target_path == "scale")
        channel.path = ChannelPath::Scale;
      else if (ch.target_path != "weights")
        throw InputError(file, where + ": unknown target path \"" + printable(ch.target_path, 40) + "\"");
      int joint = ch.target_node < 0 ? -1 : node_to_joint[static_cast<size_t>(ch.target_node)];
      if (ch.target_path == "weights" || joint < 0) {
        if (fixups) ++fixups->channels_dropped;
        continue;
      }
      channel.joint = joint;
      const tinygltf::AnimationSampler& sampler = anim.samplers[static_cast<size_t>(ch.sampler)];
      std::string sampler_where = "animation " + str(a) + " sampler " + std::to_string(ch.sampler);
      channel.interpolation = parse_interpolation(sampler.interpolation, sampler_where, file);
      channel.times = reader.floats(sampler.input, 1, sampler_where + " input");
      if (channel.times.front() < 0.0f)
        throw InputError(file, sampler_where + ": key time " + std::to_string(channel.times.front()) + " is negative");
      for (size_t k = 1; k < channel.times.size(); ++k)
        if (!(channel.times[k] > channel.times[k - 1]))
          throw InputError(file, sampler_where + ": key times do not increase at key " + str(k));
      size_t per_key = channel.interpolation == Interpolation::CubicSpline ? 3 : 1;
      int components = channel.components();
      channel.values = reader.floats(sampler.output, components, sampler_where + " output");
      size_t expected = channel.times.size() * per_key * static_cast<size_t>(components);
      if (channel.values.size() != expected)
        throw InputError(file, sampler_where + ": output has " +
                                   str(channel.values.size() / static_cast<size_t>(components)) + " values for " +
                                   str(channel.times.size()) + " keys (needs " +
                                   str(expected / static_cast<size_t>(components)) + ")");
      // Channels may share one huge accessor: bound what all of them read together.
      key_floats += channel.times.size() + channel.values.size();
      if (key_floats > kMaxActionFloats)
        throw InputError(file, sampler_where + ": the animations hold more than " + str(kMaxActionFloats) +
                                   " numbers; refused as absurd");
      if (channel.path == ChannelPath::Rotation) {
        // Only the value of each key is a rotation; cubic tangents are not unit.
        for (size_t k = 0; k < channel.times.size(); ++k) {
          float* q = &channel.values[(k * per_key + (per_key == 3 ? 1 : 0)) * 4];
          float length = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
          if (length < 1e-6f) throw InputError(file, sampler_where + ": key " + str(k) + " is a zero rotation");
          if (std::abs(length - 1.0f) > 1e-3f) {
            for (int i = 0; i < 4; ++i) q[i] /= length;
            if (fixups) ++fixups->rotations_normalised;
          }
        }
      }
      prepare_slerp(&channel);
      action.start = std::min(action.start, channel.times.front());
      action.end = std::max(action.end, channel.times.back());
      action.channels.push_back(std::move(channel));
    }
    if (action.channels.empty()) {
      if (fixups) ++fixups->actions_dropped;
      continue;
    }
    actions.push_back(std::move(action));
  }
  return actions;
}

std::vector<Action> convert_node_actions(const tinygltf::Model& model, const std::string& file) {
  std::vector<int> identity(model.nodes.size());
  for (size_t i = 0; i < identity.size(); ++i) identity[i] = static_cast<int>(i);
  return convert_actions(model, identity, file, nullptr);
}

}  // namespace crowdprof
