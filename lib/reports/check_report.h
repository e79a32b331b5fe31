// What a `check` writes and prints once it has run (gate/check_run.h): the
// result or new baseline (--json), the chart of the metric (--svg), the HTML
// report, the verdict as JUnit XML and Markdown, and the verdict's text on
// stdout (unless --quiet, or an output is stdout).
#pragma once

#include <ostream>

#include "gate/check_run.h"

namespace crowdprof {

// Writes the outputs `request` names for `outcome` and prints its text on
// `out`; returns the process's exit status (base/errors.h): 0, 1 when a metric
// is slower or the work changed, 130 when the check was interrupted.
int report_check(const CheckRun& request, const CheckOutcome& outcome, std::ostream& out);

// The whole command: run_check, each timed run writing --csv, then report_check.
int check_and_report(CheckRun request, std::ostream& out);

}  // namespace crowdprof
