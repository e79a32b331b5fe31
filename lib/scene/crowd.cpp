#include "scene/crowd.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

namespace crowdprof {

Crowd make_crowd(const Character& character, const CrowdOptions& options) {
  Crowd crowd;
  size_t n = options.copies;
  crowd.character_box = animated_bounds(character);
  glm::vec3 size = crowd.character_box.size();
  float spacing = std::max({size.x, size.z, size.y * 0.4f, 1e-3f}) * 1.1f;
  crowd.columns = std::max<size_t>(1, static_cast<size_t>(std::ceil(std::sqrt(static_cast<double>(n) * 1.6))));
  crowd.rows = (n + crowd.columns - 1) / crowd.columns;
  // std::mt19937 is specified exactly by the standard, so a seed gives the same
  // crowd with every compiler; the distributions are not, so draw by hand.
  std::mt19937 random(options.seed);
  size_t action_count = character.actions.size();
  crowd.world.reserve(n);
  for (size_t i = 0; i < n; ++i) {
    size_t column = i % crowd.columns, row = i / crowd.columns;
    float x = (static_cast<float>(column) - 0.5f * static_cast<float>(crowd.columns - 1)) * spacing;
    float z = -static_cast<float>(row) * spacing;
    glm::mat4 world = glm::translate(glm::mat4(1.0f), glm::vec3(x, 0.0f, z));
    crowd.world.push_back(world);
    crowd.world_boxes.push_back(transform_aabb(crowd.character_box, world));
    uint16_t action = 0;
    float phase = 0.0f;
    if (action_count > 0) {
      if (options.actions == ActionChoice::Random) {
        action = static_cast<uint16_t>(random() % action_count);
        float unit = static_cast<float>(random() >> 8) / static_cast<float>(1u << 24);
        phase = unit * character.actions[action].duration();
      } else {
        action = static_cast<uint16_t>(options.shared_action);
      }
    }
    crowd.action.push_back(action);
    crowd.phase.push_back(phase);
  }
  crowd.crowd_box = crowd.world_boxes.empty() ? Aabb{} : crowd.world_boxes.front();
  for (const Aabb& box : crowd.world_boxes) {
    crowd.crowd_box.min = glm::min(crowd.crowd_box.min, box.min);
    crowd.crowd_box.max = glm::max(crowd.crowd_box.max, box.max);
  }
  return crowd;
}

}  // namespace crowdprof
