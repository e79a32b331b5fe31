#include "frame/calibration_probe.h"

#include <chrono>
#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "frame/bench_threads.h"

namespace crowdprof {

namespace {

// The probe's size, fixed forever (see the header): 64 copies of a 4,096-vertex
// mesh with 64 joints and 4 influences (6.3 MB of skinned vertices), each copy
// then streaming 256 KiB more (16 MiB in all): 23 MB written a run, about what
// a frame of the thesis scene writes (160 copies, 19 MB), so that the probe
// meets the memory system as the frame does. A shared machine's swings are
// mostly there (other tenants' traffic); with the skinning alone the probe
// moved with the machine less than the frame did.
constexpr size_t kCopies = 64, kVertices = 4096, kJoints = 64;
constexpr size_t kStreamFloatsPerCopy = (256 << 10) / sizeof(float);

// A small deterministic generator: the probe's data never depends on the run.
float unit(uint32_t& state) {
  state = state * 1664525u + 1013904223u;
  return static_cast<float>(state >> 8) / static_cast<float>(1u << 24);
}

}  // namespace

CalibrationProbe::CalibrationProbe(size_t threads)
    : threads_(threads > 1 ? bench_threads(threads) : nullptr),
      positions_(kVertices * 3),
      normals_(kVertices * 3),
      weights_(kVertices * 4),
      joints_(kVertices * 4),
      palettes_(kCopies * kJoints * 12),
      output_(kCopies * kVertices * 6),
      stream_(kCopies * kStreamFloatsPerCopy) {
  uint32_t state = 1;
  for (size_t v = 0; v < kVertices; ++v) {
    float total = 0;
    for (size_t i = 0; i < 3; ++i) positions_[v * 3 + i] = unit(state) * 2 - 1;
    for (size_t i = 0; i < 3; ++i) normals_[v * 3 + i] = unit(state) * 2 - 1;
    for (size_t i = 0; i < 4; ++i) {
      joints_[v * 4 + i] = static_cast<unsigned short>(unit(state) * kJoints) % kJoints;
      total += weights_[v * 4 + i] = unit(state) + 0.01f;
    }
    for (size_t i = 0; i < 4; ++i) weights_[v * 4 + i] /= total;
  }
}

CalibrationProbe::~CalibrationProbe() = default;

void CalibrationProbe::skin_copy(size_t copy) {
  // The copy's palette: a rotation about y per joint that moves with the run,
  // the animation's share of the work.
  float* palette = &palettes_[copy * kJoints * 12];
  for (size_t j = 0; j < kJoints; ++j) {
    float angle = 0.01f * static_cast<float>(runs_ + copy + j);
    float c = std::cos(angle), s = std::sin(angle);
    float m[12] = {c, 0, s, 0.01f * static_cast<float>(j), 0, 1, 0, 0, -s, 0, c, 0.001f * static_cast<float>(copy)};
    for (size_t i = 0; i < 12; ++i) palette[j * 12 + i] = m[i];
  }
  float* __restrict out = &output_[copy * kVertices * 6];
  const float* __restrict positions = positions_.data();
  const float* __restrict normals = normals_.data();
  const float* __restrict weights = weights_.data();
  const unsigned short* __restrict joints = joints_.data();
  for (size_t v = 0; v < kVertices; ++v) {
    const float* a = &palette[joints[v * 4] * 12];
    const float* b = &palette[joints[v * 4 + 1] * 12];
    const float* c = &palette[joints[v * 4 + 2] * 12];
    const float* d = &palette[joints[v * 4 + 3] * 12];
    const float wa = weights[v * 4], wb = weights[v * 4 + 1], wc = weights[v * 4 + 2], wd = weights[v * 4 + 3];
    float m[12];
    for (size_t k = 0; k < 12; ++k) m[k] = wa * a[k] + wb * b[k] + wc * c[k] + wd * d[k];
    const float px = positions[v * 3], py = positions[v * 3 + 1], pz = positions[v * 3 + 2];
    const float nx = normals[v * 3], ny = normals[v * 3 + 1], nz = normals[v * 3 + 2];
    for (size_t r = 0; r < 3; ++r) {
      out[v * 6 + r] = m[r * 4] * px + m[r * 4 + 1] * py + m[r * 4 + 2] * pz + m[r * 4 + 3];
      out[v * 6 + 3 + r] = m[r * 4] * nx + m[r * 4 + 1] * ny + m[r * 4 + 2] * nz;
    }
  }
  float* stream = &stream_[copy * kStreamFloatsPerCopy];
  std::fill(stream, stream + kStreamFloatsPerCopy, out[copy % (kVertices * 6)]);
}

double CalibrationProbe::run() {
  auto start = std::chrono::steady_clock::now();
  if (threads_) {
    threads_->arena->execute([&] {
      tbb::parallel_for(tbb::blocked_range<size_t>(0, kCopies, 4), [&](const tbb::blocked_range<size_t>& range) {
        for (size_t copy = range.begin(); copy != range.end(); ++copy) skin_copy(copy);
      });
    });
  } else {
    for (size_t copy = 0; copy < kCopies; ++copy) skin_copy(copy);
  }
  auto end = std::chrono::steady_clock::now();
  ++runs_;
  checksum_ += output_[(runs_ * 7919) % output_.size()] + stream_[(runs_ * 104729) % stream_.size()];
  return std::chrono::duration<double, std::milli>(end - start).count();
}

}  // namespace crowdprof
