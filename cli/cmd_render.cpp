// `crowdprof render`: one frame of a bench, drawn with GL and written as a PNG,
// to see what the profile measures (and that every mode draws the same crowd).
#include <iostream>
#include <memory>

#include "base/errors.h"
#include "asset/gltf_loader.h"
#include "base/output_file.h"
#include "frame/run_bench.h"
#include "result/result_codec.h"
#include "cli/bench_options.h"
#include "cli/commands.h"
#include "render/gl_errors.h"
#include "render/png.h"

namespace {

using namespace crowdprof;

struct RenderCliOptions {
  BenchCliOptions bench;
  long long frame = 0;
  std::string output;
};

int render(RenderCliOptions& options) {
  if (options.frame < 0 || options.frame > 10'000'000)
    throw UsageError("--frame " + std::to_string(options.frame) + ": expected 0 to 10,000,000");
  resolve_bench_spec(options.bench);
  const RunSpec& spec = options.bench.spec;
  validate_run_spec(spec);
  if (spec.backend == "none") throw UsageError("--backend none draws nothing: use auto, egl or osmesa");
  require_writable_outputs(options.bench);
  BenchScene scene = load_bench_scene(spec);
  BenchConfig config = make_bench_config(spec, scene);
  check_fits_in_memory(scene.characters, config);
  BenchRendering rendering = open_bench_rendering(options.bench, scene, config);
  if (!rendering.renderer) throw GlUnavailable("no GL backend could be opened, so there is nothing to render");
  CrowdBench crowd(scene.characters, config);
  // Frame k shows time k / fps; earlier frames run too, so cursors and any
  // per-frame state reach frame k as they would in a bench.
  FrameRecord record;
  for (long long k = 0; k <= options.frame; ++k) record = crowd.step();
  std::vector<uint8_t> pixels = rendering.renderer->read_pixels();
  write_png(options.output, rendering.renderer->width(), rendering.renderer->height(), pixels);
  if (options.bench.outputs.files().prints_on_stdout(options.bench.quiet))
    std::cout << options.output << ": frame " << options.frame << ", " << rendering.renderer->width() << "x"
              << rendering.renderer->height() << ", " << record.counters.copies_visible << " of "
              << crowd.crowd().size() << " copies drawn, mode " << config.mode_name
              << (crowd.gpu_skinned() ? " (skinned on the GPU)" : "") << ", " << rendering.renderer_name() << "\n";
  return kExitOk;
}

}  // namespace

void add_render_command(CLI::App& app, std::function<int()>& run) {
  auto options = std::make_shared<RenderCliOptions>();
  options->bench.defaults.values["backend"] = "auto";
  auto* cmd = app.add_subcommand("render", "Draw one frame of a bench with OpenGL and write it as a PNG");
  cmd->footer("Examples:\n  crowdprof render scenes/humanoid.glb -n 40 --mode hwskin --frame 10 -o frame.png");
  add_bench_options(*cmd, options->bench);
  // One frame, not a measured run.
  cmd->remove_option(cmd->get_option("--frames"));
  cmd->remove_option(cmd->get_option("--warmup"));
  cmd->add_option("--frame", options->frame, "The frame to draw: it shows time frame/fps")
      ->capture_default_str()
      ->group("Run");
  options->bench.outputs.declare(*cmd, OutputOption::PngImage, options->output, "The PNG to write")->required();
  group_outputs(*cmd);
  cmd->callback([&run, options] { run = [options] { return render(*options); }; });
}
