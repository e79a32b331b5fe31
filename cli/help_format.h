// How every --help reads: one document per command (what it does, how it is
// called, its options under headings, examples), which help2man also turns
// into the command's man page (cmake/man_pages.cmake).
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

// The heading of the options every command takes: -h and the app's own.
inline const std::string kGeneralGroup = "General";

// One style of value names and defaults in every option, and the formatter
// below on the app and every command. Called once every command is declared.
void style_help(CLI::App& app);

// The formatter: the description first, then usage, the arguments, the
// groups (those holding a required option first, required options first in
// them), then "General" (-h and the global options a command also takes), the
// footer (examples). One blank line between sections, never two.
class CommandHelp : public CLI::Formatter {
 public:
  std::string make_help(const CLI::App* app, std::string name, CLI::AppFormatMode mode) const override;
  // A command in the top level's list: the first sentence of its description.
  std::string make_subcommand(const CLI::App* command) const override;

 private:
  std::string make_groups_of(const CLI::App* app) const;
  std::string make_section(const std::string& heading, const std::vector<const CLI::Option*>& options,
                           bool positional) const;
};
