// Compiled once per SIMD target by Highway's foreach_target: this file includes
// itself for each target in HWY_TARGETS, and HWY_DYNAMIC_DISPATCH calls the best
// one the CPU supports (or the one simd_target.h forces).
#include <algorithm>
#include <cstring>

#include "skinning/packed_vertex.h"
#include "skinning/skinning_kernels.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "skinning/skinning_kernels.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/cache_control.h>
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace crowdprof {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Whether a vector of D is a whole batch that streams straight from registers
// (AVX-512, through the permutes below); every other width streams a batch
// through StageLines, so that only whole cache lines leave.
template <class D>
#if HWY_TARGET == HWY_AVX3 || HWY_TARGET == HWY_AVX3_DL
constexpr bool kStreamsFromRegisters = hn::MaxLanes(D()) == kSkinBatch;
#else
constexpr bool kStreamsFromRegisters = false;
#endif

#if HWY_TARGET == HWY_AVX3 || HWY_TARGET == HWY_AVX3_DL
// Indices for two-table permutes that interleave 16 x, 16 y and 16 z into 48
// floats: for output vector o, kXy[o] takes x (0-15) and y (16-31) into their
// places, then kZ[o] keeps those (its own lane i) and takes z (16-31) into the
// rest. Two permutes a vector, six in all, where Highway 1.0.3's generic
// StoreInterleaved3 spends about fourteen shuffles: on this CPU the shuffles
// share a port with the multiplies.
struct Interleave3Tables {
  alignas(64) int32_t xy[3][16];
  alignas(64) int32_t z[3][16];
  constexpr Interleave3Tables() : xy{}, z{} {
    for (int o = 0; o < 3; ++o)
      for (int i = 0; i < 16; ++i) {
        const int p = 16 * o + i, v = p / 3, c = p % 3;
        xy[o][i] = c == 0 ? v : c == 1 ? 16 + v : 0;
        z[o][i] = c == 2 ? 16 + v : i;
      }
  }
};
constexpr Interleave3Tables kInterleave3{};
#endif

// Stores x, y, z interleaved (x0 y0 z0 x1 ...): the same bytes whichever way.
// kStream (AVX-512 only, whose vector is a whole batch): non-temporal stores
// (`out` then 64-byte aligned), which write whole cache lines to memory without
// reading them first (see SkinKernelArgs::stream). Narrower vectors stream
// through StageLines.
// An if-else chain across #if blocks, which clang-format would indent as one statement.
// clang-format off
template <bool kStream, class D, class V = hn::Vec<D>>
HWY_INLINE void StoreXyz(D d, V x, V y, V z, float* HWY_RESTRICT out) {
#if HWY_TARGET == HWY_AVX3 || HWY_TARGET == HWY_AVX3_DL
  if constexpr (kStreamsFromRegisters<D>) {
    for (int o = 0; o < 3; ++o) {
      const __m512 xy = _mm512_permutex2var_ps(x.raw, _mm512_load_si512(kInterleave3.xy[o]), y.raw);
      const __m512 xyz = _mm512_permutex2var_ps(xy, _mm512_load_si512(kInterleave3.z[o]), z.raw);
      if constexpr (kStream)
        _mm512_stream_ps(out + 16 * o, xyz);
      else
        _mm512_storeu_ps(out + 16 * o, xyz);
    }
  } else  // NOLINT(readability/braces): the branch below is every other width
#endif
#if HWY_TARGET == HWY_AVX2
  // 8 lanes: one cross-lane permute a vector puts each vertex's x, y or z in
  // the lane it takes in one of the three outputs (x0 x3 x6 x1 x4 x7 x2 x5, y
  // and z rotated alike), then two blends a vector pick them out. Three
  // shuffles and six blends, where Highway 1.0.3's StoreInterleaved3 spends
  // about nine shuffles and five blends: the blends run on any vector port.
  if constexpr (hn::MaxLanes(D()) == 8) {
    static_assert(!kStream, "below a batch's width, streamed output is staged (StageLines)");
    const __m256 xr = _mm256_permutevar8x32_ps(x.raw, _mm256_setr_epi32(0, 3, 6, 1, 4, 7, 2, 5));
    const __m256 yr = _mm256_permutevar8x32_ps(y.raw, _mm256_setr_epi32(5, 0, 3, 6, 1, 4, 7, 2));
    const __m256 zr = _mm256_permutevar8x32_ps(z.raw, _mm256_setr_epi32(2, 5, 0, 3, 6, 1, 4, 7));
    // Blend masks: bit i takes lane i from the second operand (lanes 1 4 7,
    // 2 5 and 0 3 6).
    constexpr int k147 = 0x92, k25 = 0x24, k036 = 0x49;
    _mm256_storeu_ps(out + 0, _mm256_blend_ps(_mm256_blend_ps(xr, yr, k147), zr, k25));
    _mm256_storeu_ps(out + 8, _mm256_blend_ps(_mm256_blend_ps(xr, yr, k25), zr, k036));
    _mm256_storeu_ps(out + 16, _mm256_blend_ps(_mm256_blend_ps(xr, yr, k036), zr, k147));
  } else  // NOLINT(readability/braces): the branch below is every other width
#endif
  {
    static_assert(!kStream, "below a batch's width, streamed output is staged (StageLines)");
    hn::StoreInterleaved3(x, y, z, d, out);
  }
}
// clang-format on

// Narrower vectors than a batch each write part of a cache line (an AVX2 group
// of 8 vertices, 96 bytes, ends mid-line): streamed straight, a line's parts
// leave apart, and may leave as partial writes when other misses need the fill
// buffers. So a streamed batch is skinned into L1 and streamed from there as
// whole lines (docs/performance.md).
struct StageLines {
  alignas(64) float positions[3 * kSkinBatch];
  alignas(64) float normals[3 * kSkinBatch];
};

// Streams one staged array of a batch (3 cache lines) to `out`, 64-byte aligned.
template <class D>
HWY_INLINE void StreamBatchLines(D d, const float* HWY_RESTRICT staged, float* HWY_RESTRICT out) {
  for (size_t i = 0; i < 3 * kSkinBatch; i += hn::Lanes(d)) hn::Stream(hn::Load(d, staged + i), d, out + i);
}

// Where a group of lanes' packed codes go (packed_vertex.h).
struct PackedOut {
  uint16_t* positions;
  uint32_t* normals;
};

// The packed format's codes of lanes already skinned: each exactly what
// quantise_position and pack_normal give for the float result (subtract,
// multiply, clamp, round to nearest even: the same on every target).
template <class D, class V = hn::Vec<D>>
HWY_INLINE void StorePacked(D d, const V (&position)[3], const V (&normal)[3], const SkinKernelArgs& args,
                            PackedOut out) {
  const hn::Rebind<int32_t, D> di;
  const hn::Rebind<uint16_t, D> du16;
  const hn::Rebind<uint32_t, D> du32;
  hn::Vec<decltype(du16)> code[3];
  const V top = hn::Set(d, kPositionCodeMax);
  for (int a = 0; a < 3; ++a) {
    V q = hn::Mul(hn::Sub(position[a], hn::Set(d, args.quantisation_min[a])), hn::Set(d, args.quantisation_scale[a]));
    q = hn::Min(hn::Max(q, hn::Zero(d)), top);
    code[a] = hn::DemoteTo(du16, hn::NearestInt(q));
  }
  hn::StoreInterleaved3(code[0], code[1], code[2], du16, out.positions);
  const V one = hn::Set(d, 1.0f), minus_one = hn::Set(d, -1.0f), scale = hn::Set(d, kNormalCodeMax);
  const auto field = hn::Set(di, 0x3ff);
  hn::Vec<decltype(di)> c[3];
  for (int a = 0; a < 3; ++a)
    c[a] = hn::And(hn::NearestInt(hn::Mul(hn::Min(hn::Max(normal[a], minus_one), one), scale)), field);
  const auto word = hn::Or(hn::Or(c[0], hn::ShiftLeft<10>(c[1])), hn::ShiftLeft<20>(c[2]));
  hn::StoreU(hn::BitCast(du32, word), du32, out.normals);
}

// a x b + c: fused, with one rounding, on the targets that have FMA (AVX2 and
// up: Highway's AVX2 target requires it); a multiply, then an add, on the
// others. Fused takes about a third of the kernel's floating-point operations
// away (docs/performance.md). Each target's bits are the
// same on every CPU, thread count and split into ranges, and the targets with
// FMA agree with each other bit for bit (one rounding is one rounding); the two
// arithmetics differ in the last places (tests/skinning/simd_test.cpp).
#if defined(HWY_DISABLE_BMI2_FMA)
#error "HWY_DISABLE_BMI2_FMA makes AVX2's MulAdd round twice while AVX3's fuses: one arithmetic would give two digests"
#endif
#if HWY_TARGET <= HWY_AVX2 && HWY_ARCH_X86
constexpr bool kFusedMultiplyAdd = true;
#else
constexpr bool kFusedMultiplyAdd = false;
#endif
template <class V>
HWY_INLINE V MulAdd(V a, V b, V c) {
  if constexpr (kFusedMultiplyAdd)
    return hn::MulAdd(a, b, c);
  else
    return hn::Add(hn::Mul(a, b), c);
}

// The stages of skinning lanes [lane, lane + Lanes(d)) of one batch, each step
// in the same order on every target.

// Whether the blend reads its matrix elements broadcast already, from a table
// the kernel fills once a call (BroadcastPalette). Without AVX, broadcasting an
// element from the palette is a load and a shuffle, and the shuffles share a
// port with the interleaving; from the table it is a load folded into the
// multiply. AVX2 broadcasts with a load alone and would read 8 times the bytes
// from a table, so it does not (docs/performance.md, docs/experiments.md).
#if HWY_ARCH_X86 && HWY_TARGET > HWY_AVX2 && HWY_TARGET != HWY_EMU128 && HWY_TARGET != HWY_SCALAR
constexpr bool kBroadcastTable = true;
#else
constexpr bool kBroadcastTable = false;
#endif

// The largest skeleton whose table the kernel keeps on its stack (24 KB at
// SSE4), so that skinning allocates nothing; a larger one broadcasts from the
// palette as AVX2 does. 128 is the thesis's bone limit for hardware skinning.
constexpr size_t kTableJoints = 128;

// Fills `table` with the 3x4 part of each joint the plan uses, every element
// broadcast to a vector of D: element (column c, row r) of joint j at
// table[(12 j + 3 c + r) Lanes]. Needs plan.joint_count <= kTableJoints.
template <class D>
HWY_INLINE void BroadcastPalette(D d, const float* palette, const SkinningPlan& plan, float* HWY_RESTRICT table) {
  const size_t lanes = hn::Lanes(d);
  for (uint16_t j : plan.skin_joints) {
    float* t = table + 12 * lanes * j;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 3; ++r, t += lanes) hn::Store(hn::Set(d, palette[16 * size_t{j} + 4 * c + r]), d, t);
  }
}

// Element (column c, row r) of the joint at `m` as a vector: `m` points into
// BroadcastPalette's table (kTable) or into the palette (16 floats a joint).
template <bool kTable, class D, class V = hn::Vec<D>>
HWY_INLINE V MatrixElement(D d, const float* m, int c, int r) {
  if constexpr (kTable)
    return hn::Load(d, m + (3 * c + r) * hn::Lanes(d));
  else
    return hn::Set(d, m[4 * c + r]);
}

// The blended matrix's 3x4 part, a[column][row], one lane per vertex.
// `palette` is BroadcastPalette's table where kTable.
template <bool kTable, class D, class V = hn::Vec<D>>
HWY_INLINE void BlendMatrices(D d, const float* rows, size_t lane, const uint16_t* joints, size_t joint_count,
                              const float* palette, V (&a)[4][3]) {
  if (joint_count == 0) {
    for (auto& column : a)
      for (V& v : column) v = hn::Zero(d);
    return;
  }
  const size_t stride = kTable ? 12 * hn::Lanes(d) : 16;  // floats a joint
  const V w = hn::Load(d, rows + 6 * kSkinBatch + lane);
  const float* m = palette + stride * joints[0];
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 3; ++r) a[c][r] = hn::Mul(w, MatrixElement<kTable>(d, m, c, r));
  for (size_t u = 1; u < joint_count; ++u) {
    const V wu = hn::Load(d, rows + (6 + u) * kSkinBatch + lane);
    const float* mu = palette + stride * joints[u];
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 3; ++r) a[c][r] = MulAdd(wu, MatrixElement<kTable>(d, mu, c, r), a[c][r]);
  }
}

template <class D, class V = hn::Vec<D>>
HWY_INLINE void TransformPosition(D d, const V (&a)[4][3], const float* rows, size_t lane, V (&position)[3]) {
  const V px = hn::Load(d, rows + 0 * kSkinBatch + lane);
  const V py = hn::Load(d, rows + 1 * kSkinBatch + lane);
  const V pz = hn::Load(d, rows + 2 * kSkinBatch + lane);
  for (int r = 0; r < 3; ++r)
    // Fused, the translation starts the chain; separate, it comes last (the
    // order these kernels always had: SSE4's digests did not change).
    position[r] =
        kFusedMultiplyAdd
            ? MulAdd(a[2][r], pz, MulAdd(a[1][r], py, MulAdd(a[0][r], px, a[3][r])))
            : hn::Add(hn::Add(hn::Add(hn::Mul(a[0][r], px), hn::Mul(a[1][r], py)), hn::Mul(a[2][r], pz)), a[3][r]);
}

// The normal by the 3x3 part, not yet renormalised.
template <class D, class V = hn::Vec<D>>
HWY_INLINE void TransformNormal(D d, const V (&a)[4][3], const float* rows, size_t lane, V (&normal)[3]) {
  const V nx = hn::Load(d, rows + 3 * kSkinBatch + lane);
  const V ny = hn::Load(d, rows + 4 * kSkinBatch + lane);
  const V nz = hn::Load(d, rows + 5 * kSkinBatch + lane);
  for (int r = 0; r < 3; ++r) normal[r] = MulAdd(a[2][r], nz, MulAdd(a[1][r], ny, hn::Mul(a[0][r], nx)));
}

// 1 / |normal|: the correctly rounded square root and divide (never an
// approximate reciprocal square root, whose bits differ between CPU makers); a
// normal of zero (or NaN) length gets 0, so it comes out zero.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V InverseLength(D d, const V (&normal)[3]) {
  const V length2 = MulAdd(normal[2], normal[2], MulAdd(normal[1], normal[1], hn::Mul(normal[0], normal[0])));
  return hn::IfThenElseZero(hn::Gt(length2, hn::Zero(d)), hn::Div(hn::Set(d, 1.0f), hn::Sqrt(length2)));
}

// Packed output: every stage of the lanes, then their codes.
template <bool kTable, class D>
HWY_INLINE void SkinLanesPacked(D d, const float* rows, size_t lane, const uint16_t* joints, size_t joint_count,
                                const float* palette, bool normalise, const SkinKernelArgs& args, PackedOut out) {
  using V = hn::Vec<D>;
  V a[4][3], position[3], normal[3];
  BlendMatrices<kTable>(d, rows, lane, joints, joint_count, palette, a);
  TransformPosition(d, a, rows, lane, position);
  TransformNormal(d, a, rows, lane, normal);
  if (normalise) {
    const V inverse = InverseLength(d, normal);
    for (V& v : normal) v = hn::Mul(v, inverse);
  }
  StorePacked(d, position, normal, args, out);
}

// Float output is software-pipelined: a group of lanes' normal waits for its
// square root and divide (about 36 cycles on AVX-512) while the next group's
// matrices blend, instead of holding the out-of-order window until they end
// (docs/performance.md). Same steps, same bits.
template <class D>
struct PendingNormal {
  hn::Vec<D> normal[3];
  hn::Vec<D> inverse;
  float* out = nullptr;  // nullptr: nothing pending
  bool normalise = false;
  bool stream = false;
  // The last group of a staged batch: once stored, its batch's normals are
  // whole, and go from StageLines::normals to here.
  float* stream_batch_to = nullptr;
  const float* staged_normals = nullptr;
};

// StoreXyz with the kind of stores chosen at run time (per batch).
template <class D, class V = hn::Vec<D>>
HWY_INLINE void StoreXyzAs(D d, bool stream, V x, V y, V z, float* HWY_RESTRICT out) {
  if constexpr (kStreamsFromRegisters<D>) {
    if (stream) return StoreXyz<true>(d, x, y, z, out);
  }
  (void)stream;  // otherwise never set: such batches are staged (StageLines)
  StoreXyz<false>(d, x, y, z, out);
}

template <class D>
HWY_INLINE void StoreNormal(D d, PendingNormal<D>& pending) {
  if (!pending.out) return;
  if (pending.normalise)
    for (auto& v : pending.normal) v = hn::Mul(v, pending.inverse);
  StoreXyzAs(d, pending.stream, pending.normal[0], pending.normal[1], pending.normal[2], pending.out);
  pending.out = nullptr;
  if constexpr (!kStreamsFromRegisters<D>) {
    if (pending.stream_batch_to) {
      StreamBatchLines(d, pending.staged_normals, pending.stream_batch_to);
      pending.stream_batch_to = nullptr;
    }
  }
}

// Skins lanes into float positions (stored) and `pending` (the normal, stored
// by the next call or StoreNormal), after storing the normal pending before.
template <bool kTable, class D>
HWY_INLINE void SkinLanesFloat(D d, const float* rows, size_t lane, const uint16_t* joints, size_t joint_count,
                               const float* palette, bool normalise, bool stream, float* positions, float* normals,
                               PendingNormal<D>& pending) {
  using V = hn::Vec<D>;
  V a[4][3], position[3];
  BlendMatrices<kTable>(d, rows, lane, joints, joint_count, palette, a);
  StoreNormal(d, pending);
  TransformNormal(d, a, rows, lane, pending.normal);
  if (normalise) pending.inverse = InverseLength(d, pending.normal);
  pending.out = normals;
  pending.normalise = normalise;
  pending.stream = stream;
  TransformPosition(d, a, rows, lane, position);
  StoreXyzAs(d, stream, position[0], position[1], position[2], positions);
}

template <bool kPacked, bool kTable>
void SkinBatches(const SkinKernelArgs& args) {
  using D = hn::CappedTag<float, kSkinBatch>;
  const D d;
  const size_t lanes = hn::Lanes(d);
  const SkinningPlan& plan = *args.plan;
  HWY_ALIGN float table[kTable ? 12 * hn::MaxLanes(D()) * kTableJoints : 1];
  if constexpr (kTable) BroadcastPalette(d, args.palette, plan, table);
  const float* palette = kTable ? table : args.palette;
  const size_t first_batch = args.first_vertex / kSkinBatch;
  const size_t end_batch = (args.end_vertex + kSkinBatch - 1) / kSkinBatch;
  alignas(64) float scratch_positions[3 * kSkinBatch];
  alignas(64) float scratch_normals[3 * kSkinBatch];
  alignas(64) uint16_t scratch_codes[3 * kSkinBatch];
  alignas(64) uint32_t scratch_words[kSkinBatch];
  StageLines stage;
  PendingNormal<D> pending;
  for (size_t b = first_batch; b < end_batch; ++b) {
    const SkinBatch& batch = plan.batches[b];
    const float* rows = plan.data.data() + batch.data;
    const uint16_t* joints = plan.joints.data() + batch.first_joint;
    const bool normalise = !(batch.single_influence && args.keep_single_normals);
    const size_t first = b * kSkinBatch;
    // A batch wholly inside the range is written in place; the batches at its
    // ends go through scratch and only the range's vertices are copied out.
    const bool whole = first >= args.first_vertex && first + kSkinBatch <= args.end_vertex;
    const size_t at = first - args.first_vertex;  // wraps when !whole, then unused
    if constexpr (kPacked) {
      const PackedOut out = whole ? PackedOut{args.packed_positions + 3 * at, args.packed_normals + at}
                                  : PackedOut{scratch_codes, scratch_words};
      for (size_t lane = 0; lane < kSkinBatch; lane += lanes)
        SkinLanesPacked<kTable>(d, rows, lane, joints, batch.joint_count, palette, normalise, args,
                                PackedOut{out.positions + 3 * lane, out.normals + lane});
    } else {
      float* positions = whole ? args.positions + 3 * at : scratch_positions;
      float* normals = whole ? args.normals + 3 * at : scratch_normals;
      // Streamed: whole batches whose outputs start on a cache line (a batch is
      // 192 bytes of positions and as many of normals, three lines each).
      const bool stream = args.stream && whole && reinterpret_cast<uintptr_t>(positions) % 64 == 0 &&
                          reinterpret_cast<uintptr_t>(normals) % 64 == 0;
      const bool staged = !kStreamsFromRegisters<D> && stream;
      float* skin_positions = staged ? stage.positions : positions;
      float* skin_normals = staged ? stage.normals : normals;
      for (size_t lane = 0; lane < kSkinBatch; lane += lanes)
        SkinLanesFloat<kTable>(d, rows, lane, joints, batch.joint_count, palette, normalise, stream && !staged,
                               skin_positions + 3 * lane, skin_normals + 3 * lane, pending);
      if (staged) {
        StreamBatchLines(d, stage.positions, positions);
        pending.stream_batch_to = normals;  // the last group's normal is still pending
        pending.staged_normals = stage.normals;
      }
    }
    if (!whole) {
      const size_t from = std::max(first, args.first_vertex);
      const size_t to = std::min(first + kSkinBatch, args.end_vertex);
      if constexpr (kPacked) {
        std::memcpy(args.packed_positions + 3 * (from - args.first_vertex), scratch_codes + 3 * (from - first),
                    3 * (to - from) * sizeof(uint16_t));
        std::memcpy(args.packed_normals + (from - args.first_vertex), scratch_words + (from - first),
                    (to - from) * sizeof(uint32_t));
      } else {
        StoreNormal(d, pending);  // into scratch, before it is copied out
        std::memcpy(args.positions + 3 * (from - args.first_vertex), scratch_positions + 3 * (from - first),
                    3 * (to - from) * sizeof(float));
        std::memcpy(args.normals + 3 * (from - args.first_vertex), scratch_normals + 3 * (from - first),
                    3 * (to - from) * sizeof(float));
      }
    }
  }
  if constexpr (!kPacked) StoreNormal(d, pending);
  // Streamed stores are weakly ordered: fenced before this thread hands the
  // output on (a task's end, a join), so that whoever reads it next sees it.
  if (!kPacked && args.stream) hwy::FlushStream();
}

bool FusesMultiplyAdd() {
  return kFusedMultiplyAdd;
}

void SkinVertices(const SkinKernelArgs& args) {
  if constexpr (kBroadcastTable) {
    if (args.plan->joint_count <= kTableJoints)
      return args.packed_positions ? SkinBatches<true, true>(args) : SkinBatches<false, true>(args);
  }
  if (args.packed_positions)
    SkinBatches<true, false>(args);
  else
    SkinBatches<false, false>(args);
}

}  // namespace HWY_NAMESPACE
}  // namespace crowdprof
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace crowdprof {

HWY_EXPORT(SkinVertices);
HWY_EXPORT(FusesMultiplyAdd);

void run_skinning_kernel(const SkinKernelArgs& args) {
  HWY_DYNAMIC_DISPATCH(SkinVertices)(args);
}

bool skinning_fuses_multiply_add() {
  return HWY_DYNAMIC_DISPATCH(FusesMultiplyAdd)();
}

}  // namespace crowdprof
#endif
