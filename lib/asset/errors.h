// Errors that reach the user. Every command turns these into one line on stderr
// and a documented exit status (see docs/errors.md).
#pragma once

#include <stdexcept>
#include <string>

namespace crowdprof {

enum ExitCode : int {
  kExitOk = 0,
  kExitRegression = 1,  // `check`: a metric regressed
  kExitUsage = 2,       // bad command line
  kExitBadInput = 3,    // a file that cannot be used (unreadable, malformed, unsupported)
  kExitRuntime = 4,     // the run itself failed (GL error, out of memory at run time)
};

// A problem with an input file: `what()` is "<file>: <problem>".
class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, const std::string& problem)
      : std::runtime_error(file + ": " + problem) {}
};

// A problem with the command line or with options that do not fit the input.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A bad value of one setting of a run (frame/run_spec.h), said by the
// setting's name as results and scene files spell it ("characters"); cli/
// names the option the user typed instead (-n/--characters).
struct SettingError : UsageError {
  SettingError(std::string setting_name, std::string text, const std::string& problem)
      : UsageError(setting_name + " '" + text + "': " + problem), name(std::move(setting_name)),
        value(std::move(text)), why(problem) {}
  std::string name, value, why;
};

}  // namespace crowdprof
