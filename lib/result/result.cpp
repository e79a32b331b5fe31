#include "result/result.h"

#include <algorithm>
#include <cmath>
#include <limits>

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
}  // namespace crowdprof
