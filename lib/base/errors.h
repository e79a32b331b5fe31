// Errors that reach the user. Every command turns these into one line on stderr
// and a documented exit status (see docs/errors.md).
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace crowdprof {

enum ExitCode : int {
  kExitOk = 0,
  kExitRegression = 1,  // `check`: a metric regressed
  kExitUsage = 2,       // bad command line
  kExitBadInput = 3,    // a file that cannot be used (unreadable, malformed, unsupported)
  kExitRuntime = 4,     // the run itself failed (GL error, out of memory at run time)
};

// Text that names settings, each name marked as {name}: the library says a
// name as results and scene files spell it ("share_quantum"), cli/ as the
// option the user types ("--share-quantum"), so that lib/ never spells its
// command line. Only {lower_case_words} are names; other braces are text.
class SettingText {
 public:
  using Speller = std::function<std::string(std::string_view setting)>;
  SettingText() = default;
  SettingText(std::string marked) : marked_(std::move(marked)) {}  // NOLINT: from any built string
  SettingText(const char* marked) : marked_(marked) {}             // NOLINT
  bool empty() const { return marked_.empty(); }
  const std::string& marked() const { return marked_; }
  // The names as the library spells them (the setting's own name).
  std::string str() const;
  // Each name as `spell` says it.
  std::string str(const Speller& spell) const;

 private:
  std::string marked_;
};

// Mixed into an error whose text names settings: a literal prefix (a file's
// name, never parsed for names) and the marked text; what() holds the
// library's spelling.
class NamesSettings {
 public:
  NamesSettings(std::string prefix, SettingText text) : prefix_(std::move(prefix)), text_(std::move(text)) {}
  virtual ~NamesSettings() = default;
  std::string spelled(const SettingText::Speller& spell) const { return prefix_ + text_.str(spell); }
  // The whole text marked, for a message that quotes this one (the prefix as
  // it is: only for texts the program makes, never a file's name).
  std::string marked() const { return prefix_ + text_.marked(); }

 private:
  std::string prefix_;
  SettingText text_;
};

// A problem with an input file: `what()` is "<file>: <problem>".
class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, const std::string& problem) : std::runtime_error(file + ": " + problem) {}
};

// A problem with the command line or with options that do not fit the input.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A UsageError about settings that cannot run together or values that do not fit.
// `literal` (a character's name, a value read from a file) is never parsed for names.
class SettingsUsageError : public UsageError, public NamesSettings {
 public:
  explicit SettingsUsageError(const SettingText& text, const std::string& literal = "")
      : UsageError(literal + text.str()), NamesSettings(literal, text) {}
};

// An InputError whose problem names settings (e.g. the option that would fix it).
class SettingsInputError : public InputError, public NamesSettings {
 public:
  SettingsInputError(const std::string& file, const std::string& literal, const SettingText& problem)
      : InputError(file, literal + problem.str()), NamesSettings(file + ": " + literal, problem) {}
};

// A bad value of one setting of a run (frame/run_spec.h), said by the
// setting's name as results and scene files spell it ("characters"); cli/
// names the option the user typed instead (-n/--characters).
struct SettingError : UsageError {
  SettingError(std::string setting_name, std::string text, const std::string& problem)
      : UsageError(setting_name + " '" + text + "': " + problem),
        name(std::move(setting_name)),
        value(std::move(text)),
        why(problem) {}
  std::string name, value, why;
};

}  // namespace crowdprof
