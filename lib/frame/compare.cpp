#include "frame/compare.h"

#include <algorithm>

#include "base/errors.h"

namespace crowdprof {

void check_fits_in_memory(const Character& character, std::span<const BenchConfig> configs) {
  const Character* one[] = {&character};
  check_fits_in_memory(one, configs);
}

void check_fits_in_memory(std::span<const Character* const> characters, std::span<const BenchConfig> configs) {
  uint64_t needed = 0;
  for (const BenchConfig& config : configs) needed += estimate_bench_bytes(characters, config.crowd, config.mode);
  uint64_t available = available_memory_bytes();
  if (available == 0 || needed <= available * 9 / 10) return;
  auto mib = [](uint64_t bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB"; };
  throw UsageError(std::to_string(configs.size()) + " modes of this crowd side by side need about " + mib(needed) +
                   " of memory; this machine has " + mib(available) + " available (compare fewer modes or copies)");
}

std::vector<Result> run_interleaved(std::span<CrowdBench* const> benches, const std::string& file,
                                       const RunOptions& options, size_t block) {
  block = std::max<size_t>(block, 1);
  std::vector<Result> reports(benches.size());
  Environment environment = current_environment();
  for (size_t b = 0; b < benches.size(); ++b) {
    reports[b].run = describe_run(*benches[b], file);
    reports[b].run.warmup = options.warmup;
    reports[b].environment = environment;
    reports[b].frame_records.reserve(options.frames);
    reports[b].frames_planned = options.frames;
  }
  size_t per_bench = options.warmup + options.frames;
  size_t total = per_bench * benches.size(), done = 0;
  for (size_t start = 0; start < per_bench; start += block) {
    size_t end = std::min(per_bench, start + block);
    if (options.stop && options.stop->load()) {
      // Stopped between rounds: every mode has the same frames so far.
      for (Result& report : reports) report.partial = true;
      break;
    }
    for (size_t b = 0; b < benches.size(); ++b) {
      // The other benches' blocks are not this bench's time.
      benches[b]->restart_clock();
      for (size_t i = start; i < end; ++i) {
        FrameRecord record = benches[b]->step();
        if (i >= options.warmup) reports[b].frame_records.push_back(record);
        place_gpu_times(*benches[b], options.warmup, reports[b].frame_records);
        if (options.progress) options.progress(++done, total);
      }
      // The block's last frames: their timer queries are done before the next
      // mode draws (with one renderer for all modes, its queries are shared).
      benches[b]->collect_gpu_times();
      place_gpu_times(*benches[b], options.warmup, reports[b].frame_records);
    }
  }
  for (size_t b = 0; b < benches.size(); ++b) {
    // Every mode culls the same crowd from the same camera: one audit serves all.
    finish_run(*benches[b], reports[b], b == 0);
    if (b > 0) reports[b].culling_audit = reports[0].culling_audit;
  }
  return reports;
}

}  // namespace crowdprof
