#include "advise/advise.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "base/number_text.h"
#include "base/switch_table.h"
#include "gate/paired_test.h"
#include "measuring/stats.h"

namespace crowdprof {

namespace {

constexpr std::array<std::string_view, 6> kFamilies = {"sharing",     "update_lod", "mesh_lod",
                                                       "anim_budget", "threads",    "vertex_format"};

// Sharing's quanta, finest first: each step may snap times coarser.
constexpr std::array<std::string_view, 4> kQuanta = {"1/60", "1/30", "1/15", "1/8"};
// LOD thresholds after the defaults, each halving the size at which a copy
// is updated (or drawn) in full.
constexpr std::array<std::string_view, 3> kThresholds = {"0.25,0.125,0.0625", "0.5,0.25,0.125", "1,0.5,0.25"};

// The threshold text after `now`, or "" past the last.
std::string next_thresholds(const std::string& now) {
  for (size_t i = 0; i + 1 < kThresholds.size(); ++i)
    if (now == kThresholds[i]) return std::string(kThresholds[i + 1]);
  return {};
}

std::string recorded_text(const ModeSwitches& s, std::string_view name) {
  return switch_text(find_switch(name)->get(s));
}

// Error a viewer cannot see: a lever adding less is free.
constexpr double kInvisiblePx = 0.01;

// Whether lever `a` is a better step than `b`: one that meets the budget on its
// own with the least error added (then the larger saving); else a free one
// with the larger saving; else the most milliseconds saved per pixel added.
bool better_step(const AdviceCandidate& a, const AdviceCandidate& b, double base_error_px, double budget_ms) {
  auto added = [&](const AdviceCandidate& c) { return std::max(c.error_px - base_error_px, 0.0); };
  const bool a_meets = a.metric.median <= budget_ms, b_meets = b.metric.median <= budget_ms;
  if (a_meets != b_meets) return a_meets;
  if (a_meets && added(a) != added(b)) return added(a) < added(b);
  const bool a_free = added(a) < kInvisiblePx, b_free = added(b) < kInvisiblePx;
  if (a_free != b_free) return a_free;
  if (a_free || a_meets) return a.saved.median > b.saved.median;
  return a.saved.median / added(a) > b.saved.median / added(b);
}

std::vector<double> paired_savings(const std::vector<double>& base, const std::vector<double>& lever) {
  std::vector<double> saved;
  for (size_t i = 0; i < base.size() && i < lever.size(); ++i)
    if (std::isfinite(base[i]) && std::isfinite(lever[i])) saved.push_back(base[i] - lever[i]);
  return saved;
}

MsInterval interval_of(const std::vector<double>& values) {
  // Fewer resamples of a long run (a ^C after many fast frames): its interval
  // is narrow anyway, and 4,000 of a million frames would take minutes.
  const size_t resamples = std::clamp<size_t>(20'000'000 / std::max<size_t>(values.size(), 1), 200, 4000);
  MedianInterval m = bootstrap_median(values, 0.95, resamples);
  return {m.median, m.low, m.high};
}

AdviceCandidate measured(const AdviseRule& rule, const Result& run, const std::vector<double>* base_values) {
  AdviceCandidate c;
  std::vector<double> values = metric_values(run, rule.metric);
  c.metric = interval_of(values);
  // The median capacity's search and the reports read (the lower of two).
  c.metric.median = summarize(values).median;
  c.frame_ms = summarize(metric_values(run, CapacityMetric{})).median;
  if (base_values) {
    const std::vector<double> saved = paired_savings(*base_values, values);
    c.saved = interval_of(saved);
    // The same median as the frame's (the lower of two): a saving is then
    // never more than the base's frame_ms, as a midpoint could read.
    c.saved.median = summarize(saved).median;
  }
  c.error_measured = run.drawn_error.has_value();
  if (run.drawn_error) {
    c.error_px = run.drawn_error->max_px;
    c.error_mm = run.drawn_error->max * 1000.0;
    c.error_height_pct = run.drawn_error->max_fraction * 100.0;
  }
  if (c.metric.median > 0)
    c.capacity_estimate =
        static_cast<size_t>(std::floor(static_cast<double>(rule.characters) * rule.budget_ms / c.metric.median));
  c.digest = run.digest;
  return c;
}

std::string lever_list(const std::vector<std::string>& levers) {
  std::string text;
  for (const std::string& lever : levers) text += (text.empty() ? "" : ", ") + lever;
  return text;
}

std::string describe(const AdviceCandidate& c) {
  return c.lever + " (" + c.changes + ")";
}

std::string ms(double value) {
  return fixed(value, value < 1 ? 3 : 2) + " ms";
}

// Why no lever of the step was taken, in a sentence.
std::pair<std::string, std::string> ran_out(const AdviceStep& step, const AdviseRule& rule) {
  const AdviceCandidate* past = nullptr;
  const AdviceCandidate* noise = nullptr;
  for (const AdviceCandidate& c : step.candidates) {
    if (c.verdict == "past max error" && (!past || c.saved.median > past->saved.median)) past = &c;
    if (c.verdict == "noise" && (!noise || c.saved.median > noise->saved.median)) noise = &c;
  }
  if (past && (!noise || past->saved.median > noise->saved.median))
    return {"max error", "the levers that still save time draw past {max_error} " + shortest_text(rule.max_error_px) +
                             " px: the best, " + describe(*past) + ", would save " + ms(past->saved.median) + " at " +
                             fixed(past->error_px, 2) + " px"};
  if (noise)
    return {"noise", "no lever saves time outside its interval: the best, " + describe(*noise) + ", saves " +
                         ms(noise->saved.median) + " [" + fixed(noise->saved.low, 3) + ", " +
                         fixed(noise->saved.high, 3) + "]"};
  return {"no lever left", "every lever left is slower here or cannot run with the configuration"};
}

}  // namespace

std::span<const std::string_view> lever_families() {
  return kFamilies;
}

std::string lever_family_names() {
  std::string names;
  for (std::string_view family : kFamilies) names += (names.empty() ? "" : ", ") + std::string(family);
  return names;
}

ModeSwitches AdviseConfig::mode_switches() const {
  const ModePreset* mode = find_mode(preset);
  if (!mode) throw std::logic_error("advise: no preset " + preset);
  ModeSwitches s = mode->switches;
  for (const auto& [name, value] : switches) {
    const SwitchSpec* spec = find_switch(name);
    if (!spec) throw std::logic_error("advise: no switch " + name);
    if (std::string problem = spec->set(s, value); !problem.empty())
      throw std::logic_error("advise: " + name + " " + value + ": " + problem);
  }
  return s;
}

SettingText AdviseRule::Validate() const {
  if (!(budget_ms > 0) || !std::isfinite(budget_ms)) return "{budget} must be a number of milliseconds above 0";
  if (!(max_error_px >= 0) || !std::isfinite(max_error_px)) return "{max_error} must be a number of pixels, 0 or more";
  if (!(time_limit_s > 0) || !std::isfinite(time_limit_s)) return "{time_limit} must be a number of seconds above 0";
  if (metric.category && *metric.category != Category::Animations)
    return "{metric} must be frame or Animations: the levers save CPU time in the frame and in Animations";
  for (const std::string& lever : levers)
    if (std::find(kFamilies.begin(), kFamilies.end(), lever) == kFamilies.end())
      return "{levers} '" + lever + "': expected some of " + lever_family_names();
  return {};
}

std::string options_over(const AdviseConfig& start, const AdviseConfig& config) {
  std::string text;
  for (const auto& [name, value] : config.switches) {
    auto it = start.switches.find(name);
    if (it != start.switches.end() && it->second == value) continue;
    text += (text.empty() ? "" : " ") + option_spelling(name) + " " + value;
  }
  if (config.threads != start.threads)
    text += (text.empty() ? "" : " ") + std::string("--threads ") + std::to_string(config.threads);
  return text;
}

std::vector<LeverSetting> next_lever_settings(const AdviseRule& rule, const AdviseConfig& current, const Result& base) {
  const ModeSwitches s = current.mode_switches();
  std::vector<LeverSetting> out;
  auto wanted = [&](std::string_view family) {
    return rule.levers.empty() || std::find(rule.levers.begin(), rule.levers.end(), family) != rule.levers.end();
  };
  auto add = [&](std::string_view family, std::initializer_list<std::pair<const char*, std::string>> changes,
                 int threads = -1) {
    LeverSetting lever;
    lever.family = family;
    lever.config = current;
    for (const auto& [name, value] : changes) lever.config.switches[name] = value;
    if (threads >= 0) lever.config.threads = threads;
    lever.changes = options_over(current, lever.config);
    lever.why_not = conflicts(lever.config.mode_switches());
    out.push_back(std::move(lever));
  };
  for (std::string_view family : kFamilies) {
    if (!wanted(family)) continue;
    if (family == "sharing") {
      if (!s.share_poses) {
        add(family, {{"share", "on"}, {"share_quantum", std::string(kQuanta[0])}});
        continue;
      }
      // The quantum after the current one (exact sharing first snaps at the finest).
      for (size_t i = 0; i < kQuanta.size(); ++i) {
        ModeSwitches probe;
        find_switch("share_quantum")->set(probe, kQuanta[i]);
        if (probe.share_quantum_s > s.share_quantum_s + 1e-9) {
          add(family, {{"share_quantum", std::string(kQuanta[i])}});
          break;
        }
      }
    } else if (family == "update_lod" || family == "mesh_lod") {
      const bool on = family == "update_lod" ? s.update_lod : s.mesh_lod;
      const std::string thresholds = family == "update_lod" ? "lod_thresholds" : "mesh_lod_thresholds";
      if (!on) {
        add(family, {{std::string(family) == "update_lod" ? "update_lod" : "mesh_lod", "on"}});
        continue;
      }
      std::string next = next_thresholds(recorded_text(s, thresholds));
      if (!next.empty()) add(family, {{thresholds.c_str(), next}});
    } else if (family == "anim_budget") {
      const std::vector<double> animations = metric_values(base, CapacityMetric{Category::Animations});
      const double now = s.anim_budget_ms > 0 ? s.anim_budget_ms : summarize(animations).median;
      const double half = std::round(now * 50.0) / 100.0;  // half, to 0.01 ms
      if (half >= 0.01 && (s.anim_budget_ms == 0 || half < s.anim_budget_ms))
        add(family, {{"anim_budget", shortest_text(half)}});
    } else if (family == "threads") {
      if (s.parallel && current.threads > 0 && current.threads < rule.cores) add(family, {}, rule.cores);
    } else if (family == "vertex_format") {
      if (s.vertex_format == VertexFormat::Float) add(family, {{"vertex_format", "packed"}});
    }
  }
  return out;
}

AdviseRun run_advise(const AdviseRule& rule, const AdviseConfig& start, const AdviseHooks& hooks) {
  AdviseRun run;
  run.start = start;
  run.final = start;
  AdviceRecord& record = run.record;
  record.budget_ms = rule.budget_ms;
  record.metric = rule.metric.name();
  record.max_error_px = rule.max_error_px;
  record.time_limit_s = rule.time_limit_s;
  record.characters = rule.characters;
  for (std::string_view family : kFamilies)
    if (rule.levers.empty() || std::find(rule.levers.begin(), rule.levers.end(), family) != rule.levers.end())
      record.levers.emplace_back(family);
  record.left_out.push_back(
      "GPU levers (hwskin, buffer, instanced, compute, baked, gpu frustum): timed on a software GL they would give "
      "wrong advice");
  auto stopped = [&](const std::vector<Result>& runs) {
    return std::any_of(runs.begin(), runs.end(), [](const Result& r) { return r.partial; });
  };
  auto finish = [&](const std::string& outcome) {
    record.outcome = outcome;
    record.elapsed_s = hooks.elapsed_s();
  };

  // The start alone first: the budget may be met already, and the first
  // anim_budget is sized from its Animations.
  AdviseConfig one[] = {start};
  hooks.progress("measuring the start (" + start.preset + (start.switches.empty() ? "" : ", as given") + ")");
  std::vector<Result> first = hooks.measure(one);
  record.configurations_measured = stopped(first) ? 0 : 1;
  if (first.size() != 1) throw std::logic_error("advise: the start measured the wrong number of runs");
  if (stopped(first)) {
    // The frames measured so far, as bench keeps a cut run's.
    run.partial = hooks.stop_reason() == "interrupted";
    if (!first.front().frame_records.empty()) {
      run.start_run = run.final_run = first.front();
      record.start = measured(rule, first.front(), nullptr);
      record.start.verdict = "start";
      record.final = record.start;
      record.final.verdict = "final";
    }
    record.start_mode = start.preset;
    record.start_options = record.final_options = options_over(AdviseConfig{start.preset, {}, 0}, start);
    finish(hooks.stop_reason());
    return run;
  }
  run.start_run = first.front();
  run.final_run = first.front();
  AdviseConfig current = start;
  Result current_run = first.front();
  record.start = measured(rule, current_run, nullptr);
  record.start.verdict = "start";
  record.final = record.start;
  double current_ms = record.start.metric.median;

  for (size_t step_number = 1; current_ms > rule.budget_ms; ++step_number) {
    if (hooks.elapsed_s() >= rule.time_limit_s) {
      record.ran_out = "the time limit of " + shortest_text(rule.time_limit_s) +
                       " s passed before the budget was met: {time_limit} gives the search longer";
      finish("time limit");
      break;
    }
    std::vector<LeverSetting> levers = next_lever_settings(rule, current, current_run);
    std::vector<const LeverSetting*> runnable;
    for (const LeverSetting& lever : levers)
      if (lever.why_not.empty()) runnable.push_back(&lever);
    AdviceStep step;
    if (runnable.empty()) {
      std::string why;
      for (const LeverSetting& lever : levers) why += "; " + lever.family + " cannot run: " + lever.why_not.marked();
      record.ran_out =
          "no lever of " + lever_list(record.levers) + " has a setting left to try over this configuration" + why;
      finish("no lever left");
      break;
    }
    // Groups as large as memory allows, each with the base, so every saving is
    // paired with a base measured in the same blocks.
    const size_t per_group = std::max<size_t>(rule.side_by_side, 2) - 1;
    std::string names;
    for (const LeverSetting* lever : runnable) names += (names.empty() ? "" : ", ") + lever->family;
    hooks.progress("step " + std::to_string(step_number) + ": the configuration beside " + names);
    std::vector<AdviceCandidate> candidates;
    std::vector<std::pair<const LeverSetting*, Result>> lever_runs;
    std::vector<double> first_base;
    bool cut = false;
    double base_error_px = 0;
    for (size_t at = 0; at < runnable.size() && !cut; at += per_group) {
      std::vector<AdviseConfig> group = {current};
      for (size_t k = at; k < std::min(runnable.size(), at + per_group); ++k) group.push_back(runnable[k]->config);
      std::vector<Result> runs = hooks.measure(group);
      if (runs.size() != group.size()) throw std::logic_error("advise: a step measured the wrong number of runs");
      if (stopped(runs)) {
        cut = true;
        break;
      }
      record.configurations_measured += group.size();
      std::vector<double> base_values = metric_values(runs[0], rule.metric);
      if (at == 0) {
        AdviceCandidate base = measured(rule, runs[0], nullptr);
        base.verdict = "base";
        base_error_px = base.error_px;
        step.candidates.push_back(base);
        current_run = runs[0];
        if (step_number == 1) {
          // Measured beside the levers, after the lone start warmed the
          // machine: the start's figure from now on.
          run.start_run = runs[0];
          record.start = base;
          record.start.verdict = "start";
        }
      }
      for (size_t k = 1; k < runs.size(); ++k) {
        const LeverSetting* lever = runnable[at + k - 1];
        AdviceCandidate c = measured(rule, runs[k], &base_values);
        c.lever = lever->family;
        c.changes = lever->changes;
        step.candidates.push_back(c);
        lever_runs.emplace_back(lever, runs[k]);
      }
    }
    if (cut) {
      run.partial = hooks.stop_reason() == "interrupted";
      if (!run.partial)
        record.ran_out = "the time limit of " + shortest_text(rule.time_limit_s) + " s passed during step " +
                         std::to_string(step_number) + ", which is left out: {time_limit} gives the search longer";
      finish(hooks.stop_reason());
      break;
    }
    for (const LeverSetting& lever : levers)
      if (!lever.why_not.empty()) {
        AdviceCandidate c;
        c.lever = lever.family;
        c.changes = lever.changes;
        c.verdict = "cannot run: " + lever.why_not.marked();
        step.candidates.push_back(c);
      }
    // Verdicts, then the best by milliseconds saved per pixel added.
    std::optional<size_t> best;
    for (size_t i = 1; i < step.candidates.size(); ++i) {
      AdviceCandidate& c = step.candidates[i];
      if (!c.verdict.empty()) continue;
      // Past the error allowed only when it adds to it: a start already past
      // it may still take a lever that draws no further off.
      if (c.saved.median <= 0)
        c.verdict = "slower";
      else if (c.error_px > rule.max_error_px + 1e-12 && c.error_px > base_error_px + kInvisiblePx)
        c.verdict = "past max error";
      else if (c.saved.low <= 0)
        c.verdict = "noise";
      else if (!best || better_step(c, step.candidates[*best], base_error_px, rule.budget_ms))
        best = i;
    }
    for (size_t i = 1; i < step.candidates.size(); ++i)
      if (step.candidates[i].verdict.empty()) step.candidates[i].verdict = i == best ? "taken" : "not the best";
    step.taken = best;
    record.steps.push_back(step);
    current_ms = step.candidates.front().metric.median;
    run.final_run = current_run;
    record.final = step.candidates.front();
    if (!best) {
      auto [outcome, why] = ran_out(step, rule);
      record.ran_out = why;
      finish(outcome);
      break;
    }
    const AdviceCandidate& taken = step.candidates[*best];
    for (auto& [lever, lever_run] : lever_runs)
      if (lever->family == taken.lever) {
        current = lever->config;
        current_run = lever_run;
      }
    run.final = current;
    run.final_run = current_run;
    record.final = taken;
    current_ms = taken.metric.median;
    hooks.progress("step " + std::to_string(step_number) + " took " + describe(taken) + ": " +
                   ms(step.candidates.front().metric.median) + " to " + ms(taken.metric.median));
  }
  if (record.outcome.empty()) finish("met");
  record.final.verdict = "final";
  record.final.saved = {};
  record.met = current_ms <= rule.budget_ms;
  record.start_options = options_over(AdviseConfig{start.preset, {}, 0}, start);
  record.start_mode = start.preset;
  record.final_options = options_over(AdviseConfig{start.preset, {}, 0}, run.final);
  record.added_options = options_over(start, run.final);
  if (run.partial || record.outcome == "time limit" || record.outcome == "interrupted") return run;

  // One search when no lever was taken: the start is the final configuration.
  const bool same = run.final == start;
  hooks.progress(std::string(same ? "capacity of the start" : "capacity of the start and of the final configuration") +
                 " at " + ms(rule.budget_ms));
  std::vector<AdviseConfig> ends = {start};
  if (!same) ends.push_back(run.final);
  CapacityRun capacity = hooks.capacity(ends);
  if (capacity.partial) {
    run.partial = hooks.stop_reason() == "interrupted";
    record.left_out.push_back("the capacities: their search was cut short (" + hooks.stop_reason() + ")");
  } else {
    for (size_t m = 0; m < capacity.modes.size() && m < 2; ++m) {
      const ModeCapacity& mode = capacity.modes[m];
      AdviceCapacity c;
      c.configuration = m == 0 ? (same ? "start and final" : "start") : "final";
      if (mode.result.fit) c.fit = mode.result.fit->n;
      if (mode.result.fail) c.over = mode.result.fail->n;
      c.capped = mode.result.capped;
      c.measured = mode.tried.size();
      record.capacities.push_back(c);
    }
  }
  record.elapsed_s = hooks.elapsed_s();
  return run;
}

}  // namespace crowdprof
