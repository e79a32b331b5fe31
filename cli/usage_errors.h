// Command-line mistakes as one line that says what to do: the nearest command
// or option for a typo, the option's words for a value that is not a number,
// what to give for a missing argument, and the command's own --help.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

// The candidate closest to `typed` when it is close enough to be a typo (a
// letter or two wrong, swapped, missing or extra; or a unique prefix), else "".
std::string nearest_name(std::string_view typed, const std::vector<std::string>& candidates);

// The app's commands in the order they were added, and as "info, gen, ...".
std::vector<std::string> command_names(const CLI::App& app);
std::string command_list(const CLI::App& app);

// The word of argv that names the command (skipping the app's own options
// and their values), or "" when there is none.
std::string command_word(const CLI::App& app, const std::vector<std::string>& args);

// The line for a parse error of `app` (without "crowdprof: "), naming the
// command's own --help: e.g. "bench: unknown option --frame; did you mean
// --frames? (see crowdprof bench --help)".
std::string describe_parse_error(CLI::App& app, const CLI::ParseError& error);

namespace crowdprof {

// Prints one line on stderr for the exception being handled ("crowdprof: ...")
// and returns its exit status (base/errors.h: 2 usage, 3 bad input, 4 failed
// run); a measured run's failure (gate/processes.h) was reported by the run.
// Call only inside a catch block.
int report_current_exception();

// The command being run ("bench"), so that a bad option value is reported as
// "bench: --fps 'x': ... (see crowdprof bench --help)".
void set_current_command(const std::string& command);

}  // namespace crowdprof
