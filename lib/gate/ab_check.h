// An A/B of two builds at the same moment (check --against): the base and the
// current build run the same bench in processes that take turns in ABBA groups
// (A B B A, then B A A B, ...), so a change of the machine's speed, which on a
// shared machine comes within seconds, falls on both builds of a group. Each
// group gives one ratio per metric (current over base, of the processes'
// medians), and the gate judges the ratios: their median against the
// tolerance, the Wilcoxon signed-rank test for significance (Holm-corrected
// over the metrics), and a floor in milliseconds.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "gate/paired_test.h"
#include "gate/regression.h"
#include "result/result.h"

namespace crowdprof {

// One measured process of one build, reduced to what the gate compares.
struct AbProcess {
  std::map<std::string, double> median_ms;  // per samples key ("frame_ms", "cpu_ms", categories)
  std::string digest;
  bool digest_cpu_vertices = true;      // Result::digest_cpu_vertices
  std::string vertex_order = "joints";  // Result::vertex_order
  RecordedCounters counters;
};

// A B B A or B A A B: two processes of each build, taken in turns.
struct AbGroup {
  AbProcess base[2], current[2];
  bool base_first = true;  // ABBA when true, BAAB otherwise
};

// From a bench result (bench --json, validated): the median of each samples
// key, the digest and the counters.
AbProcess ab_process(const Result& result);

// The A/B's defaults: the frame (wall clock) rather than CPU time, which counts
// worker threads spinning as work; pairing, not the metric, is what absorbs the
// machine's drift. A tolerance below the stored baseline's 7%: paired ratios
// move much less than processes do.
inline constexpr double kAbTolerance = 0.05;
inline constexpr size_t kAbGroups = 20;

struct AbOptions {
  std::vector<std::string> metrics = {"frame_ms"};
  double tolerance = kAbTolerance;
  double alpha = 0.05;
  Floor floor;  // resolved against the base's median frame
  double confidence = 0.95;
  bool compare_work = true;
};

struct AbMetric {
  std::string metric;  // samples key
  // The base's median over all its processes, and the current build's time
  // at the same moments: the base's times the paired change. So base, current
  // and change are one computation (current / base - 1 is the change), never a
  // change beside two medians that moved the other way.
  double base_ms = 0, current_ms = 0;
  // The current build's own median over its processes: the machine's drift
  // between processes in it, which the pairing removes (JSON only).
  double current_median_ms = 0;
  std::vector<double> ratios;  // per group, current over base
  MedianInterval change;       // of the ratios, minus 1: +0.1 is 10% slower
  SignedRank test;             // of the log ratios against zero
  double p_adjusted = 1;
  double floor_ms = 0;
  bool beyond_tolerance = false, beyond_floor = false, significant = false;
  bool regressed = false, improved = false;
};

struct AbWork {
  bool compared = false;
  bool equal = true;
  std::string base_digest, current_digest;
  // Set when the builds hashed their vertices in other orders (one from before
  // the bench ordered them by joints): the digests are not compared, and why.
  std::string digest_note;
  std::vector<CounterDifference> counters;  // base's first process against current's first, those that differ
  std::string inconsistent;                 // a build whose own processes did different work, if any
  std::string run_difference;               // set by the caller: the runs' settings differ (require_same_run's words)
};

struct AbResult {
  std::vector<AbMetric> metrics;
  AbWork work;
  bool regressed() const;
};

// Judges the groups. Needs at least one group; a metric missing from a
// process is a std::invalid_argument (the caller checks the results first).
AbResult judge_ab(const std::vector<AbGroup>& groups, const AbOptions& options);

}  // namespace crowdprof
