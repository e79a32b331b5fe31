// What a timing gate is told: the metrics it judges, the tolerance, the
// significance level and the floor, parsed from what users write.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace crowdprof {

// "10%" or "0.1" (both a tenth) to a fraction; UsageError for anything else:
// words, negative values, NaN, more than 1000%.
double parse_tolerance(std::string_view text);

// The metric's key in "samples": "frame" gives "frame_ms"; a category is named
// as the BGE printed it or as a CSV column ("Animations", "animations",
// "GPU Latency", "gpu_latency"). UsageError listing the choices otherwise.
std::string resolve_metric(std::string_view name);

// The smallest slowdown that can fail a check, however significant: a fixed
// time, or a fraction of the baseline's median frame time. It keeps changes far
// below anything a user would notice (a category of microseconds moving by a
// microsecond) from failing CI.
struct Floor {
  double ms = 0;                    // when fraction is 0
  double fraction_of_frame = 0.02;  // of the baseline's median frame time
};

// "0.05ms", "50us" or "2%" (of the baseline's median frame); UsageError naming
// --floor for anything else.
Floor parse_floor(std::string_view text);

// The floor in milliseconds for a baseline whose median frame is `frame_ms`.
double floor_ms(const Floor& floor, double frame_ms);

// Default tolerance: a 10% slowdown of the frame, real work added, must fail
// (docs/compare-and-check.md measures how often it does), so the tolerance sits
// below it, and noise that moves a median by a few percent does not.
inline constexpr double kDefaultTolerance = 0.07;

struct CheckOptions {
  // Keys of "samples" (resolve_metric). The calibrated frame by default: on a
  // machine shared with other jobs the wall-clock frame swings by half and the
  // CPU time counts waiting workers' spinning, while the frame over a probe timed
  // at the same moment moves least (docs/compare-and-check.md has the measurement).
  std::vector<std::string> metrics = {"calibrated"};
  double tolerance = kDefaultTolerance;  // a slowdown of the median beyond this fraction...
  double alpha = 0.05;  // ...that the U test finds significant at this level (Holm-corrected over metrics)...
  Floor floor;          // ...and larger than this
  // False only to measure the gate itself (check --timings-only): timings of
  // two different runs, counters and digest not compared.
  bool compare_work = true;
};

// Every key of "samples" (frame_ms, then the categories): --metric all.
std::vector<std::string> all_metrics();

// How a samples key is named to users: "cpu_ms" as "cpu", "frame_ms" as
// "frame", a category by its key ("animations_ms").
std::string metric_display_name(const std::string& key);

}  // namespace crowdprof
