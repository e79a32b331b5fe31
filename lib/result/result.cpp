#include "result/result.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "measuring/stats.h"

namespace crowdprof {

std::vector<double> finite(const std::vector<double>& values) {
  std::vector<double> out;
  std::copy_if(values.begin(), values.end(), std::back_inserter(out), [](double v) { return std::isfinite(v); });
  return out;
}

std::vector<double> calibrated_frames(const std::vector<double>& frame_ms, const std::vector<double>& probe_ms) {
  std::vector<double> ratios;
  if (frame_ms.size() != probe_ms.size()) return ratios;
  for (size_t i = 0; i < frame_ms.size(); ++i)
    ratios.push_back(probe_ms[i] > 0 ? frame_ms[i] / probe_ms[i] : std::numeric_limits<double>::quiet_NaN());
  return ratios;
}

std::optional<AnimationSplit> animation_split(const Result& result) {
  const ResultSamples& s = result.samples;
  const size_t frames = s.frame_ms.size();
  for (const std::vector<double>& stage : s.animation_stage_ms)
    if (stage.size() != frames || frames == 0) return std::nullopt;
  AnimationSplit split;
  split.threads = result.run.switches.parallel ? std::max(1, result.run.threads) : 1;
  double sum = 0;
  for (size_t st = 0; st < kAnimationStageCount; ++st)
    sum += split.median_ms[st] = quantile(s.animation_stage_ms[st], 0.5);
  if (!(sum > 0)) return std::nullopt;
  for (size_t st = 0; st < kAnimationStageCount; ++st) split.share[st] = split.median_ms[st] / sum;
  const std::vector<double>& animations = s.category_ms[static_cast<size_t>(Category::Animations)];
  std::vector<double> covered;
  for (size_t f = 0; f < frames; ++f) {
    double staged = 0;
    for (size_t st = 0; st < kAnimationStageCount; ++st) staged += s.animation_stage_ms[st][f];
    if (animations[f] > 0) covered.push_back(staged / (animations[f] * split.threads));
  }
  split.coverage = covered.empty() ? 0 : quantile(covered, 0.5);
  return split;
}

const std::vector<double>* metric_samples(const Result& result, std::string_view key) {
  const ResultSamples& s = result.samples;
  if (key == "frame_ms") return &s.frame_ms;
  if (key == "cpu_ms") return s.cpu_ms.empty() ? nullptr : &s.cpu_ms;
  if (key == "gpu_ms") return s.gpu_ms.empty() ? nullptr : &s.gpu_ms;
  if (key == "calibrated") return s.calibrated.empty() ? nullptr : &s.calibrated;
  for (size_t c = 0; c < kCategoryCount; ++c)
    if (key == series_name(static_cast<Category>(c))) return &s.category_ms[c];
  return nullptr;
}

std::vector<std::string> recorded_metrics(const Result& result) {
  std::vector<std::string> keys = {"frame_ms"};
  if (!result.samples.cpu_ms.empty()) keys.emplace_back("cpu_ms");
  if (!result.samples.calibrated.empty()) keys.emplace_back("calibrated");
  for (size_t c = 0; c < kCategoryCount; ++c) keys.emplace_back(series_name(static_cast<Category>(c)));
  if (!finite(result.samples.gpu_ms).empty()) keys.emplace_back("gpu_ms");
  return keys;
}

double metric_median(const Result& result, std::string_view key) {
  const std::vector<double>* values = metric_samples(result, key);
  if (!values) return 0;
  std::vector<double> measured = finite(*values);
  return measured.empty() ? 0 : summarize(measured).median;
}
uint32_t crowd_draws_in(GpuPass pass, uint32_t passes) {
  if (pass == GpuPass::Skinning || !pass_drawn(pass, passes)) return 0;
  return pass == GpuPass::Shadows ? passes - 2 : 1;
}

size_t median_frame(const std::vector<FrameRecord>& frames) {
  if (frames.empty()) return 0;
  std::vector<size_t> order(frames.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return frames[a].times.total_ms() < frames[b].times.total_ms(); });
  return order[(order.size() - 1) / 2];
}

namespace {

// The median over the frames with a copy on screen of `bytes` per copy on
// screen; 0 without such a frame.
double median_per_copy_on_screen(const std::vector<FrameRecord>& frames, uint64_t Counters::*bytes) {
  std::vector<double> per_copy;
  for (const FrameRecord& f : frames)
    if (f.counters.copies_visible > 0)
      per_copy.push_back(static_cast<double>(f.counters.*bytes) / static_cast<double>(f.counters.copies_visible));
  return per_copy.empty() ? 0.0 : quantile(per_copy, 0.5);
}

}  // namespace

void record_samples(Result& r) {
  const std::vector<FrameRecord>& frames = r.frame_records;
  // A result read from a file keeps no frames: what it stores is all there is.
  if (frames.empty() && r.frames() > 0) return;
  r.samples = ResultSamples{};
  for (const FrameRecord& f : frames) {
    r.samples.frame_ms.push_back(f.times.total_ms());
    r.samples.cpu_ms.push_back(f.cpu_ms);
    if (r.calibration_probe) r.samples.probe_ms.push_back(f.probe_ms);
    for (size_t c = 0; c < kCategoryCount; ++c) r.samples.category_ms[c].push_back(f.times.ms[c]);
    for (size_t st = 0; st < kAnimationStageCount; ++st)
      r.samples.animation_stage_ms[st].push_back(f.animation_stages.ms[st]);
  }
  // GPU times only when a timer measured some frame: never a column of NaN.
  if (std::any_of(frames.begin(), frames.end(), [](const FrameRecord& f) { return std::isfinite(f.gpu_ms); }))
    for (const FrameRecord& f : frames) r.samples.gpu_ms.push_back(f.gpu_ms);
  bool split = std::any_of(frames.begin(), frames.end(), [](const FrameRecord& f) { return f.gpu_passes.timed(); });
  for (size_t p = 0; split && p < kGpuPassCount; ++p)
    for (const FrameRecord& f : frames) r.samples.gpu_pass_ms[p].push_back(f.gpu_passes.ms[p]);
  r.pipeline_statistics.reset();
  r.invocations_per_vertex_drawn.reset();
  if (std::any_of(frames.begin(), frames.end(), [](const FrameRecord& f) { return f.gpu_passes.has_stats(); })) {
    auto& medians = r.pipeline_statistics.emplace();
    for (size_t p = 0; p < kGpuPassCount; ++p)
      for (size_t s = 0; s < kPipelineStatCount; ++s) {
        std::vector<double> values;
        for (const FrameRecord& f : frames)
          if (f.gpu_passes.has_stats()) values.push_back(f.gpu_passes.stats[p][s]);
        medians[p][s] = quantile(values, 0.5);
      }
    auto& reuse = r.invocations_per_vertex_drawn.emplace();
    const auto vs = static_cast<size_t>(PipelineStat::VertexShaderInvocations);
    for (size_t p = 0; p < kGpuPassCount; ++p) {
      const uint32_t draws = crowd_draws_in(static_cast<GpuPass>(p), r.run.switches.passes);
      std::vector<double> ratios;
      for (const FrameRecord& f : frames)
        if (f.gpu_passes.has_stats() && draws > 0 && f.counters.vertices_drawn > 0)
          ratios.push_back(f.gpu_passes.stats[p][vs] / (static_cast<double>(f.counters.vertices_drawn) * draws));
      reuse[p] = ratios.empty() ? std::numeric_limits<double>::quiet_NaN() : quantile(ratios, 0.5);
    }
  }
  r.samples.calibrated = calibrated_frames(r.samples.frame_ms, r.samples.probe_ms);
  for (const CounterField& field : kCounterFields) {
    std::vector<double> values;
    for (const FrameRecord& f : frames) values.push_back(static_cast<double>(f.counters.*field.member));
    r.counters.values.*field.member = static_cast<uint64_t>(quantile(values, 0.5));
  }
  r.counters.present.fill(true);
  r.bytes_uploaded_per_copy_on_screen = median_per_copy_on_screen(frames, &Counters::bytes_uploaded);
  r.palette_bytes_per_copy_on_screen = median_per_copy_on_screen(frames, &Counters::palette_bytes_uploaded);
  r.record_bytes_per_copy_on_screen = median_per_copy_on_screen(frames, &Counters::record_bytes_uploaded);
  if (r.instructions && r.instructions->source == "perf_event") {
    std::vector<double> counts;
    for (const FrameRecord& f : frames) counts.push_back(static_cast<double>(f.instructions));
    r.instructions->per_frame = quantile(counts, 0.5);
  }
}

}  // namespace crowdprof
