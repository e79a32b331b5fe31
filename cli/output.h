// What the commands that run benches share about output: progress on a
// terminal, and writing result files with one clear error.
#pragma once

#include <cstddef>
#include <functional>
#include <ostream>
#include <initializer_list>
#include <string>

#include "result/result.h"

// Progress on stderr once a run has taken a second, only when a person watches
// (stderr is a terminal) and not --quiet; an empty function otherwise. One line,
// redrawn in place: "crowdprof: <what> 120/1130 frames, 4 s left", where `what`
// names the mode and sweep point; erased when the run ends.
std::function<void(size_t, size_t)> terminal_progress(bool quiet, const std::string& what = "frame");

// Whether a command prints its text on stdout: not with --quiet, nor when one
// of its output files is stdout ("--csv -", /dev/stdout), which then holds
// that file alone.
bool prints_on_stdout(bool quiet, std::initializer_list<std::string> outputs);

// Writes `path` with `body`; UsageError naming the file when it cannot (see
// base/output_file.h, whose require_writable checks paths before a run).
void write_text(const std::string& path, const std::string& what, const std::function<void(std::ostream&)>& body);

// A result as bench --json writes it, its scene file stored relative to `path`
// (result/result_codec.h), through write_text.
void write_result_file(const std::string& path, const std::string& what, const crowdprof::Result& result);
