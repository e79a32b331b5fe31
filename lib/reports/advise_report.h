// How `crowdprof advise` reports its plan (docs/advise.md): the text for
// stdout and one CSV row per configuration measured. The JSON is the typed
// document's (result_document.h, kind "advise"); the page is html_report's.
#pragma once

#include <ostream>
#include <string>

#include "result/advice_record.h"
#include "result/result.h"

namespace crowdprof {

// The plan: the question and the host, the start, each step's configurations
// (the base, then each lever: metric median [interval], saved [interval],
// drawn error in px, mm and % of height, the capacity it would give
// (estimated), its verdict), the outcome, the final options and the
// capacities capacity's search found. `start` describes the scene and host
// (none: not said).
std::string format_advice(const AdviceRecord& advice, const Result* start);

// step, lever, changes, verdict, the metric's median and interval, the
// frame's median, the saving's median and interval, error px, mm, % of height,
// capacity_estimate, digest: one row per configuration of every step.
void write_advice_csv(const AdviceRecord& advice, std::ostream& out);

}  // namespace crowdprof
