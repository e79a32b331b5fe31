// A finished run as the BGE's profile overlay (text) and one CSV row per frame
// (docs/formats.md); the JSON summary is the result's (result/result_codec.h).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "result/result.h"

namespace crowdprof {

// The BGE overlay for the median frame, then a line describing the run.
std::string format_profile(const Result& report);
// The culling audit's line under the table: per box, false and missed culls
// (copy-frames) and its slack.
std::string format_culling_audit(const CullingAudit& audit);
// The drawn error's line under the table, in millimetres (model units x 1000).
std::string format_drawn_error(const DrawnErrorRecord& error);

// Header, then one row per frame (docs/formats.md).
void write_csv(const Result& report, std::ostream& out);
std::string csv_header();

}  // namespace crowdprof
