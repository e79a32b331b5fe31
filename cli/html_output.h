// --html on the commands and `crowdprof report`: the page of
// reports/html_report.h, with the presets' colours, written to a file.
#pragma once

#include <string>

#include "reports/html_report.h"

// Writes the report to `path` (UsageError naming it when it cannot). The
// presets of base/modes.h keep their colours in every report.
void write_html_report(const std::string& path, crowdprof::HtmlReportInput input);


// The bytes of a PNG to show in a report; InputError naming `path` when it is
// missing or not a PNG.
std::string read_png(const std::string& path);
