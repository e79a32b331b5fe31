// `crowdprof check` against a stored baseline: did this change make things
// slower, or change the work? Timing is judged on the per-frame samples of two
// results with a tolerance and the Mann-Whitney U test together, so noise
// alone does not fail; the deterministic counters and the digest are compared
// exactly.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "gate/check_options.h"
#include "gate/mann_whitney.h"
#include "gate/work_witness.h"
#include "result/result.h"
#include "measuring/stats.h"

namespace crowdprof {

struct MetricCheck {
  std::string metric;  // as the user named it: "frame", "Animations"
  Summary baseline, current;
  double baseline_iqr = 0, current_iqr = 0;  // interquartile range, ms
  double change = 0;                         // of the median, a fraction; +0.2 is 20% slower
  double floor_ms = 0;                       // the floor it was judged against
  MannWhitney test;                          // current against baseline
  double p_adjusted = 1;                     // test.p, Holm-corrected for the metrics tested together
  bool beyond_tolerance = false, beyond_floor = false, significant = false;
  bool too_few_samples = false;  // under kMannWhitneyMinSamples: decided on the tolerance and floor alone
  // False: shown for its change alone, never tested nor judged (diff of two
  // results measured apart: frames of one process are not samples of another
  // moment, so a p-value would call the machine's drift significant).
  bool tested = true;
  std::string unit = "frames";  // what was compared: each frame, or the median of each run ("runs")
  // What the values are in: "ms", or "probes" for calibrated (each frame over
  // the calibration probe's time at the same moment).
  std::string value_unit = "ms";
  bool regressed = false;
  // Slower beyond the gate, but the work witness found the same instructions
  // on a machine that had changed (gate/work_witness.h): a warning, not a
  // failure (regressed is then false).
  bool excused = false;
  // Its median beyond the tolerance and floor, not significant, and the work
  // witness counted instructions per frame grown beyond the tolerance too: the
  // build's slowdown, which runs too noisy to test do not hide (regressed).
  bool work_grew = false;
};

// Faster beyond the tolerance, and significantly so: the test's p is
// two-sided, `significant` is slower's side alone.
inline bool significantly_faster(const MetricCheck& m, const CheckOptions& options) {
  return m.tested && m.change < -options.tolerance && m.p_adjusted < options.alpha && m.test.z < 0;
}

struct CounterDifference {
  std::string name;
  uint64_t baseline = 0, current = 0;
};

// Whether two runs hashed their vertices in different orders: a difference
// only where a digest hashes vertices at all (`digest_of_kernels`: either run's
// Result::digest_cpu_vertices), since palettes have no order.
inline bool vertex_orders_differ(const std::string& baseline, const std::string& current, bool digest_of_kernels) {
  return digest_of_kernels && baseline != current;
}

struct CheckResult {
  std::vector<MetricCheck> metrics;
  std::vector<CounterDifference> counters;    // only those that differ
  std::vector<std::string> counters_missing;  // in the baseline, not in the current result
  std::string baseline_digest, current_digest;
  // The SIMD targets the two ran on and whether their kernels fused
  // multiply-adds (environment.simd, environment.fused_multiply_add).
  std::string baseline_simd, current_simd;
  bool baseline_fused = false, current_fused = false;
  // Whether either digest hashes vertices the SIMD kernels skinned
  // (Result::digest_cpu_vertices): false when both runs' renderers skinned
  // every character, whose digests hash palettes and records no kernel computes.
  bool digest_of_kernels = true;
  // One run's kernels fused multiplies and adds and the other's did not, and
  // the digests hash their vertices: their last bits differ by design (within
  // 1e-5 of the height), so digests are not compared.
  bool arithmetic_differs() const { return digest_of_kernels && baseline_fused != current_fused; }
  // The order each hashed its vertices in (Result::vertex_order): a baseline
  // recorded before the bench ordered vertices by joints hashes them in the
  // file's, so digests are not compared either (palettes have no order).
  std::string baseline_vertex_order = "joints", current_vertex_order = "joints";
  bool order_differs() const {
    return vertex_orders_differ(baseline_vertex_order, current_vertex_order, digest_of_kernels);
  }
  // A mesh-LOD run recorded before a copy drawn whole digested as without
  // mesh LOD (Result::digest_scheme): its digest hashed every copy's level.
  bool scheme_differs = false;
  // The digests differ and say nothing: one of the reasons above.
  bool digest_not_comparable() const {
    return baseline_digest != current_digest && (arithmetic_differs() || order_differs() || scheme_differs);
  }
  bool digest_differs() const { return baseline_digest != current_digest && !digest_not_comparable(); }
  // What to say of the digests: "same", "CHANGED" or why they were not compared.
  std::string digest_note() const;
  // digest_not_comparable's reasons in a few words: "other arithmetic", "other
  // vertex order", "other digest scheme", joined by "and".
  std::string digest_not_compared_why() const;
  bool regressed() const;
  // The instructions per frame counted when the timings regressed and the
  // baseline holds a count (check_run.h); its verdict may excuse them.
  std::optional<WorkWitness> witness;
  // Marks every regressed metric excused (the witness's verdict).
  void excuse_timings();
};

// Why digests hashed in two vertex orders (Result::vertex_order) are not
// compared, in words: "the baseline hashed its vertices in the file's order,
// this run ordered by their joints (record the baseline again ...)".
std::string vertex_order_note(const std::string& baseline, const std::string& current);

// Judges one metric's samples: regressed when the median grew by more than the
// tolerance and by more than `floor` ms, and the U test says the shift is
// significant (or, with too few samples for the test, on the tolerance and the
// floor alone). `tested` is how many metrics are judged together, for
// adjust_holm; alone, p_adjusted is p.
MetricCheck check_metric(std::string metric, std::span<const double> baseline, std::span<const double> current,
                         const CheckOptions& options, double floor = 0);

// Holm's step-down correction over metrics tested at once: with m metrics, the
// k-th smallest p-value (from 0) is multiplied by m - k, made monotone, and
// capped at 1. Sets p_adjusted, significant and regressed again.
void adjust_holm(std::vector<MetricCheck>& metrics, const CheckOptions& options);

// Both results of the same run (run_match.h). When both pool
// kMannWhitneyMinSamples runs or more (pooled_runs.h), each metric compares the
// medians of their runs; otherwise the frames of each (of the median run). The
// floor is resolved against the baseline's median frame, and the metrics are
// Holm-corrected together. A metric either result lacks samples of is an
// std::invalid_argument: the caller chooses metrics both have.
CheckResult check_results(const Result& baseline, const Result& current, const CheckOptions& options);
// A metric's value as text, without its unit (m.value_unit): milliseconds to
// the microsecond, the calibrated ratio to four significant digits.
std::string metric_value_text(const MetricCheck& m, double value);

// What stdout shows: a line per regressed metric or changed counter (metric,
// both medians, their IQRs, the change and the p-value), or one summary line
// when nothing regressed.
std::string format_check(const CheckResult& result, const CheckOptions& options);

}  // namespace crowdprof
