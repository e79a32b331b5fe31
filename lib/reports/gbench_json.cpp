#include "reports/gbench_json.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <string>
#include <tuple>

#include "measuring/category_clock.h"
#include "measuring/stats.h"

namespace crowdprof {

namespace {

std::string iso_time_now() {
  std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm local{};
  localtime_r(&now, &local);
  char text[40];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S%z", &local);
  return text;
}

std::vector<double> load_average() {
  std::ifstream in("/proc/loadavg");
  std::vector<double> load(3, 0.0);
  for (double& value : load) in >> value;
  return load;
}

std::string host_name() {
  char name[256] = {};
  return ::gethostname(name, sizeof name - 1) == 0 ? name : "";
}

struct Series {
  std::string metric;
  std::vector<double> real, cpu;
};

// The frame, then each category with time in some frame.
std::vector<Series> series_of(const Result& report) {
  std::vector<Series> series(1);
  series[0].metric = "frame";
  for (const FrameRecord& frame : report.frame_records) {
    series[0].real.push_back(frame.times.total_ms());
    series[0].cpu.push_back(frame.cpu_ms);
  }
  for (size_t c = 0; c < kCategoryCount; ++c) {
    Series category{std::string(category_name(static_cast<Category>(c))), {}, {}};
    bool any = false;
    for (const FrameRecord& frame : report.frame_records) {
      category.real.push_back(frame.times.ms[c]);
      any = any || frame.times.ms[c] > 0;
    }
    if (!any) continue;
    category.cpu = category.real;  // a category is wall-clock time inside the frame
    series.push_back(std::move(category));
  }
  return series;
}

nlohmann::json entry(const std::string& name, size_t family, size_t repetitions, const Result& report) {
  return {{"name", name},     {"family_index", family},     {"per_family_instance_index", 0},
          {"run_name", name}, {"repetitions", repetitions}, {"threads", report.run.threads},
          {"iterations", 1},  {"time_unit", "ms"}};
}

}  // namespace

nlohmann::json gbench_document(const std::vector<const Result*>& runs) {
  nlohmann::json benchmarks = nlohmann::json::array();
  size_t family = 0;
  for (const Result* report : runs) {
    for (const Series& series : series_of(*report)) {
      uint32_t passes = report->run.switches.passes;
      std::string name = report->run.mode + "/" + report->run.character +
                         "/n:" + std::to_string(report->run.characters) +
                         (passes != 1 ? "/passes:" + std::to_string(passes) : std::string()) + "/" + series.metric;
      const size_t n = series.real.size();
      for (size_t i = 0; i < n; ++i) {
        nlohmann::json e = entry(name, family, n, *report);
        e["run_type"] = "iteration";
        e["repetition_index"] = i;
        e["real_time"] = series.real[i];
        e["cpu_time"] = series.cpu[i];
        benchmarks.push_back(std::move(e));
      }
      Summary real = summarize(series.real), cpu = summarize(series.cpu);
      for (const auto& [aggregate, real_value, cpu_value] : {std::tuple{"mean", real.mean, cpu.mean},
                                                             {"median", real.median, cpu.median},
                                                             {"stddev", real.stddev, cpu.stddev}}) {
        nlohmann::json e = entry(name + "_" + aggregate, family, n, *report);
        e["run_name"] = name;
        e["run_type"] = "aggregate";
        e["aggregate_name"] = aggregate;
        e["aggregate_unit"] = "time";
        e["real_time"] = real_value;
        e["cpu_time"] = cpu_value;
        benchmarks.push_back(std::move(e));
      }
      ++family;
    }
  }
  const Environment& environment = runs.empty() ? current_environment() : runs.front()->environment;
  nlohmann::json context = {{"date", iso_time_now()},
                            {"host_name", host_name()},
                            {"executable", "crowdprof"},
                            {"num_cpus", environment.cores},
                            {"mhz_per_cpu", 0},
                            {"cpu_scaling_enabled", false},
                            {"caches", nlohmann::json::array()},
                            {"load_avg", load_average()},
                            {"library_build_type", environment.build_type == "Debug" ? "debug" : "release"},
                            {"crowdprof_version", environment.version},
                            {"crowdprof_commit", environment.commit},
                            {"cpu", environment.cpu},
                            {"simd", environment.simd}};
  return {{"context", context}, {"benchmarks", benchmarks}};
}

}  // namespace crowdprof
