#include "animation/joint_mask.h"

#include <algorithm>

namespace crowdprof {

std::string joint_mask(const Skeleton& skeleton, std::string_view root, int falloff, std::vector<float>* weights) {
  const size_t joints = skeleton.joint_count();
  if (falloff < 0) return "a falloff of " + std::to_string(falloff) + " joints: expected 0 or more";
  if (root.empty()) {
    weights->assign(joints, 1.0f);
    return {};
  }
  const auto found = std::find(skeleton.names.begin(), skeleton.names.end(), root);
  if (found == skeleton.names.end()) {
    std::string names;
    for (const std::string& name : skeleton.names) names += (names.empty() ? "" : ", ") + name;
    return "no joint '" + std::string(root) + "' (the joints are " + names + ")";
  }
  const int top = static_cast<int>(found - skeleton.names.begin());
  // Joints below `top`, counted from it (0 for itself); -1 outside. Parents
  // come before their children (the loader orders joints so).
  std::vector<int> below(joints, -1);
  below[static_cast<size_t>(top)] = 0;
  for (size_t j = static_cast<size_t>(top) + 1; j < joints; ++j) {
    const int parent = skeleton.parents[j];
    if (parent >= 0 && below[static_cast<size_t>(parent)] >= 0) below[j] = below[static_cast<size_t>(parent)] + 1;
  }
  weights->assign(joints, 0.0f);
  for (size_t j = 0; j < joints; ++j)
    if (below[j] >= 0)
      (*weights)[j] = std::min(1.0f, static_cast<float>(below[j] + 1) / static_cast<float>(falloff + 1));
  return {};
}

}  // namespace crowdprof
