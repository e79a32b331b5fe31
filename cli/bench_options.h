// The options `bench` shares with the commands that run benches (compare,
// check): the scene, the mode and its switches, the clock.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "asset/character.h"
#include "frame/bench_setup.h"
#include "frame/crowd_bench.h"
#include "frame/run_spec.h"
#include "base/output_file.h"
#include "render/bench_rendering.h"
#include "scene/scene_file.h"

#include <memory>

// The output options, each declared once: its option and what its file holds
// come from one table (cli/bench_options.cpp), the help from the command that
// opts into it. The table's order is the order the files are checked in.
// PngImage and HtmlPage are -o,--output: the file that render and report write.
enum class OutputOption {
  Csv,
  Json,
  Trace,
  Screenshot,
  Html,
  Svg,
  SummaryCsv,
  GbenchJson,
  Junit,
  Markdown,
  PngImage,
  HtmlPage,
  SceneOut
};

// The outputs a command opts into (hyperfine's ExportManager): declared on the
// command once each, then, as the command line gave them, the files that are
// checked before any work and that say whether stdout stays free
// (crowdprof::OutputFiles).
class DeclaredOutputs {
 public:
  // Declares `output` on `cmd` with the command's `help`, its path in `path`,
  // under Outputs, its value named FILE.
  CLI::Option* declare(CLI::App& cmd, OutputOption output, std::string& path, const std::string& help);
  crowdprof::OutputFiles files() const;

 private:
  std::vector<std::pair<OutputOption, const std::string*>> declared_;
};

// The options `bench` shares with compare, check, capacity and render: every
// setting and switch of a run (frame/run_spec.h, base/switch_table.h) as the
// command line gave it, then the run they resolve to.
struct BenchCliOptions {
  // Text of every setting and switch option, by name; only those the command
  // line gave make its layer (command_line_layer).
  std::map<std::string, std::string> typed;
  bool allow_static = false;
  // A command's own defaults over the table's (render draws with auto).
  crowdprof::SpecLayer defaults{crowdprof::SpecLayer::Source::Defaults, "", {}};
  crowdprof::RunSpec spec;  // resolved by resolve_bench_spec
  bool quiet = false;
  std::string csv, json, trace;
  std::string screenshot;       // bench: the last frame as a PNG
  std::string html;             // the HTML report of the run (docs/report.md)
  DeclaredOutputs outputs;      // the command's output options, bench's and its own
  CLI::App* command = nullptr;  // the command the options were parsed by
};

// The settings the command line gave, as a layer.
crowdprof::SpecLayer command_line_layer(const BenchCliOptions& options);

// Resolves options.spec from the command's defaults, the scene file, the
// baseline's layer (when re-running one) and the command line, in that order.
void resolve_bench_spec(BenchCliOptions& options, const crowdprof::SpecLayer* baseline = nullptr);

// The command-line spelling of a setting or switch: "-n/--characters",
// "--share-quantum".
std::string option_name(const std::string& setting);
// A library text that names settings, each as the option the user types
// (lib/ spells "share_quantum", the command line "--share-quantum").
std::string as_options(const crowdprof::SettingText& text);

// The headings --help lists options under: the settings' own (Crowd, Run,
// View, GPU; frame/run_spec.h), then these.
inline const std::string kModeSwitchesGroup = "Mode switches";
inline const std::string kOutputsGroup = "Outputs";
inline const std::string kGateGroup = "Gate";
inline const std::string kMeasurementGroup = "Measurement";

// Puts the options named (those the command has) under `group` in --help.
void group_options(CLI::App& cmd, const std::string& group, std::initializer_list<const char*> names);

// The output options every command that runs a bench may have: under Outputs.
void group_outputs(CLI::App& cmd);

void add_bench_options(CLI::App& cmd, BenchCliOptions& options);

// UsageError, before any work, when one of the command's declared outputs
// cannot be written, is the character file or a character of the scene (or one
// of the command's `inputs`), or when two of them share a path.
void require_writable_outputs(const BenchCliOptions& options, const std::vector<crowdprof::NamedPath>& inputs = {});

// Opens --backend at --resolution for the config's crowd and points
// config.renderer at its renderer (left null for none). When auto finds no GL,
// says so on stderr and goes on without.
crowdprof::BenchRendering open_bench_rendering(const BenchCliOptions& options, const crowdprof::BenchScene& scene,
                                               crowdprof::BenchConfig& config);

// --scene-out: the configuration that ran, as a scene file bench runs as is
// (run_scene_file); a note on stderr names what the scene cannot hold.
void write_scene_out(const std::string& path, const crowdprof::RunSpec& spec, const crowdprof::BenchScene& scene,
                     const crowdprof::BenchConfig& config);

// A comma-separated option's items, as typed ("a,b" -> {"a", "b"}; "" -> {}):
// one value on the command line, so a file after it stays the file, and help
// shows it as one (CLI11 lists a vector option as "VALUE ...").
std::vector<std::string> split_commas(const std::string& text);
