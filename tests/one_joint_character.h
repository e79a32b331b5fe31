// A character small enough to work out by hand: one root joint at the origin,
// every vertex bound rigidly to it (weight 1), and one action of one channel
// from 0 to 1 s. What a vertex does is what the joint does.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "asset/character.h"

namespace crowdprof::test {

inline Character one_joint_character(const std::string& name, std::vector<glm::vec3> positions,
                                     std::vector<glm::vec3> normals, std::vector<uint32_t> indices, ChannelPath path,
                                     std::vector<float> key_values) {
  Character c;
  c.name = name;
  Skeleton& s = c.skeleton;
  s.names = {"root"};
  s.parents = {-1};
  s.rest_translations = {glm::vec3(0.0f)};
  s.rest_rotations = {glm::quat(1.0f, 0.0f, 0.0f, 0.0f)};
  s.rest_scales = {glm::vec3(1.0f)};
  s.parent_offsets = {glm::mat4(1.0f)};
  s.inverse_binds = {glm::mat4(1.0f)};
  SkinnedMesh& m = c.mesh;
  const auto vertices = static_cast<uint32_t>(positions.size());
  const auto index_count = static_cast<uint32_t>(indices.size());
  m.positions = std::move(positions);
  m.normals = std::move(normals);
  m.joints.assign(vertices, glm::u16vec4(0));
  m.weights.assign(vertices, glm::vec4(1, 0, 0, 0));
  m.indices = std::move(indices);
  m.primitives = {{0, index_count, 0, vertices}};
  Action action;
  action.name = name;
  action.start = 0.0f;
  action.end = 1.0f;
  Channel channel;
  channel.joint = 0;
  channel.path = path;
  channel.times = {0.0f, 1.0f};
  channel.values = std::move(key_values);
  action.channels = {channel};
  c.actions = {action};
  return c;
}

}  // namespace crowdprof::test
