// A Result made up from frame times, for testing what reads reports
// (comparison tables, charts) without running a bench.
#pragma once

#include <string>
#include <vector>

#include "frame/run_bench.h"

namespace crowdprof::test {

// Frames of the given times, `animations_share` of each charged to
// Animations and the rest to Rasterizer.
inline Result fake_run(const std::string& mode, size_t characters, const std::vector<double>& frame_ms,
                       double animations_share = 1.0) {
  Result report;
  report.run.mode = mode;
  report.run.characters = characters;
  for (double ms : frame_ms) {
    FrameRecord f;
    f.times.ms[static_cast<size_t>(Category::Animations)] = ms * animations_share;
    if (animations_share < 1.0) f.times.ms[static_cast<size_t>(Category::Rasterizer)] = ms * (1.0 - animations_share);
    report.frame_records.push_back(f);
  }
  report.digest = "00000000000000aa";
  record_samples(report);
  return report;
}

}  // namespace crowdprof::test
