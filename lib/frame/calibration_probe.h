// A fixed piece of work of the frame's own kind, timed beside every frame, so
// that a stored baseline can be compared in units of the machine's speed at the
// moment each frame ran (check --metric calibrated).
//
// Why: a shared machine switches speed within seconds (another tenant's memory
// traffic, a core taken by another job), so a frame time recorded at another
// moment fails an unchanged build. The probe skins a fixed crowd with a fixed
// scalar kernel on the bench's own threads right after each frame: it meets the
// same memory system and the same competition for the cores, while a change of
// the bench's work (more copies, a slower kernel) leaves it unchanged.
//
// The probe's work must never change: baselines hold frames over its time. A
// change needs kCalibrationProbeVersion bumped (a baseline of another version is
// not compared on this metric).
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

namespace crowdprof {

struct BenchThreads;

inline constexpr int kCalibrationProbeVersion = 1;

class CalibrationProbe {
 public:
  // Runs on the bench's arena of `threads` threads (bench_threads.h), serially
  // for one. Allocates its mesh, palettes and output once.
  explicit CalibrationProbe(size_t threads);
  ~CalibrationProbe();
  CalibrationProbe(const CalibrationProbe&) = delete;
  CalibrationProbe& operator=(const CalibrationProbe&) = delete;

  // Runs the work once and returns its wall-clock time in milliseconds.
  double run();

  // A checksum of the last output, so the work cannot be optimised away.
  float checksum() const { return checksum_; }

 private:
  void skin_copy(size_t copy);

  std::shared_ptr<BenchThreads> threads_;
  size_t runs_ = 0;
  std::vector<float> positions_, normals_, weights_;  // per vertex: 3, 3, 4
  std::vector<unsigned short> joints_;                // per vertex: 4
  std::vector<float> palettes_;                       // per copy: kJoints 3x4 matrices
  std::vector<float> output_;                         // per copy and vertex: position, normal
  std::vector<float> stream_;                         // per copy: a block streamed after skinning
  float checksum_ = 0;
};

}  // namespace crowdprof
