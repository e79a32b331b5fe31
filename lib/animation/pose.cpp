#include "animation/pose.h"

#include <cstring>

namespace crowdprof {
namespace {

const glm::mat4 kIdentity(1.0f);

bool is_identity(const glm::mat4& m) { return std::memcmp(&m, &kIdentity, sizeof m) == 0; }

// parent * TRS(t, r, s) without forming TRS as a 4x4 and without the products by
// its constant bottom row: three scaled rotation columns and a translation.
glm::mat4 times_trs(const glm::mat4& parent, const glm::vec3& t, const glm::quat& r,
                    const glm::vec3& s) {
  const glm::mat3 rotation = glm::mat3_cast(r);
  glm::mat4 out;
  for (int c = 0; c < 3; ++c) {
    const glm::vec3 column = rotation[c] * s[c];
    out[c] = parent[0] * column.x + parent[1] * column.y + parent[2] * column.z;
  }
  out[3] = parent[0] * t.x + parent[1] * t.y + parent[2] * t.z + parent[3];
  return out;
}

glm::mat4 trs(const glm::vec3& t, const glm::quat& r, const glm::vec3& s) {
  const glm::mat3 rotation = glm::mat3_cast(r);
  return glm::mat4(glm::vec4(rotation[0] * s.x, 0.0f), glm::vec4(rotation[1] * s.y, 0.0f),
                   glm::vec4(rotation[2] * s.z, 0.0f), glm::vec4(t, 1.0f));
}

bool skeleton_sized(const Skeleton& skeleton) {
  const size_t n = skeleton.joint_count();
  if (skeleton.parents.size() != n || skeleton.inverse_binds.size() != n ||
      skeleton.parent_offsets.size() != n)
    return false;
  for (size_t j = 0; j < n; ++j)
    if (skeleton.parents[j] >= static_cast<int>(j)) return false;  // parents come first
  return true;
}

}  // namespace

bool LocalToModelJob::Validate() const {
  if (skeleton == nullptr || input == nullptr || !skeleton_sized(*skeleton)) return false;
  const size_t n = skeleton->joint_count();
  return input->translations.size() == n && input->rotations.size() == n &&
         input->scales.size() == n && output.size() == n;
}

bool LocalToModelJob::Run() const {
  if (!Validate()) return false;
  const LocalPose& pose = *input;
  const size_t n = output.size();
  for (size_t j = 0; j < n; ++j) {
    const int parent = skeleton->parents[j];
    const glm::mat4& offset = skeleton->parent_offsets[j];
    const glm::vec3& t = pose.translations[j];
    const glm::quat& r = pose.rotations[j];
    const glm::vec3& s = pose.scales[j];
    if (parent < 0) {
      output[j] = is_identity(offset) ? trs(t, r, s) : times_trs(offset, t, r, s);
    } else {
      const glm::mat4& parent_model = output[static_cast<size_t>(parent)];
      output[j] = is_identity(offset) ? times_trs(parent_model, t, r, s)
                                      : times_trs(parent_model * offset, t, r, s);
    }
  }
  return true;
}

bool SkinningMatricesJob::Validate() const {
  if (skeleton == nullptr) return false;
  const size_t n = skeleton->joint_count();
  return skeleton->inverse_binds.size() == n && model.size() == n && output.size() == n;
}

bool SkinningMatricesJob::Run() const {
  if (!Validate()) return false;
  const size_t n = output.size();
  for (size_t j = 0; j < n; ++j) output[j] = model[j] * skeleton->inverse_binds[j];
  return true;
}

}  // namespace crowdprof
