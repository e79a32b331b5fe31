#include "cli/help_format.h"

#include <algorithm>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "cli/bench_options.h"
#include "frame/run_spec.h"

namespace {

// One style in every --help: a value named by what it is (N, NUMBER, VALUE;
// never CLI11's "INT:INT in [0 - 10]") and its default after the text,
// "(default: X)", as the settings and switches print theirs.
void one_style_of_values(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    if (option->get_type_size() == 0) continue;  // a flag
    std::string value = option->get_type_name();
    value = value.substr(0, value.find(':'));
    if (value == "INT" || value == "UINT")
      value = "N";
    else if (value == "FLOAT")
      value = "NUMBER";
    else if (value == "TEXT") {
      // Files: what a command writes, and the files it reads besides its positionals.
      bool file = option->get_group() == "Outputs" || !option->nonpositional();  // every positional is a file
      for (const char* name : {"--output", "--baseline", "--result", "--against", "--screenshot"})
        file |= option->check_lname(std::string(name).substr(2));
      value = file ? "FILE" : "VALUE";
    }
    option->type_name(value);
    std::string fallback = option->get_default_str();
    if (fallback.size() >= 2 && fallback.front() == '[' && fallback.back() == ']')
      fallback = fallback.substr(1, fallback.size() - 2);
    if (!fallback.empty() && option->get_description().find("(default:") == std::string::npos)
      option->description(option->get_description() + " (default: " + fallback + ")");
    option->default_str("");
  }
  for (CLI::App* command : app.get_subcommands({})) one_style_of_values(*command);
}

// `text` broken into lines of at most `width` characters, at spaces.
std::string wrapped(const std::string& text, size_t width) {
  std::istringstream words(text);
  std::string out, line;
  for (std::string word; words >> word;) {
    if (!line.empty() && line.size() + 1 + word.size() > width) {
      out += line + "\n";
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
  }
  return out + line;
}

bool is_help(const CLI::App* app, const CLI::Option* option) {
  return option == app->get_help_ptr() || option == app->get_help_all_ptr();
}

}  // namespace

void style_help(CLI::App& app) {
  one_style_of_values(app);
  auto formatter = std::make_shared<CommandHelp>();
  formatter->label("Positionals", "Arguments");
  formatter->label("REQUIRED", "(required)");
  app.formatter(formatter);
  for (CLI::App* command : app.get_subcommands({})) command->formatter(formatter);
}

std::string CommandHelp::make_section(const std::string& heading, const std::vector<const CLI::Option*>& options,
                                      bool positional) const {
  if (options.empty()) return {};
  std::string out = heading + ":\n";
  for (const CLI::Option* option : options) out += make_option(option, positional);
  return out;
}

std::string CommandHelp::make_groups_of(const CLI::App* app) const {
  // The top level's options are all general: its default group is that section.
  const std::string general_group = app->get_parent() ? kGeneralGroup : "Options";
  std::vector<std::string> groups;  // as declared, then as listed
  for (const std::string& group : app->get_groups())
    if (!group.empty() && group != general_group) groups.push_back(group);
  auto options_of = [&](const std::string& group) {
    std::vector<const CLI::Option*> options = app->get_options([&](const CLI::Option* option) {
      return option->get_group() == group && option->nonpositional() && !is_help(app, option);
    });
    std::stable_partition(options.begin(), options.end(), [](const CLI::Option* o) { return o->get_required(); });
    return options;
  };
  // What the command is for first: a group holding a required option, then
  // the command's own, then the settings of the run it shares with the other
  // commands that bench, then the files it writes.
  auto rank = [&](const std::string& group) {
    std::vector<const CLI::Option*> options = options_of(group);
    if (!options.empty() && options.front()->get_required()) return 0;
    if (group == kOutputsGroup) return 3;
    if (group == kModeSwitchesGroup || group == kMeasurementGroup) return 2;
    for (const crowdprof::SettingSpec& setting : crowdprof::setting_table())
      if (setting.group == group) return 2;
    return 1;
  };
  std::stable_sort(groups.begin(), groups.end(),
                   [&](const std::string& a, const std::string& b) { return rank(a) < rank(b); });
  std::vector<std::string> sections;
  for (const std::string& group : groups) sections.push_back(make_section(group, options_of(group), false));
  // General: -h, and the global options (the app's) a command also takes.
  std::vector<const CLI::Option*> general = options_of(general_group);
  if (app->get_help_ptr()) general.insert(general.begin(), app->get_help_ptr());
  if (const CLI::App* parent = app->get_parent())
    for (const CLI::Option* option : parent->get_options())
      if (!is_help(parent, option) && option->get_lnames() != std::vector<std::string>{"version"})
        general.push_back(option);
  sections.push_back(make_section(general_group, general, false));
  std::string out;
  for (const std::string& section : sections)
    if (!section.empty()) out += (out.empty() ? "" : "\n") + section;
  return out;
}

std::string CommandHelp::make_subcommand(const CLI::App* command) const {
  std::string description = command->get_description();
  description = description.substr(0, description.find(". "));
  std::stringstream out;
  CLI::detail::format_help(out, command->get_name(), description, column_width_);
  return out.str();
}

std::string CommandHelp::make_help(const CLI::App* app, std::string name, CLI::AppFormatMode mode) const {
  if (mode == CLI::AppFormatMode::Sub) return make_expanded(app);
  std::vector<std::string> sections;
  if (!app->get_description().empty()) sections.push_back(wrapped(app->get_description(), 100) + "\n");
  sections.push_back(make_usage(app, name));
  std::vector<const CLI::Option*> positionals =
      app->get_options([](const CLI::Option* option) { return option->get_positional(); });
  sections.push_back(make_section(get_label("Positionals"), positionals, true));
  sections.push_back(make_groups_of(app));
  std::string commands = make_subcommands(app, mode);  // the top level's: "\nSubcommands:\n..."
  if (!commands.empty() && commands.front() == '\n') commands.erase(0, 1);
  sections.push_back(commands);
  sections.push_back(make_footer(app));
  std::string out;
  for (const std::string& section : sections)
    if (!section.empty()) out += (out.empty() ? "" : "\n") + section;
  return out;
}
