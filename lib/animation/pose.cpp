#include "animation/pose.h"

#include <cstring>

namespace crowdprof {
namespace {

const glm::mat4 kIdentity(1.0f);

bool is_identity(const glm::mat4& m) { return std::memcmp(&m, &kIdentity, sizeof m) == 0; }

// A matrix as four column vectors (GCC/Clang vector types), so that products
// are column multiply-adds whatever glm's own code compiles to.
typedef float Float4 __attribute__((vector_size(16)));
struct Columns {
  Float4 c[4];
};

Columns columns_of(const glm::mat4& m) {
  Columns columns;
  std::memcpy(&columns, &m[0][0], sizeof m);  // glm::mat4 is only 4-byte aligned
  return columns;
}

glm::mat4 to_mat4(const Columns& columns) {
  glm::mat4 m;
  std::memcpy(&m[0][0], &columns, sizeof m);
  return m;
}

// a * b, general 4x4.
glm::mat4 multiply(const glm::mat4& a, const glm::mat4& b) {
  const Columns ca = columns_of(a);
  Columns out;
  for (int c = 0; c < 4; ++c)
    out.c[c] = ca.c[0] * b[c][0] + ca.c[1] * b[c][1] + ca.c[2] * b[c][2] + ca.c[3] * b[c][3];
  return to_mat4(out);
}

// parent * TRS(t, r, s) without forming TRS as a 4x4 and without the products by
// its constant bottom row: three scaled rotation columns and a translation.
glm::mat4 times_trs(const glm::mat4& parent, const glm::vec3& t, const glm::quat& r,
                    const glm::vec3& s) {
  const glm::mat3 rotation = glm::mat3_cast(r);
  const Columns p = columns_of(parent);
  Columns out;
  for (int c = 0; c < 3; ++c) {
    const glm::vec3 axis = rotation[c] * s[c];
    out.c[c] = p.c[0] * axis.x + p.c[1] * axis.y + p.c[2] * axis.z;
  }
  out.c[3] = p.c[0] * t.x + p.c[1] * t.y + p.c[2] * t.z + p.c[3];
  return to_mat4(out);
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
                                      : times_trs(multiply(parent_model, offset), t, r, s);
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
  for (size_t j = 0; j < n; ++j) output[j] = multiply(model[j], skeleton->inverse_binds[j]);
  return true;
}

}  // namespace crowdprof
