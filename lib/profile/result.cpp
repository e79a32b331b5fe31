#include "profile/result.h"

#include <algorithm>
#include <cmath>

#include "profile/stats.h"

namespace crowdprof {

std::vector<double> finite(const std::vector<double>& values) {
  std::vector<double> out;
  std::copy_if(values.begin(), values.end(), std::back_inserter(out), [](double v) { return std::isfinite(v); });
  return out;
}

const std::vector<double>* metric_samples(const Result& result, std::string_view key) {
  const ResultSamples& s = result.samples;
  if (key == "frame_ms") return &s.frame_ms;
  if (key == "cpu_ms") return s.cpu_ms.empty() ? nullptr : &s.cpu_ms;
  if (key == "gpu_ms") return s.gpu_ms.empty() ? nullptr : &s.gpu_ms;
  for (size_t c = 0; c < kCategoryCount; ++c)
    if (key == series_name(static_cast<Category>(c))) return &s.category_ms[c];
  return nullptr;
}

std::vector<std::string> recorded_metrics(const Result& result) {
  std::vector<std::string> keys = {"frame_ms"};
  if (!result.samples.cpu_ms.empty()) keys.emplace_back("cpu_ms");
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
