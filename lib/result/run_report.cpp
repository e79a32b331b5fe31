#include "result/run_report.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "measuring/stats.h"
#include "result/result_codec.h"

namespace crowdprof {

size_t median_frame(const std::vector<FrameRecord>& frames) {
  if (frames.empty()) return 0;
  std::vector<size_t> order(frames.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return frames[a].times.total_ms() < frames[b].times.total_ms();
  });
  return order[(order.size() - 1) / 2];
}

Result make_result(const RunReport& report) {
  Result r;
  r.environment = report.environment;
  r.run = report.run;
  for (const FrameRecord& f : report.frames) {
    r.samples.frame_ms.push_back(f.times.total_ms());
    r.samples.cpu_ms.push_back(f.cpu_ms);
    if (report.calibration_probe) r.samples.probe_ms.push_back(f.probe_ms);
    for (size_t c = 0; c < kCategoryCount; ++c) r.samples.category_ms[c].push_back(f.times.ms[c]);
  }
  // GPU times only when a timer measured some frame: never a column of NaN.
  if (std::any_of(report.frames.begin(), report.frames.end(), [](const FrameRecord& f) { return std::isfinite(f.gpu_ms); }))
    for (const FrameRecord& f : report.frames) r.samples.gpu_ms.push_back(f.gpu_ms);
  bool split = std::any_of(report.frames.begin(), report.frames.end(),
                           [](const FrameRecord& f) { return f.gpu_passes.timed(); });
  for (size_t p = 0; split && p < kGpuPassCount; ++p)
    for (const FrameRecord& f : report.frames) r.samples.gpu_pass_ms[p].push_back(f.gpu_passes.ms[p]);
  if (std::any_of(report.frames.begin(), report.frames.end(),
                  [](const FrameRecord& f) { return f.gpu_passes.has_stats(); })) {
    auto& medians = r.pipeline_statistics.emplace();
    for (size_t p = 0; p < kGpuPassCount; ++p)
      for (size_t s = 0; s < kPipelineStatCount; ++s) {
        std::vector<double> values;
        for (const FrameRecord& f : report.frames)
          if (f.gpu_passes.has_stats()) values.push_back(f.gpu_passes.stats[p][s]);
        medians[p][s] = quantile(values, 0.5);
      }
  }
  r.calibration_probe = report.calibration_probe;
  r.samples.calibrated = calibrated_frames(r.samples.frame_ms, r.samples.probe_ms);
  for (const CounterField& field : kCounterFields) {
    std::vector<double> values;
    for (const FrameRecord& f : report.frames) values.push_back(static_cast<double>(f.counters.*field.member));
    r.counters.values.*field.member = static_cast<uint64_t>(quantile(values, 0.5));
  }
  r.counters.present.fill(true);
  r.digest = report.digest;
  r.digest_cpu_vertices = report.digest_cpu_vertices;
  r.stores = report.stores;
  r.partial = report.partial;
  r.frames_planned = report.frames_planned;
  r.animation = report.animation;
  r.mesh_lod = report.mesh_lod;
  r.culling_audit = report.culling_audit;
  r.drawn_error = report.drawn_error;
  if (!report.instruction_source.empty()) {
    // What a stored instruction baseline must match to be compared.
    InstructionRecord i;
    i.source = report.instruction_source;
    i.threads = report.run.threads;
    i.simd = report.environment.simd;
    i.compiler = report.environment.compiler;
    i.problem = report.instruction_problem;
    if (i.source == "perf_event") {  // callgrind's is filled from its output by who ran it
      std::vector<double> counts;
      for (const FrameRecord& f : report.frames) counts.push_back(static_cast<double>(f.instructions));
      i.per_frame = quantile(counts, 0.5);
    }
    r.instructions = i;
  }
  return r;
}

nlohmann::json to_json(const RunReport& report) { return result_to_json(make_result(report)); }

}  // namespace crowdprof
