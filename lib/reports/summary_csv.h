// The summary CSV (--summary-csv): one row per run, the numbers a script or a
// spreadsheet compares (as hyperfine's --export-csv and Google Benchmark's CSV
// are summaries): median, p95 and p99 of the frame and of its CPU time, and
// the rate each median gives.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "reports/profile_table.h"

namespace crowdprof {

// "mode,characters,threads,frames,frame_median_ms,frame_p95_ms,frame_p99_ms,
// frame_fps,cpu_median_ms,cpu_p95_ms,cpu_p99_ms,cpu_fps,partial"
std::string summary_csv_header();

// A field as CSV writes it: quoted when it holds a comma, a quote or a line
// break (a mode named with switches: master+lod-thresholds=0.3,0.2,0.1).
std::string csv_field(const std::string& text);

// The header, then a row per run in the order given.
void write_summary_csv(const std::vector<const Result*>& runs, std::ostream& out);

}  // namespace crowdprof
