// `crowdprof diff A.json B.json`: two results side by side, as Google
// Benchmark's compare.py does for two builds. Per metric (CPU time, the frame,
// each category that took time) the medians and the change; counters and
// digest compared exactly. Two results ran apart, never interleaved: frames of
// one process are not independent samples of another moment (the same bench
// run twice, one after the other, differed by +50% and -24% at p = 3e-11), so
// timings get no p-value and no verdict, and the text says to use compare or
// check --against. Only the calibrated frame, where both results carry it, is
// judged under check's rule (significant after Holm's correction, beyond the
// tolerance and beyond the floor).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "gate/regression.h"
#include "result/result.h"
#include "result/result_document.h"

namespace crowdprof {

// One mode at one crowd size present in both files.
struct DiffPair {
  std::string mode;
  size_t characters = 0;
  CheckResult check;               // A as the baseline, B as the current result
  std::vector<std::string> notes;  // scene fields that differ (timings may not compare)
};

struct Diff {
  std::string a, b;  // the files, as named
  std::vector<DiffPair> pairs;
  // Other work (counters, digest), or a tested metric that regressed.
  bool regressed() const;
  // Whether any metric was tested (the calibrated frame in both results).
  bool tested() const;
};

// Pairs the results of A and B by mode and crowd size (two single results
// whatever their modes and sizes, noting what differs). Each pair's metrics:
// the calibrated frame when both have it, judged with `options` (its metrics
// are replaced); then, shown untested (MetricCheck::tested false), CPU time
// when both have it, the frame, and every category whose median is at least
// 0.005 ms in either.
// InputError when B is of another character than A, or when the files share
// no mode and crowd size.
Diff diff_results(const std::vector<Result>& a, const std::string& path_a, const std::vector<Result>& b,
                  const std::string& path_b, const CheckOptions& options);

// The table for stdout: per pair a header, one row per metric (A and B
// medians, change, p, Holm-corrected p, verdict; "-" and "not tested" for
// untested rows, and a line saying why), then counters and digest.
std::string format_diff(const Diff& diff, const CheckOptions& options);

// {"crowdprof": {"kind": "diff", ...}, "a", "b", "tolerance", "floor", "alpha",
//  "pairs": [{"mode", "characters", "metrics": [...], "counters": [...],
//  "digest": {...}, "notes", "regressed"}], "regressed"} (docs/formats.md).
nlohmann::json diff_to_json(const Diff& diff, const CheckOptions& options);
// The same as a typed record (result/result_document.h), which the codec
// writes: diff_to_json is diff_record_to_json(diff_record(diff, options)).
DiffRecord diff_record(const Diff& diff, const CheckOptions& options);

}  // namespace crowdprof
