// The documents crowdprof writes with --json, read into types so that the
// reports take records, never JSON: a bench result (bench, check), a
// comparison (compare: its runs and its sweep) or a capacity search (capacity:
// its outcome per mode, the runs at each mode's capacity and every point it
// tried); and diff's verdicts (DiffRecord). Bench results themselves are
// result_codec.h's.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "result/advice_record.h"
#include "result/result.h"
#include "result/sweep_axis.h"

namespace crowdprof {

// A median frame time at one point of a sweep (compare --sweep, or several
// results of different crowd sizes).
struct SweepPoint {
  std::string mode;
  size_t x = 0;  // on the axis: copies, or passes
  double frame_median_ms = 0;
};

// One mode at one point in a comparison (its summary row, or a sweep row):
// medians over the frames of the frame and each category, the speedup over
// the first mode of the same size and passes, the digest and the median
// frame's counters. A capacity search's sweep rows hold mode, characters and
// frame_ms only.
struct ModeMedians {
  std::string mode;
  size_t characters = 0;
  uint32_t passes = 1;
  int threads = 1;
  double frame_ms = 0;
  std::array<double, kCategoryCount> category_ms{};
  double speedup = 0;  // the first mode's frame_ms over this one's (same size and passes)
  std::string digest;
  Counters counters;  // of the median frame
  size_t on(SweepAxis axis) const { return axis == SweepAxis::Passes ? passes : characters; }
};

// One crowd size measured for one mode.
struct CapacityPoint {
  size_t n = 0;
  double median_ms = 0;  // the metric's median over the point's frames: the search reads this
  double p95_ms = 0, p99_ms = 0, min_ms = 0, max_ms = 0;
  double frame_median_ms = 0;  // the whole frame's median (the same as median_ms for the frame metric)
  size_t frames = 0;
  size_t round = 0;      // 1 for the first round of the run
  bool partial = false;  // measured in a round cut short by ^C: shown, never used by the search
  std::string digest;
};

// What a capacity search found (capacity --json): its rule, and per mode the
// points it measured and the boundary they give.
struct CapacityRecord {
  double budget_ms = 0;
  std::string metric;  // "frame" or a category
  size_t start = 0;
  double precision = 0;  // the search stops when over - fits <= max(1, precision x fits)
  size_t frames_per_point = 0, warmup = 0;
  struct Row {
    std::string mode;
    size_t threads = 0;
    size_t cap = 0;
    bool capped = false;                // the cap fits
    bool non_monotonic = false;         // a larger crowd was more than 10% faster than a smaller one
    std::optional<CapacityPoint> fit;   // the largest crowd within the budget (none: not even the smallest)
    std::optional<CapacityPoint> over;  // the smallest crowd found over it (none: the cap fits)
    std::vector<CapacityPoint> points;  // in the order measured
  };
  std::vector<Row> rows;
};

struct ResultDocument {
  std::string kind = "bench";        // "bench" (bench, check), "compare", "capacity" or "advise"
  std::vector<Result> runs;          // the bench result; a comparison's runs; a search's runs at each capacity
  std::vector<ModeMedians> summary;  // compare: one row per run
  std::vector<ModeMedians> sweep;    // compare --sweep, or every point a capacity search measured whole
  SweepAxis sweep_axis = SweepAxis::Characters;
  size_t block_frames = 10;                // compare: frames per block of the interleaving
  bool partial = false;                    // stopped early (^C)
  std::optional<CapacityRecord> capacity;  // kind "capacity"
  // kind "advise": the plan; runs holds the start's and the final configuration's runs.
  std::optional<AdviceRecord> advice;
  // capacity: the first run measured, whose build, environment and scene head
  // the document (none read back: then the first of `runs` heads it).
  std::optional<Result> described;
};

// What `crowdprof diff --json` writes: per pair of results (by mode and crowd
// size) each metric's medians, change and verdict, the counters that differ
// and the digests (gate/diff.h makes it).
struct DiffRecord {
  struct Metric {
    std::string metric, unit = "ms", verdict;  // verdict: "same", "SLOWER", "faster" or "not tested"
    double a_median = 0, b_median = 0, floor_ms = 0;
    std::optional<double> change, p, p_holm;  // none: not finite, or not tested
    bool tested = false;
  };
  struct Counter {
    std::string name;
    std::optional<uint64_t> a, b;  // none: missing in B (and so not compared)
  };
  struct Pair {
    std::string mode;
    size_t characters = 0;
    bool regressed = false;
    std::vector<std::string> notes;
    std::vector<Metric> metrics;
    std::vector<Counter> counters;
    std::string digest_a, digest_b, digest_note;  // the note only when the digests are not comparable
  };
  std::string version, commit;  // of the crowdprof that judged
  std::string a, b;             // the files, as named
  double tolerance = 0, alpha = 0;
  std::vector<Pair> pairs;
  bool regressed = false;
};

// diff's document, every field checked (InputError naming `path` and the field).
DiffRecord diff_record_from_json(const nlohmann::json& doc, const std::string& path);
nlohmann::json diff_record_to_json(const DiffRecord& diff);

// The document `doc` (read from `path`, which errors name), every field
// checked before use. InputError for another kind of document (a diff, a
// check's verdict) or a field of the wrong type or range, as result_from_json
// for each run.
ResultDocument result_document_from_json(const nlohmann::json& doc, const std::string& path);
// read_json_file, then result_document_from_json.
ResultDocument read_result_document(const std::string& path);

// The document as crowdprof writes it (docs/formats.md): a bench result's own
// JSON; a comparison's header (from its first run), block_frames, modes,
// summary, sweep (sweep_axis when it is not characters) and runs; a capacity
// search's header (without the crowd's size), its rule, per mode its points
// and boundary, the sweep of whole points and the runs at each capacity.
nlohmann::json result_document_to_json(const ResultDocument& document);

}  // namespace crowdprof
