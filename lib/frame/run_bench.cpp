#include "frame/run_bench.h"

#include <fstream>
#include <sstream>

#include "asset/errors.h"

namespace crowdprof {

uint64_t available_memory_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key, unit;
  uint64_t value = 0;
  while (meminfo >> key >> value >> unit)
    if (key == "MemAvailable:") return value * 1024;
  return 0;
}

void check_fits_in_memory(const Character& character, size_t copies, const ModeSwitches& mode) {
  uint64_t needed = estimate_bench_bytes(character, copies, mode);
  uint64_t available = available_memory_bytes();
  if (available == 0 || needed <= available * 9 / 10) return;
  auto mib = [](uint64_t bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB"; };
  throw UsageError(std::to_string(copies) + " copies of this character need about " + mib(needed) +
                   " of memory; this machine has " + mib(available) + " available");
}

RunDescription describe_run(const CrowdBench& bench, const std::string& file) {
  const Character& c = bench.character();
  const BenchConfig& config = bench.config();
  RunDescription run;
  run.file = file;
  run.character = c.name;
  run.characters = bench.crowd().size();
  run.joints = c.skeleton.joint_count();
  run.vertices = c.mesh.vertex_count();
  run.actions = c.actions.size();
  run.action_choice = config.crowd.actions == ActionChoice::Random ? "random" : "shared";
  if (config.crowd.actions == ActionChoice::Shared && static_cast<size_t>(config.crowd.shared_action) < c.actions.size())
    run.action = c.actions[static_cast<size_t>(config.crowd.shared_action)].name;
  run.seed = config.crowd.seed;
  run.mode = config.mode_name;
  const ModeSwitches& s = config.mode;
  run.switches = {{"lookups", to_string(s.lookups)},
                  {"culling", s.animation_culling},
                  {"pose", to_string(s.pose)},
                  {"parallel", s.parallel},
                  {"skinning", to_string(s.skinning)}};
  run.threads = s.parallel ? config.threads : 1;
  run.fps = config.fps;
  run.camera = config.camera;
  run.resolution = config.resolution;
  return run;
}

RunReport run_bench(CrowdBench& bench, const std::string& file, const RunOptions& options) {
  RunReport report;
  report.run = describe_run(bench, file);
  report.run.warmup = options.warmup;
  report.environment = current_environment();
  size_t total = options.warmup + options.frames;
  report.frames.reserve(options.frames);
  for (size_t i = 0; i < total; ++i) {
    FrameRecord record = bench.step();
    if (i >= options.warmup) report.frames.push_back(record);
    if (options.progress) options.progress(i + 1, total);
  }
  report.digest = bench.digest();
  return report;
}

}  // namespace crowdprof
