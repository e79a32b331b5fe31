#include "scene/crowd.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

namespace crowdprof {

namespace {

// A float in [0, 1) from 24 bits of the generator (std::mt19937 is exact in
// the standard; its distributions are not, so draws are made by hand).
float unit(std::mt19937& random) {
  return static_cast<float>(random() >> 8) / static_cast<float>(1u << 24);
}

}  // namespace

std::vector<CrowdGroup> crowd_groups(const CrowdOptions& options) {
  if (options.groups.empty()) {
    CrowdGroup group;
    group.copies = options.copies;
    group.actions = options.actions;
    group.shared_action = options.shared_action;
    return {group};
  }
  std::vector<CrowdGroup> groups = options.groups;
  size_t total = 0;
  for (const CrowdGroup& g : groups) total += g.copies;
  if (total == options.copies || total == 0) return groups;
  // Scale by largest remainders, so the counts add up exactly.
  std::vector<std::pair<double, size_t>> remainders;
  size_t given = 0;
  for (size_t i = 0; i < groups.size(); ++i) {
    double exact =
        static_cast<double>(groups[i].copies) * static_cast<double>(options.copies) / static_cast<double>(total);
    groups[i].copies = static_cast<size_t>(std::floor(exact));
    given += groups[i].copies;
    remainders.push_back({exact - std::floor(exact), i});
  }
  std::stable_sort(remainders.begin(), remainders.end(), [](auto a, auto b) { return a.first > b.first; });
  for (size_t k = 0; given < options.copies; ++k, ++given) ++groups[remainders[k % remainders.size()].second].copies;
  return groups;
}

Crowd make_crowd(const Character& character, const CrowdOptions& options) {
  const Character* one[] = {&character};
  return make_crowd(one, options);
}

Crowd make_crowd(std::span<const Character* const> characters, const CrowdOptions& options) {
  Crowd crowd;
  std::vector<CrowdGroup> groups = crowd_groups(options);
  size_t n = 0;
  for (const CrowdGroup& g : groups) n += g.copies;
  float footprint = 1e-3f;
  for (const Character* character : characters) {
    crowd.character_boxes.push_back(animated_bounds(*character));
    glm::vec3 size = crowd.character_boxes.back().size();
    footprint = std::max({footprint, size.x, size.z, size.y * 0.4f});
  }
  const CrowdLayout& layout = options.layout;
  float spacing = layout.spacing > 0 ? layout.spacing : footprint * 1.1f;
  if (layout.rows > 0) {
    crowd.rows = std::min(layout.rows, std::max<size_t>(n, 1));
    crowd.columns = std::max<size_t>(1, (n + crowd.rows - 1) / crowd.rows);
  } else {
    crowd.columns = std::max<size_t>(1, static_cast<size_t>(std::ceil(std::sqrt(static_cast<double>(n) * 1.6))));
  }
  crowd.rows = (n + crowd.columns - 1) / crowd.columns;

  // Which group each grid slot gets: the group furthest behind its share, so
  // a mixed crowd is spread evenly (a single group takes every slot).
  std::vector<size_t> placed(groups.size(), 0);
  std::mt19937 random(options.seed);
  std::mt19937 jitter(layout.jitter_seed);
  crowd.world.reserve(n);
  for (size_t i = 0; i < n; ++i) {
    size_t pick = 0;
    double best = -1e300;
    for (size_t g = 0; g < groups.size(); ++g) {
      if (placed[g] >= groups[g].copies) continue;
      double deficit = static_cast<double>(groups[g].copies) * static_cast<double>(i + 1) / static_cast<double>(n) -
                       static_cast<double>(placed[g]);
      if (deficit > best) best = deficit, pick = g;
    }
    ++placed[pick];
    const CrowdGroup& group = groups[pick];
    const Character& character = *characters[group.character];

    size_t column = i % crowd.columns, row = i / crowd.columns;
    float x = (static_cast<float>(column) - 0.5f * static_cast<float>(crowd.columns - 1)) * spacing;
    float z = -static_cast<float>(row) * spacing;
    if (layout.jitter > 0) {
      x += (2.0f * unit(jitter) - 1.0f) * layout.jitter;
      z += (2.0f * unit(jitter) - 1.0f) * layout.jitter;
    }
    glm::mat4 world = glm::translate(glm::mat4(1.0f), glm::vec3(x, 0.0f, z));
    crowd.world.push_back(world);
    crowd.kind.push_back(static_cast<uint16_t>(group.character));
    crowd.world_boxes.push_back(transform_aabb(crowd.character_boxes[group.character], world));
    uint16_t action = 0;
    float phase = 0.0f;
    size_t action_count = character.actions.size();
    if (action_count > 0) {
      if (group.actions == ActionChoice::Random) {
        action = static_cast<uint16_t>(random() % action_count);
        phase = unit(random) * character.actions[action].duration();
      } else if (group.actions == ActionChoice::Weighted) {
        double total = std::accumulate(group.weights.begin(), group.weights.end(), 0.0);
        double draw = static_cast<double>(unit(random)) * total;
        size_t a = 0, last = 0;  // the last action with a weight: rounding never picks a zero
        for (size_t w = 0; w < group.weights.size(); ++w)
          if (group.weights[w] > 0) last = w;
        while (a < last && (group.weights[a] <= 0 || draw >= group.weights[a])) draw -= group.weights[a++];
        action = static_cast<uint16_t>(a);
        phase = unit(random) * character.actions[action].duration();
      } else {
        action = static_cast<uint16_t>(group.shared_action);
      }
    }
    crowd.action.push_back(action);
    crowd.phase.push_back(phase);
    crowd.schedule_stream.push_back(static_cast<uint32_t>(group.actions == ActionChoice::Shared ? n + pick : i));
    crowd.transitions.push_back(group.transitions.value_or(options.transitions));
  }
  if (std::none_of(crowd.transitions.begin(), crowd.transitions.end(),
                   [](const TransitionTiming& t) { return t.mean_s > 0; }))
    crowd.transitions.clear();
  crowd.crowd_box = crowd.world_boxes.empty() ? Aabb{} : crowd.world_boxes.front();
  for (const Aabb& box : crowd.world_boxes) {
    crowd.crowd_box.min = glm::min(crowd.crowd_box.min, box.min);
    crowd.crowd_box.max = glm::max(crowd.crowd_box.max, box.max);
  }
  return crowd;
}

}  // namespace crowdprof
