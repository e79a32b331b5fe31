#include "gate/check_plan.h"

#include <algorithm>

#include "base/errors.h"

namespace crowdprof {

CheckPlan plan_check(const CheckRequest& r) {
  CheckPlan plan;
  plan.update_baseline = r.update_baseline;
  plan.gate.tolerance = parse_tolerance(r.tolerance);
  plan.gate.floor = parse_floor(r.floor);
  if (!(r.alpha > 0 && r.alpha < 1)) throw SettingError("alpha", std::to_string(r.alpha), "expected between 0 and 1");
  plan.gate.alpha = r.alpha;
  bool instructions = false;
  for (const std::string& metric : r.metrics) instructions = instructions || metric == kInstructionsMetric;
  long long runs = r.runs.value_or(instructions ? 1 : r.update_baseline ? kBaselineRuns : kCheckRuns);
  if (runs < 1 || runs > static_cast<long long>(kMaxRuns))
    throw SettingError("runs", std::to_string(runs), "expected 1 to " + std::to_string(kMaxRuns));
  plan.runs = static_cast<size_t>(runs);
  plan.spread_s = r.spread_s.value_or(0.0);
  if (!(plan.spread_s >= 0 && plan.spread_s <= 3600))
    throw SettingError("spread", std::to_string(plan.spread_s), "expected 0 to 3600 seconds");
  plan.gate.compare_work = !r.timings_only;
  if (instructions) {
    if (r.metrics.size() > 1)
      throw SettingError("metric", kInstructionsMetric,
                         "instructions is a metric of its own: its runs are counted, not timed");
    // A counted run is not a timed one: no frame times worth a file.
    for (const std::string& option : r.timed_outputs)
      throw UsageError(option +
                       " is not written by --metric instructions (its runs are counted, not timed); --json, "
                       "--junit and --markdown are");
    if (r.ab) throw UsageError("--metric instructions is for a stored baseline: an A/B times both builds side by side");
    if (!r.tolerance_given) plan.gate.tolerance = kInstructionTolerance;
    plan.gate.metrics = {kInstructionsMetric};
    return plan;
  }
  if (r.timings_only && r.update_baseline)
    throw SettingsUsageError("{timings_only} compares; it cannot record a baseline");
  plan.gate.metrics.clear();
  auto add = [&](const std::string& key) {
    if (std::find(plan.gate.metrics.begin(), plan.gate.metrics.end(), key) == plan.gate.metrics.end())
      plan.gate.metrics.push_back(key);
  };
  for (const std::string& metric : r.metrics) {
    if (metric == "all") {
      for (const std::string& key : all_metrics()) add(key);
      continue;
    }
    add(resolve_metric(metric));
  }
  if (plan.gate.metrics.empty()) throw SettingError("metric", "", "name at least one metric");
  return plan;
}

GateMetrics gate_metrics(const Result& baseline, const Result& current, std::vector<std::string> metrics, bool named,
                         const std::string& baseline_path, const std::string& current_name) {
  GateMetrics out;
  const bool base_probe = !baseline.samples.probe_ms.empty(), current_probe = !current.samples.probe_ms.empty();
  const bool same_probe = baseline.calibration_probe == current.calibration_probe;
  auto uses = [&](const char* key) { return std::find(metrics.begin(), metrics.end(), key) != metrics.end(); };
  if (named && uses("calibrated") && base_probe && current_probe && !same_probe)
    throw InputError(baseline_path, "was calibrated by probe version " + std::to_string(baseline.calibration_probe) +
                                        ", " + current_name + " by version " +
                                        std::to_string(current.calibration_probe) +
                                        ": the calibrated frame does not compare; record the baseline again, or check "
                                        "another --metric");
  // The probe leaves the frame after it with cold caches (its frames run
  // longer) and its workers spin on into it: one side timed with it and the
  // other without compare no timed metric like for like.
  if (!named && metrics == std::vector<std::string>{"calibrated"} && base_probe != current_probe)
    throw InputError(baseline_path, std::string("was timed ") + (base_probe ? "with" : "without") +
                                        " the calibration probe between frames and " + current_name + " " +
                                        (current_probe ? "with" : "without") +
                                        " it: the probe slows the frame after it, so no timed metric compares like "
                                        "for like; time both alike (bench --calibrate or check --json for both, or "
                                        "neither), or name a --metric to compare anyway");
  if (!named && metrics == std::vector<std::string>{"calibrated"}) {
    std::string why;
    if (!base_probe || !current_probe)
      why = (!base_probe ? baseline_path : current_name) +
            " has no calibrated frame time (recorded by an older crowdprof or by bench without --calibrate)";
    else if (!same_probe)
      why = "the two were calibrated by different probes (version " + std::to_string(baseline.calibration_probe) +
            " and " + std::to_string(current.calibration_probe) + ")";
    if (!why.empty()) {
      const bool cpu = metric_samples(baseline, "cpu_ms") && metric_samples(current, "cpu_ms");
      metrics = {cpu ? "cpu_ms" : "frame_ms"};
      out.notes.push_back(why + ": checking " + metric_display_name(metrics.front()) + " instead");
    }
  } else if (base_probe != current_probe && !uses("calibrated")) {  // named calibrated: the gate refuses
    out.notes.push_back(
        "warning: only one of the two ran the calibration probe, which slows the frame after it and whose workers "
        "raise CPU time: no timed metric compares like for like");
  }
  out.metrics = std::move(metrics);
  return out;
}

}  // namespace crowdprof
