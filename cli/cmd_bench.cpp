// `crowdprof bench`: the main job. Parses options into a BenchConfig, runs the
// frames and prints the profile; the work itself is in lib/frame.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <thread>

#include "asset/errors.h"
#include "asset/gltf_loader.h"
#include "cli/bench_options.h"
#include "cli/commands.h"
#include "frame/run_bench.h"
#include "render/gl_errors.h"
#include "render/png.h"

namespace {

using namespace crowdprof;

// Progress on stderr once a run has taken a second, only when a person watches.
std::function<void(size_t, size_t)> terminal_progress(bool quiet) {
  if (quiet || !isatty(STDERR_FILENO)) return {};
  auto start = std::chrono::steady_clock::now();
  auto last = std::make_shared<std::chrono::steady_clock::time_point>(start);
  return [start, last](size_t done, size_t total) {
    auto now = std::chrono::steady_clock::now();
    if (now - start < std::chrono::seconds(1) && done < total) return;
    if (now - *last < std::chrono::milliseconds(100) && done < total) return;
    *last = now;
    std::fprintf(stderr, "\rcrowdprof: frame %zu/%zu", done, total);
    if (done == total) std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
  };
}

void write_text(const std::string& path, const std::string& what, const std::function<void(std::ostream&)>& body) {
  std::ofstream out(path);
  if (!out) throw UsageError("cannot write " + what + " file '" + path + "'");
  body(out);
  if (!out) throw UsageError("error writing " + what + " file '" + path + "'");
}

int bench(const BenchCliOptions& options) {
  Character character = load_character(options.file);
  BenchConfig config = make_bench_config(options, character);
  check_fits_in_memory(character, config.crowd.copies, config.mode);
  if (!options.screenshot.empty() && options.backend == "none")
    throw UsageError("--screenshot needs a GL backend: --backend auto, egl or osmesa");
  BenchRendering rendering = open_bench_rendering(options, character, config);
  if (!options.screenshot.empty() && !rendering.renderer)
    throw GlUnavailable("--screenshot: no GL backend could be opened, so no frame would be drawn");
  CrowdBench crowd(character, config);
  RunOptions run;
  run.frames = options.frames;
  run.warmup = options.warmup;
  run.progress = terminal_progress(options.quiet);
  RunReport report = run_bench(crowd, options.file, run);
  report.run.backend = rendering.backend_name();
  report.run.renderer = rendering.renderer_name();
  if (!options.quiet) std::cout << format_profile(report);
  if (!options.csv.empty()) write_text(options.csv, "CSV", [&](std::ostream& out) { write_csv(report, out); });
  if (!options.json.empty())
    write_text(options.json, "JSON", [&](std::ostream& out) { out << to_json(report).dump(2) << "\n"; });
  if (!options.screenshot.empty()) {
    std::vector<uint8_t> pixels = rendering.renderer->read_pixels();
    write_png(options.screenshot, rendering.renderer->width(), rendering.renderer->height(), pixels);
  }
  return kExitOk;
}

}  // namespace

void add_bench_command(CLI::App& app, std::function<int()>& run) {
  auto options = std::make_shared<BenchCliOptions>();
  auto* cmd = app.add_subcommand("bench", "Fill a scene with copies of a character, play actions and print where "
                                          "each frame's time goes (BGE-style profile)");
  add_bench_options(*cmd, *options);
  cmd->add_option("--csv", options->csv, "Write one row per measured frame to this CSV file");
  cmd->add_option("--json", options->json, "Write the run's summary (and per-frame samples) to this JSON file");
  cmd->add_option("--screenshot", options->screenshot, "Write the last frame as a PNG (needs a GL backend)");
  cmd->callback([&run, options] { run = [options] { return bench(*options); }; });
}
