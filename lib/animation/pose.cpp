#include "animation/pose.h"

#include <algorithm>
#include <cstddef>
#include <cstring>

namespace crowdprof {
namespace {

const glm::mat4 kIdentity(1.0f);

bool is_identity(const glm::mat4& m) {
  return std::memcmp(&m, &kIdentity, sizeof m) == 0;
}

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
  for (int c = 0; c < 4; ++c) out.c[c] = ca.c[0] * b[c][0] + ca.c[1] * b[c][1] + ca.c[2] * b[c][2] + ca.c[3] * b[c][3];
  return to_mat4(out);
}

// R(r) S(s) of up to four joints, lane i for joint i: axis[3 c + k] holds
// element k of column c. The products and sums are glm::mat3_cast's, then each
// column times its scale, in the same order (and no contraction:
// -ffp-contract=off), so the same bits as one joint at a time with glm, in
// less time (docs/performance.md).
struct ScaledAxes {
  Float4 axis[9];
};

// A quaternion's x, y, z, w, loaded as one vector (glm stores them in that
// order unless GLM_FORCE_QUAT_DATA_WXYZ).
static_assert(sizeof(glm::quat) == 16 && offsetof(glm::quat, x) == 0 && offsetof(glm::quat, w) == 12);
Float4 load_quat(const glm::quat& q) {
  Float4 v;
  std::memcpy(&v, &q, sizeof v);
  return v;
}

// A vec3's x, y, z, then 0, built in registers: copied as 12 bytes into a
// vector in memory and loaded, the load waited for the smaller stores.
Float4 load_vec3(const glm::vec3& p) {
  return Float4{p.x, p.y, p.z, 0.0f};
}

// Transposes the 4x4 whose rows are a, b, c and d: a then holds their first
// elements, b their second, and so on.
void transpose(Float4& a, Float4& b, Float4& c, Float4& d) {
  const Float4 ab_low = __builtin_shufflevector(a, b, 0, 4, 1, 5);
  const Float4 cd_low = __builtin_shufflevector(c, d, 0, 4, 1, 5);
  const Float4 ab_high = __builtin_shufflevector(a, b, 2, 6, 3, 7);
  const Float4 cd_high = __builtin_shufflevector(c, d, 2, 6, 3, 7);
  a = __builtin_shufflevector(ab_low, cd_low, 0, 1, 4, 5);
  b = __builtin_shufflevector(ab_low, cd_low, 2, 3, 6, 7);
  c = __builtin_shufflevector(ab_high, cd_high, 0, 1, 4, 5);
  d = __builtin_shufflevector(ab_high, cd_high, 2, 3, 6, 7);
}

ScaledAxes scaled_axes(const LocalPose& pose, size_t first, size_t count) {
  Float4 q[4], s[4];  // per joint, then transposed: per component
  for (size_t i = 0; i < 4; ++i) {
    const size_t j = first + std::min(i, count - 1);  // lanes past the end repeat the last joint
    q[i] = load_quat(pose.rotations[j]);
    s[i] = load_vec3(pose.scales[j]);
  }
  transpose(q[0], q[1], q[2], q[3]);
  transpose(s[0], s[1], s[2], s[3]);
  const Float4 &x = q[0], &y = q[1], &z = q[2], &w = q[3];
  const Float4 qxx = x * x, qyy = y * y, qzz = z * z, qxz = x * z, qxy = x * y, qyz = y * z;
  const Float4 qwx = w * x, qwy = w * y, qwz = w * z;
  const Float4 rotation[9] = {1.0f - 2.0f * (qyy + qzz), 2.0f * (qxy + qwz),        2.0f * (qxz - qwy),
                              2.0f * (qxy - qwz),        1.0f - 2.0f * (qxx + qzz), 2.0f * (qyz + qwx),
                              2.0f * (qxz + qwy),        2.0f * (qyz - qwx),        1.0f - 2.0f * (qxx + qyy)};
  ScaledAxes out;
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k) out.axis[3 * c + k] = rotation[3 * c + k] * s[c];
  return out;
}

// Column c of joint i's R(r) S(s).
glm::vec3 axis(const ScaledAxes& axes, int c, int i) {
  return {axes.axis[3 * c][i], axes.axis[3 * c + 1][i], axes.axis[3 * c + 2][i]};
}

// parent * TRS(t, r, s) without forming TRS as a 4x4 and without the products by
// its constant bottom row: three scaled rotation columns (lane i of `axes`)
// and a translation.
// Inlined: as a call it returns its matrix through the stack, which the
// caller then reads back, where inlined it stays in registers.
inline __attribute__((always_inline)) glm::mat4 times_trs(const glm::mat4& parent, const glm::vec3& t,
                                                          const ScaledAxes& axes, int i) {
  const Columns p = columns_of(parent);
  Columns out;
  for (int c = 0; c < 3; ++c) {
    const glm::vec3 a = axis(axes, c, i);
    out.c[c] = p.c[0] * a.x + p.c[1] * a.y + p.c[2] * a.z;
  }
  out.c[3] = p.c[0] * t.x + p.c[1] * t.y + p.c[2] * t.z + p.c[3];
  return to_mat4(out);
}

glm::mat4 trs(const glm::vec3& t, const ScaledAxes& axes, int i) {
  return glm::mat4(glm::vec4(axis(axes, 0, i), 0.0f), glm::vec4(axis(axes, 1, i), 0.0f),
                   glm::vec4(axis(axes, 2, i), 0.0f), glm::vec4(t, 1.0f));
}

bool skeleton_sized(const Skeleton& skeleton) {
  const size_t n = skeleton.joint_count();
  if (skeleton.parents.size() != n || skeleton.inverse_binds.size() != n || skeleton.parent_offsets.size() != n)
    return false;
  for (size_t j = 0; j < n; ++j)
    if (skeleton.parents[j] >= static_cast<int>(j)) return false;  // parents come first
  return true;
}

}  // namespace

bool LocalToModelJob::Validate() const {
  if (skeleton == nullptr || input == nullptr || !skeleton_sized(*skeleton)) return false;
  const size_t n = skeleton->joint_count();
  return input->translations.size() == n && input->rotations.size() == n && input->scales.size() == n &&
         output.size() == n;
}

bool LocalToModelJob::Run() const {
  if (!Validate()) return false;
  const LocalPose& pose = *input;
  const size_t n = output.size();
  ScaledAxes axes;
  for (size_t j = 0; j < n; ++j) {
    const int lane = static_cast<int>(j % 4);
    if (lane == 0) axes = scaled_axes(pose, j, std::min<size_t>(4, n - j));
    const int parent = skeleton->parents[j];
    const glm::mat4& offset = skeleton->parent_offsets[j];
    const glm::vec3& t = pose.translations[j];
    if (parent < 0) {
      output[j] = is_identity(offset) ? trs(t, axes, lane) : times_trs(offset, t, axes, lane);
    } else {
      const glm::mat4& parent_model = output[static_cast<size_t>(parent)];
      output[j] = is_identity(offset) ? times_trs(parent_model, t, axes, lane)
                                      : times_trs(multiply(parent_model, offset), t, axes, lane);
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
