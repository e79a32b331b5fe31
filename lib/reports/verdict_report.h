// A gate's verdict as a table (one row per metric, one for the work), and its
// reporters: the terminal's text, JUnit XML (one test case per metric and one
// for the work; CI systems show a failure's message) and Markdown (a job
// summary or a pull-request comment). Both gates fill it: the A/B of two
// builds (ab_check.h) and the stored baseline (regression.h).
#pragma once

#include <string>
#include <vector>

#include "gate/ab_check.h"
#include "gate/regression.h"
#include "result/result.h"

namespace crowdprof {

struct GateRow {
  std::string metric;                  // as users name it: "frame", "cpu", "animations_ms"
  double base_ms = 0, current_ms = 0;  // in `unit`
  std::string unit = "ms";             // or "instructions" (per frame)
  double change = 0;                   // a fraction: +0.1 is 10% slower
  bool has_interval = false;
  double change_low = 0, change_high = 0;  // the confidence interval of the change
  double p = 1;                            // after Holm's correction
  bool has_p = true;                       // false for a count, which no test judges
  std::string verdict;                     // "slower", "faster", "no change"
  bool failed = false;
  std::string why;  // for a failure: the rule it broke
};

struct GateTable {
  // The check ("crowdprof check", "crowdprof check --against") and its scene
  // (verdict_scene): together they name the JUnit suite and the Markdown
  // title, so that two gates in one pipeline read apart.
  std::string command = "crowdprof check";
  std::string scene;
  double seconds = 0;  // the check's wall time: JUnit's `time`
  std::string title;   // what was compared (lines)
  std::vector<GateRow> metrics;
  bool work_compared = false, work_equal = true;
  std::string work_detail;  // the digests, or what differs
  std::string reproduce;    // the command that reproduces the check
  bool failed() const;
  // "crowdprof check (thesis.json × 160, threaded)": the command alone without a scene.
  std::string name() const;
};

// The scene a gate ran, on one line: its file's name (the scene file's, else
// the character's), the crowd and the mode, "thesis.json × 160, threaded".
std::string verdict_scene(const Result& result);

GateTable ab_verdict_table(const AbResult& result, const AbOptions& options);
GateTable check_verdict_table(const CheckResult& result, const CheckOptions& options);

// Columns: metric, base, current, change, confidence interval, p, verdict;
// then the work's line and, on a failure, the command that reproduces it.
std::string verdict_text(const GateTable& table);
// JUnit: one suite named table.name(), with the check's seconds as `time` on
// it, on <testsuites> and on each case (the cases are judged from the same
// runs); every attribute one line, what takes lines in elements' text.
std::string verdict_junit(const GateTable& table);
std::string verdict_markdown(const GateTable& table);

}  // namespace crowdprof
