#include "skinning/skinning.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#if defined(__SSE__)
#include <immintrin.h>
#endif

namespace crowdprof {
namespace {

// GCC/Clang vector types: one mat4 is two 8-float halves (columns 0-1 and 2-3),
// so a weighted sum of four matrices is eight 8-wide multiply-adds.
typedef float Float4 __attribute__((vector_size(16)));
typedef float Float8 __attribute__((vector_size(32)));

inline Float8 load8(const float* p) {
  Float8 v;
  std::memcpy(&v, p, sizeof v);  // glm::mat4 is only 4-byte aligned
  return v;
}

// Vertices per block: long enough that the normals' square roots and divides
// run 8 wide, short enough that the block's scratch stays in L1.
constexpr size_t kBlock = 64;

// inverse[k] = 1 / sqrt(length2[k]), or 0 where length2[k] is not positive. The
// correctly rounded sqrt and divide (never the approximate rsqrt, whose bits
// differ between CPU makers), so a vertex's result depends neither on its lane
// nor on which of the paths below was compiled.
void inverse_lengths(const float* length2, float* inverse) {
#if defined(__AVX__)
  for (size_t k = 0; k < kBlock; k += 8) {
    const __m256 l = _mm256_load_ps(length2 + k);
    const __m256 r = _mm256_div_ps(_mm256_set1_ps(1.0f), _mm256_sqrt_ps(l));
    _mm256_store_ps(inverse + k, _mm256_and_ps(r, _mm256_cmp_ps(l, _mm256_setzero_ps(), _CMP_GT_OQ)));
  }
#elif defined(__SSE__)
  for (size_t k = 0; k < kBlock; k += 4) {
    const __m128 l = _mm_load_ps(length2 + k);
    const __m128 r = _mm_div_ps(_mm_set1_ps(1.0f), _mm_sqrt_ps(l));
    _mm_store_ps(inverse + k, _mm_and_ps(r, _mm_cmpgt_ps(l, _mm_setzero_ps())));
  }
#else
  for (size_t k = 0; k < kBlock; ++k)
    inverse[k] = length2[k] > 0.0f ? 1.0f / std::sqrt(length2[k]) : 0.0f;
#endif
}

// The mesh's arrays from one vertex on, read by skin_vertex.
struct VertexArrays {
  const glm::vec3* positions;
  const glm::vec3* normals;
  const glm::u16vec4* joints;
  const glm::vec4* weights;
};

// Skins vertex i: writes its position, and its unnormalised normal and that
// normal's squared length for the block's normalisation.
inline void skin_vertex(const SkinMatrix* palette, const VertexArrays& in, size_t i,
                        glm::vec3* position, Float4* normal, float* length2) {
  const glm::u16vec4 joint = in.joints[i];
  const glm::vec4 w = in.weights[i];
  const float* m = &palette[joint.x][0][0];
  Float8 lo = load8(m) * w.x;
  Float8 hi = load8(m + 8) * w.x;
  if (w.y != 0.0f) {
    m = &palette[joint.y][0][0];
    lo += load8(m) * w.y;
    hi += load8(m + 8) * w.y;
    if (w.z != 0.0f) {
      m = &palette[joint.z][0][0];
      lo += load8(m) * w.z;
      hi += load8(m + 8) * w.z;
      if (w.w != 0.0f) {
        m = &palette[joint.w][0][0];
        lo += load8(m) * w.w;
        hi += load8(m + 8) * w.w;
      }
    }
  }
  // column0 * x + column1 * y + column2 * z + column3 * (1 for points, 0 for
  // normals): the halves hold columns 0|1 and 2|3, so multiply each by its
  // coordinates and add the two 4-float halves.
  const glm::vec3 p = in.positions[i];
  const Float8 s = lo * Float8{p.x, p.x, p.x, p.x, p.y, p.y, p.y, p.y} +
                   hi * Float8{p.z, p.z, p.z, p.z, 1.0f, 1.0f, 1.0f, 1.0f};
  const Float4 skinned_p =
      __builtin_shufflevector(s, s, 0, 1, 2, 3) + __builtin_shufflevector(s, s, 4, 5, 6, 7);
  *position = glm::vec3(skinned_p[0], skinned_p[1], skinned_p[2]);

  const glm::vec3 n = in.normals[i];
  const Float8 t = lo * Float8{n.x, n.x, n.x, n.x, n.y, n.y, n.y, n.y} +
                   hi * Float8{n.z, n.z, n.z, n.z, 0.0f, 0.0f, 0.0f, 0.0f};
  const Float4 skinned_n =
      __builtin_shufflevector(t, t, 0, 1, 2, 3) + __builtin_shufflevector(t, t, 4, 5, 6, 7);
  *normal = skinned_n;
  *length2 = skinned_n[0] * skinned_n[0] + skinned_n[1] * skinned_n[1] + skinned_n[2] * skinned_n[2];
}

}  // namespace

bool SkinningJob::Validate() const {
  if (mesh == nullptr) return false;
  const size_t n = mesh->positions.size();
  if (mesh->normals.size() != n || mesh->joints.size() != n || mesh->weights.size() != n)
    return false;
  if (first_vertex > n || vertex_count > n - first_vertex) return false;
  if (out_positions.size() != vertex_count || out_normals.size() != vertex_count) return false;
  // An empty range of a mesh without vertices (a skin bound to no mesh) has no
  // joint to scan, and its data() may be null.
  if (vertex_count == 0) return true;
  // Joint indices come from the file: one past the palette would read beyond it.
  // As one flat array of indices, so that the scan vectorises.
  const uint16_t* joints = &mesh->joints.data()[first_vertex].x;
  uint16_t largest = 0;
  for (size_t k = 0; k < 4 * vertex_count; ++k) largest = std::max(largest, joints[k]);
  return largest < skinning_matrices.size();
}

bool SkinningJob::Run() const {
  if (!Validate()) return false;
  const SkinMatrix* palette = skinning_matrices.data();
  const VertexArrays in{mesh->positions.data() + first_vertex, mesh->normals.data() + first_vertex,
                        mesh->joints.data() + first_vertex, mesh->weights.data() + first_vertex};
  glm::vec3* positions = out_positions.data();
  glm::vec3* normals = out_normals.data();
  alignas(32) Float4 unnormalised[kBlock];
  alignas(32) float length2[kBlock];
  alignas(32) float inverse[kBlock];
  for (size_t start = 0; start < vertex_count; start += kBlock) {
    const size_t count = std::min(kBlock, vertex_count - start);
    for (size_t k = count; k < kBlock; ++k) length2[k] = 0.0f;  // lanes past the end
    for (size_t k = 0; k < count; ++k)
      skin_vertex(palette, in, start + k, &positions[start + k], &unnormalised[k], &length2[k]);
    inverse_lengths(length2, inverse);
    for (size_t k = 0; k < count; ++k) {
      const Float4 unit = unnormalised[k] * inverse[k];
      normals[start + k] = glm::vec3(unit[0], unit[1], unit[2]);
    }
  }
  return true;
}

}  // namespace crowdprof
