// Compiled once per SIMD target by Highway's foreach_target: this file includes
// itself for each target in HWY_TARGETS, and HWY_DYNAMIC_DISPATCH calls the best
// one the CPU supports (or the one simd_target.h forces).
#include <algorithm>
#include <cstring>

#include "skinning/skinning_kernels.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "skinning/skinning_kernels.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace crowdprof {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Lanes [lane, lane + Lanes(d)) of one batch. Mul and Add, never MulAdd: the
// targets with FMA would otherwise round differently from those without.
template <class D>
HWY_INLINE void SkinLanes(D d, const float* rows, size_t lane, const uint16_t* joints, size_t joint_count,
                          const float* palette, bool normalise, float* positions, float* normals) {
  using V = hn::Vec<D>;
  // The blended matrix's 3x4 part, a[column][row], one lane per vertex.
  V a[4][3];
  if (joint_count == 0) {
    for (auto& column : a)
      for (V& v : column) v = hn::Zero(d);
  } else {
    const V w = hn::Load(d, rows + 6 * kSkinBatch + lane);
    const float* m = palette + 16 * size_t{joints[0]};
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 3; ++r) a[c][r] = hn::Mul(w, hn::Set(d, m[4 * c + r]));
  }
  for (size_t u = 1; u < joint_count; ++u) {
    const V w = hn::Load(d, rows + (6 + u) * kSkinBatch + lane);
    const float* m = palette + 16 * size_t{joints[u]};
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 3; ++r) a[c][r] = hn::Add(a[c][r], hn::Mul(w, hn::Set(d, m[4 * c + r])));
  }
  const V px = hn::Load(d, rows + 0 * kSkinBatch + lane);
  const V py = hn::Load(d, rows + 1 * kSkinBatch + lane);
  const V pz = hn::Load(d, rows + 2 * kSkinBatch + lane);
  V out[3];
  for (int r = 0; r < 3; ++r)
    out[r] = hn::Add(hn::Add(hn::Add(hn::Mul(a[0][r], px), hn::Mul(a[1][r], py)), hn::Mul(a[2][r], pz)), a[3][r]);
  hn::StoreInterleaved3(out[0], out[1], out[2], d, positions);

  const V nx = hn::Load(d, rows + 3 * kSkinBatch + lane);
  const V ny = hn::Load(d, rows + 4 * kSkinBatch + lane);
  const V nz = hn::Load(d, rows + 5 * kSkinBatch + lane);
  for (int r = 0; r < 3; ++r)
    out[r] = hn::Add(hn::Add(hn::Mul(a[0][r], nx), hn::Mul(a[1][r], ny)), hn::Mul(a[2][r], nz));
  if (normalise) {
    const V length2 =
        hn::Add(hn::Add(hn::Mul(out[0], out[0]), hn::Mul(out[1], out[1])), hn::Mul(out[2], out[2]));
    // The correctly rounded square root and divide (never an approximate
    // reciprocal square root, whose bits differ between CPU makers); a normal
    // of zero (or NaN) length comes out zero.
    const V inverse =
        hn::IfThenElseZero(hn::Gt(length2, hn::Zero(d)), hn::Div(hn::Set(d, 1.0f), hn::Sqrt(length2)));
    for (V& v : out) v = hn::Mul(v, inverse);
  }
  hn::StoreInterleaved3(out[0], out[1], out[2], d, normals);
}

void SkinVertices(const SkinKernelArgs& args) {
  const hn::CappedTag<float, kSkinBatch> d;
  const size_t lanes = hn::Lanes(d);
  const SkinningPlan& plan = *args.plan;
  const size_t first_batch = args.first_vertex / kSkinBatch;
  const size_t end_batch = (args.end_vertex + kSkinBatch - 1) / kSkinBatch;
  alignas(64) float scratch_positions[3 * kSkinBatch];
  alignas(64) float scratch_normals[3 * kSkinBatch];
  for (size_t b = first_batch; b < end_batch; ++b) {
    const SkinBatch& batch = plan.batches[b];
    const float* rows = plan.data.data() + batch.data;
    const uint16_t* joints = plan.joints.data() + batch.first_joint;
    const bool normalise = !(batch.single_influence && args.keep_single_normals);
    const size_t first = b * kSkinBatch;
    // A batch wholly inside the range is written in place; the batches at its
    // ends go through scratch and only the range's vertices are copied out.
    const bool whole = first >= args.first_vertex && first + kSkinBatch <= args.end_vertex;
    float* positions = whole ? args.positions + 3 * (first - args.first_vertex) : scratch_positions;
    float* normals = whole ? args.normals + 3 * (first - args.first_vertex) : scratch_normals;
    for (size_t lane = 0; lane < kSkinBatch; lane += lanes)
      SkinLanes(d, rows, lane, joints, batch.joint_count, args.palette, normalise, positions + 3 * lane,
                normals + 3 * lane);
    if (!whole) {
      const size_t from = std::max(first, args.first_vertex);
      const size_t to = std::min(first + kSkinBatch, args.end_vertex);
      std::memcpy(args.positions + 3 * (from - args.first_vertex), scratch_positions + 3 * (from - first),
                  3 * (to - from) * sizeof(float));
      std::memcpy(args.normals + 3 * (from - args.first_vertex), scratch_normals + 3 * (from - first),
                  3 * (to - from) * sizeof(float));
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace crowdprof
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace crowdprof {

HWY_EXPORT(SkinVertices);

void run_skinning_kernel(const SkinKernelArgs& args) { HWY_DYNAMIC_DISPATCH(SkinVertices)(args); }

}  // namespace crowdprof
#endif
