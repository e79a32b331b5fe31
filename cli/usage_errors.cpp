#include "cli/usage_errors.h"

#include <algorithm>
#include <iostream>
#include <map>
#include <new>

#include "base/errors.h"
#include "cli/bench_options.h"
#include "gate/processes.h"

namespace {

// Edits to turn `a` into `b`: letters inserted, deleted, replaced, or two
// neighbours swapped (optimal string alignment distance).
size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i)
    for (size_t j = 1; j <= b.size(); ++j) {
      size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

std::string help_hint(const CLI::App* command) {
  return command && command->get_parent() ? " (see crowdprof " + command->get_name() + " --help)"
                                          : " (see crowdprof --help)";
}

// The command being parsed when the error came: the last one named, or the app.
CLI::App* current_command(CLI::App& app) {
  std::vector<CLI::App*> parsed = app.get_subcommands();
  return parsed.empty() ? &app : parsed.back();
}

// Every spelling of every option `command` takes, global ones included.
std::vector<std::string> option_names(const CLI::App& command) {
  std::vector<std::string> names;
  for (const CLI::App* app = &command; app; app = app->get_parent())
    for (const CLI::Option* option : app->get_options()) {
      for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
      for (const std::string& name : option->get_snames()) names.push_back("-" + name);
    }
  return names;
}

// "-n/--characters": the option's names, as its --help shows them.
std::string spelled(const CLI::Option& option) {
  std::string names;
  for (const std::string& name : option.get_snames()) names += (names.empty() ? "-" : "/-") + name;
  for (const std::string& name : option.get_lnames()) names += (names.empty() ? "--" : "/--") + name;
  return names.empty() ? option.get_name() : names;
}

const CLI::Option* find_option(const CLI::App& command, const std::string& name) {
  for (const CLI::App* app = &command; app; app = app->get_parent())
    for (const CLI::Option* option : app->get_options())
      if (option->check_name(name)) return option;
  return nullptr;
}

std::string expected_value(const CLI::Option& option) {
  std::string type = option.get_type_name();
  if (type == "INT") return "a whole number";
  if (type == "UINT" || type == "N") return "a whole number, 0 or more";
  if (type == "FLOAT" || type == "FLOAT:FLOAT") return "a number";
  if (type == "MS") return "a number of milliseconds";
  if (type == "PX") return "a number of pixels";
  if (type == "SECONDS") return "a number of seconds";
  return "a value";
}

std::string unexpected(CLI::App& app, CLI::App& command) {
  std::vector<std::string> extras = app.remaining(true);
  // The first option (the rest are likely its values); else the first word.
  auto option =
      std::find_if(extras.begin(), extras.end(), [](const std::string& e) { return e.size() > 1 && e[0] == '-'; });
  if (option != extras.end()) {
    std::string typed = option->substr(0, option->find('='));
    std::string near = nearest_name(typed, option_names(command));
    return "unknown option " + typed + (near.empty() ? "" : "; did you mean " + near + "?");
  }
  if (extras.empty()) return "unexpected arguments";
  std::string word = extras.front();
  if (command.get_parent() == nullptr) return "unknown command '" + word + "'";
  return "unexpected argument '" + word + "' (" + command.get_name() + " takes " +
         (command.get_options([](const CLI::Option* o) { return o->get_positional(); }).empty()
              ? std::string("no files")
              : std::string("fewer files")) +
         ")";
}

std::string missing(const CLI::App& command, const std::string& message) {
  for (const CLI::Option* option : command.get_options()) {
    if (!option->get_required() || option->count() > 0) continue;
    if (option->get_positional()) {
      std::string name = option->get_name();
      if (name == "file")
        return "no file given: name a character (.glb or .gltf) or a scene file (.json) after " + command.get_name();
      std::string what = option->get_description().substr(0, option->get_description().find(" ("));
      return "no " + name + " given: " + what;
    }
    return spelled(*option) + " is required: " + option->get_description();
  }
  return message;
}

}  // namespace

std::string nearest_name(std::string_view typed, const std::vector<std::string>& candidates) {
  std::string best;
  size_t best_distance = 0;
  bool tie = false;
  for (const std::string& candidate : candidates) {
    size_t distance = edit_distance(typed, candidate);
    if (best.empty() || distance < best_distance) {
      best = candidate, best_distance = distance, tie = false;
    } else if (distance == best_distance && candidate != best) {
      tie = true;
    }
  }
  std::string_view letters = typed.substr(
      typed.find_first_not_of('-') == std::string_view::npos ? typed.size() : typed.find_first_not_of('-'));
  size_t allowed = letters.size() <= 3 ? 1 : letters.size() <= 8 ? 2 : 3;
  if (!best.empty() && !tie && best_distance <= allowed) return best;
  // A unique prefix: --fram for --frames.
  std::string prefixed;
  for (const std::string& candidate : candidates)
    if (letters.size() >= 3 && candidate.size() > typed.size() && candidate.compare(0, typed.size(), typed) == 0) {
      if (!prefixed.empty() && prefixed != candidate) return "";
      prefixed = candidate;
    }
  return prefixed;
}

std::vector<std::string> command_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* command : app.get_subcommands(std::function<bool(const CLI::App*)>{}))
    names.push_back(command->get_name());
  return names;
}

std::string command_list(const CLI::App& app) {
  std::string list;
  for (const std::string& name : command_names(app)) list += (list.empty() ? "" : ", ") + name;
  return list;
}

std::string command_word(const CLI::App& app, const std::vector<std::string>& args) {
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (arg == "--") return i + 1 < args.size() ? args[i + 1] : "";
    if (arg.size() > 1 && arg[0] == '-') {
      // A global option's value is not the command: --simd AVX2 bench ...
      const CLI::Option* option = arg.find('=') == std::string::npos ? find_option(app, arg) : nullptr;
      if (option && option->get_type_size_max() > 0 && option->get_items_expected_max() > 0) ++i;
      continue;
    }
    return arg;
  }
  return "";
}

std::string describe_parse_error(CLI::App& app, const CLI::ParseError& error) {
  CLI::App& command = *current_command(app);
  std::string prefix = command.get_parent() ? command.get_name() + ": " : "";
  std::string message = error.what();
  std::string line;
  if (dynamic_cast<const CLI::ExtrasError*>(&error)) {
    line = unexpected(app, command);
  } else if (dynamic_cast<const CLI::ConversionError*>(&error) && message.rfind("Could not convert: ", 0) == 0) {
    // "Could not convert: --characters = abc"
    size_t equals = message.find(" = ");
    std::string name = message.substr(19, equals == std::string::npos ? std::string::npos : equals - 19);
    std::string value = equals == std::string::npos ? "" : message.substr(equals + 3);
    const CLI::Option* option = find_option(command, name);
    line = option ? spelled(*option) + " '" + value + "': expected " + expected_value(*option) : message;
  } else if (dynamic_cast<const CLI::RequiredError*>(&error)) {
    line = missing(command, message);
  } else if (dynamic_cast<const CLI::ArgumentMismatch*>(&error)) {
    // "--frames: 1 required INT missing": a value was not given; "--frames: At
    // Most 1 required but received 2": the option was given twice.
    std::string name = message.substr(0, message.find(':'));
    const CLI::Option* option = find_option(command, name);
    if (!option)
      line = message;
    else if (message.find("received") != std::string::npos)
      line = spelled(*option) + " was given more than once; it takes one value";
    else
      line = spelled(*option) + " needs a value" +
             (option->get_type_name().empty() ? std::string()
                                              : " (" + spelled(*option) + " " + option->get_type_name() + ")");
  } else {
    line = message;
  }
  return prefix + line + help_hint(&command);
}

namespace crowdprof {

namespace {
std::string current_command;
}  // namespace

void set_current_command(const std::string& command) {
  current_command = command;
}

namespace {
// An error's text with the settings it names spelled as the options the user typed.
std::string as_typed(const std::exception& e) {
  if (const auto* names = dynamic_cast<const NamesSettings*>(&e))
    return names->spelled([](std::string_view setting) { return option_name(std::string(setting)); });
  return e.what();
}
}  // namespace

int report_current_exception() {
  try {
    throw;
  } catch (const ChildFailed& e) {
    return e.status;  // the child said why
  } catch (const InputError& e) {
    std::cerr << "crowdprof: " << as_typed(e) << "\n";
    return kExitBadInput;
  } catch (const SettingError& e) {
    // lib/ names the setting; the user typed its option.
    std::cerr << "crowdprof: " << (current_command.empty() ? "" : current_command + ": ") << option_name(e.name) << " '"
              << e.value << "': " << e.why
              << (current_command.empty() ? "" : " (see crowdprof " + current_command + " --help)") << "\n";
    return kExitUsage;
  } catch (const UsageError& e) {
    std::cerr << "crowdprof: " << as_typed(e) << "\n";
    return kExitUsage;
  } catch (const std::bad_alloc&) {
    std::cerr << "crowdprof: out of memory\n";
    return kExitRuntime;
  } catch (const std::exception& e) {
    std::cerr << "crowdprof: " << as_typed(e) << "\n";
    return kExitRuntime;
  }
}

}  // namespace crowdprof
