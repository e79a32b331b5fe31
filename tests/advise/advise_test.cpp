// `advise`'s search against fake costs (no bench runs): which lever each step
// takes and why the others are not, when it stops, what it keeps, how it
// groups what it measures; the lever settings step by step; the record's codec.
#include <gtest/gtest.h>

#include <cmath>

#include "advise/advise.h"
#include "base/errors.h"
#include "fake_run.h"
#include "result/result_document.h"

using namespace crowdprof;

namespace {

// A made-up crowd: 10 ms a frame, each lever scaling it and adding drawn error.
struct FakeCrowd {
  double base_ms = 10;
  double share = 0.6, update_lod = 0.7, mesh_lod = 0.85, packed = 0.98;
  double share_px = 0.2, update_lod_px = 3, mesh_lod_px = 0.1;
  // Frame-to-frame jitter: the same for every configuration (paired savings
  // are exact), or of alternating sign per configuration (they are not).
  double jitter = 0.01;
  bool paired_jitter = true;
  double elapsed = 0;              // what elapsed_s says
  double seconds_per_measure = 0;  // added to elapsed per measure call
  std::optional<size_t> stop_at;   // the measure call that comes back partial
  bool on_screen = true;           // false: no copy drawn, so no drawn error
  std::vector<std::vector<AdviseConfig>> calls;
  size_t capacity_calls = 0;

  double cost(const ModeSwitches& s) const {
    double ms = base_ms;
    if (s.share_poses) ms *= share * (s.share_quantum_s > 0.02 ? 0.9 : 1.0);
    if (s.update_lod) ms *= update_lod;
    if (s.mesh_lod) ms *= mesh_lod;
    if (s.vertex_format == VertexFormat::Packed) ms *= packed;
    return ms;
  }
  double error(const ModeSwitches& s) const {
    return (s.share_poses ? share_px * (s.share_quantum_s > 0.02 ? 2 : 1) : 0) + (s.update_lod ? update_lod_px : 0) +
           (s.mesh_lod ? mesh_lod_px : 0);
  }
  Result run(const AdviseConfig& config, size_t index) const {
    const ModeSwitches s = config.mode_switches();
    std::vector<double> frames;
    for (size_t f = 0; f < 30; ++f) {
      double sign = (f % 2 ? 1.0 : -1.0) * (paired_jitter || index % 2 ? 1.0 : -1.0);
      frames.push_back(cost(s) * (1.0 + jitter * sign * static_cast<double>(f % 5)));
    }
    Result r = test::fake_run(config.preset, 100, frames);
    DrawnErrorRecord e;
    e.copies_checked = 100;
    e.max_px = error(s);
    e.max = e.max_px / 1000.0;
    e.max_fraction = e.max_px / 500.0;
    if (on_screen) r.drawn_error = e;
    r.digest = std::to_string(static_cast<long long>(cost(s) * 1e6));
    return r;
  }
  AdviseHooks hooks() {
    AdviseHooks h;
    h.measure = [this](std::span<const AdviseConfig> configs) {
      calls.emplace_back(configs.begin(), configs.end());
      elapsed += seconds_per_measure;
      std::vector<Result> out;
      for (size_t i = 0; i < configs.size(); ++i) out.push_back(run(configs[i], i));
      if (stop_at && calls.size() - 1 == *stop_at)
        for (Result& r : out) r.partial = true;
      return out;
    };
    h.capacity = [this](std::span<const AdviseConfig> configs) {
      ++capacity_calls;
      CapacityRun run;
      for (const AdviseConfig& config : configs) {
        ModeCapacity mode;
        size_t fit = static_cast<size_t>(100 * 5.0 / cost(config.mode_switches()));
        CapacityPoint p;
        p.n = fit;
        mode.result.fit = p;
        mode.tried = {p, p};
        run.modes.push_back(mode);
      }
      return run;
    };
    h.stop_reason = [] { return std::string("interrupted"); };
    h.elapsed_s = [this] { return elapsed; };
    h.progress = [](const std::string&) {};
    return h;
  }
};

AdviseRule rule_of(double budget_ms) {
  AdviseRule rule;
  rule.budget_ms = budget_ms;
  rule.characters = 100;
  rule.cores = 2;
  return rule;
}

const AdviceCandidate& lever(const AdviceStep& step, const std::string& family) {
  for (const AdviceCandidate& c : step.candidates)
    if (c.lever == family) return c;
  throw std::logic_error("no lever " + family);
}

}  // namespace

TEST(AdviseSearch, TakesTheLeverThatSavesMostPerPixelUntilTheBudgetIsMet) {
  FakeCrowd crowd;
  AdviseRun run = run_advise(rule_of(5.5), AdviseConfig{}, crowd.hooks());
  const AdviceRecord& a = run.record;
  EXPECT_TRUE(a.met);
  EXPECT_EQ(a.outcome, "met");
  ASSERT_GE(a.steps.size(), 2u);
  // Step 1: packed adds no error, so it goes first; update_lod draws 3 px.
  const AdviceStep& first = a.steps[0];
  EXPECT_EQ(first.candidates[0].verdict, "base");
  EXPECT_EQ(lever(first, "vertex_format").verdict, "taken");
  EXPECT_EQ(lever(first, "update_lod").verdict, "past max error");
  EXPECT_EQ(lever(first, "sharing").verdict, "not the best");
  EXPECT_NEAR(lever(first, "sharing").saved.median, 4.0, 0.2);
  EXPECT_NEAR(lever(first, "sharing").error_px, 0.2, 1e-9);
  // No saving reads more than the base's frame (the same median, the lower of two).
  for (const AdviceStep& step : a.steps)
    for (const AdviceCandidate& c : step.candidates)
      EXPECT_LE(c.saved.median, step.candidates[0].metric.median) << c.lever;
  // Then sharing: 9.8 ms x 0.6 = 5.88, not yet 5.5; a coarser quantum then meets it.
  EXPECT_EQ(lever(a.steps[1], "sharing").verdict, "taken");
  EXPECT_EQ(run.final.switches.at("share"), "on");
  EXPECT_LE(a.final.metric.median, 5.5);
  EXPECT_EQ(a.final.verdict, "final");
  EXPECT_EQ(a.start.verdict, "start");
  EXPECT_NEAR(a.start.metric.median, 10, 0.3);
  // Capacities: the start's and the final's, from the capacity hook.
  ASSERT_EQ(a.capacities.size(), 2u);
  EXPECT_EQ(a.capacities[0].configuration, "start");
  EXPECT_EQ(a.capacities[1].configuration, "final");
  EXPECT_GT(*a.capacities[1].fit, *a.capacities[0].fit);
  EXPECT_EQ(
      a.configurations_measured, crowd.calls.size() == 0 ? 0 : [&] {
        size_t n = 0;
        for (auto& call : crowd.calls) n += call.size();
        return n;
      }());
  // The estimated capacity: copies x budget / median.
  EXPECT_EQ(a.start.capacity_estimate, static_cast<size_t>(std::floor(100 * 5.5 / a.start.metric.median)));
}

TEST(AdviseSearch, ALeverThatMeetsTheBudgetAloneBeatsAFreeOne) {
  FakeCrowd crowd;
  AdviseRun run = run_advise(rule_of(6.5), AdviseConfig{}, crowd.hooks());
  ASSERT_EQ(run.record.steps.size(), 1u);
  EXPECT_EQ(lever(run.record.steps[0], "sharing").verdict, "taken");
  EXPECT_EQ(lever(run.record.steps[0], "vertex_format").verdict, "not the best");
  EXPECT_TRUE(run.record.met);
}

TEST(AdviseSearch, ASavingInsideItsIntervalIsNotTaken) {
  FakeCrowd crowd;
  crowd.packed = 0.999;  // 0.01 ms against a jitter of up to 4%
  crowd.paired_jitter = false;
  AdviseRule rule = rule_of(1);
  rule.levers = {"vertex_format"};
  AdviseRun run = run_advise(rule, AdviseConfig{}, crowd.hooks());
  ASSERT_EQ(run.record.steps.size(), 1u);
  const AdviceCandidate& packed = lever(run.record.steps[0], "vertex_format");
  EXPECT_EQ(packed.verdict, "noise");
  EXPECT_LE(packed.saved.low, 0.0);
  EXPECT_FALSE(run.record.steps[0].taken);
  EXPECT_FALSE(run.record.met);
  EXPECT_EQ(run.record.outcome, "noise");
  EXPECT_NE(run.record.ran_out.find("outside its interval"), std::string::npos) << run.record.ran_out;
  EXPECT_EQ(run.final, AdviseConfig{});
  // No lever taken: one capacity search, of the start that is also the end.
  ASSERT_EQ(run.record.capacities.size(), 1u);
  EXPECT_EQ(run.record.capacities[0].configuration, "start and final");
}

TEST(AdviseSearch, StopsWhenEverySavingDrawsPastTheErrorAllowed) {
  FakeCrowd crowd;
  AdviseRule rule = rule_of(1);
  rule.levers = {"update_lod"};
  AdviseRun run = run_advise(rule, AdviseConfig{}, crowd.hooks());
  EXPECT_EQ(run.record.outcome, "max error");
  EXPECT_NE(run.record.ran_out.find("{max_error} 1 px"), std::string::npos) << run.record.ran_out;
  EXPECT_NE(run.record.ran_out.find("update_lod (--update-lod on)"), std::string::npos) << run.record.ran_out;
  // Allowed 5 px, it is taken.
  rule.max_error_px = 5;
  FakeCrowd again;
  EXPECT_EQ(lever(run_advise(rule, AdviseConfig{}, again.hooks()).record.steps[0], "update_lod").verdict, "taken");
}

TEST(AdviseSearch, MetAtTheStartTakesNoStep) {
  FakeCrowd crowd;
  AdviseRun run = run_advise(rule_of(20), AdviseConfig{}, crowd.hooks());
  EXPECT_TRUE(run.record.met);
  EXPECT_TRUE(run.record.steps.empty());
  EXPECT_EQ(crowd.calls.size(), 1u);
  EXPECT_EQ(run.record.final.digest, run.record.start.digest);
}

TEST(AdviseSearch, EveryGroupMeasuredHoldsTheBaseFirst) {
  FakeCrowd crowd;
  AdviseRule rule = rule_of(1);
  rule.side_by_side = 3;
  run_advise(rule, AdviseConfig{}, crowd.hooks());
  ASSERT_GE(crowd.calls.size(), 3u);
  EXPECT_EQ(crowd.calls[0].size(), 1u);  // the start alone
  // Step 1: five levers over three groups of the base and up to 2.
  EXPECT_EQ(crowd.calls[1].size(), 3u);
  EXPECT_EQ(crowd.calls[2].size(), 3u);
  EXPECT_EQ(crowd.calls[1][0], crowd.calls[2][0]);
  for (const auto& call : crowd.calls) EXPECT_LE(call.size(), 3u);
}

TEST(AdviseSearch, KeepsTheTransitionsLayersAndSwitchesTheUserGave) {
  FakeCrowd crowd;
  AdviseConfig start;
  start.switches = {{"transitions", "3"}, {"anim_layer", "action=wave,mask=spine,weight=0.5"}, {"index_order", "file"}};
  AdviseRun run = run_advise(rule_of(5.5), start, crowd.hooks());
  ASSERT_FALSE(run.record.steps.empty());
  for (const auto& call : crowd.calls)
    for (const AdviseConfig& config : call) {
      EXPECT_EQ(config.switches.at("transitions"), "3");
      EXPECT_EQ(config.switches.at("anim_layer"), "action=wave,mask=spine,weight=0.5");
    }
  EXPECT_EQ(run.record.start_options,
            "--anim-layer action=wave,mask=spine,weight=0.5 --index-order file --transitions 3");
  EXPECT_EQ(run.record.added_options.find("--transitions"), std::string::npos) << run.record.added_options;
  // The final options are a command line of their own: the start's and the levers'.
  EXPECT_EQ(run.record.final_options.find("--transitions 3"), run.record.final_options.find("--transitions"));
  EXPECT_NE(run.record.final_options.find("--transitions 3"), std::string::npos) << run.record.final_options;
}

TEST(AdviseSearch, TheTimeLimitAndAnInterruptEndTheSearchWithWholeSteps) {
  FakeCrowd slow;
  slow.seconds_per_measure = 100;
  AdviseRule rule = rule_of(1);
  rule.time_limit_s = 150;  // the start and step 1 run; step 2 does not start
  AdviseRun timed = run_advise(rule, AdviseConfig{}, slow.hooks());
  EXPECT_EQ(timed.record.outcome, "time limit");
  EXPECT_EQ(timed.record.steps.size(), 1u);
  EXPECT_FALSE(timed.partial);
  EXPECT_EQ(slow.capacity_calls, 0u);
  EXPECT_NE(timed.record.ran_out.find("{time_limit}"), std::string::npos);

  FakeCrowd cut;
  cut.stop_at = 2;  // step 2's measurement comes back partial
  AdviseRun interrupted = run_advise(rule_of(1), AdviseConfig{}, cut.hooks());
  EXPECT_TRUE(interrupted.partial);
  EXPECT_EQ(interrupted.record.outcome, "interrupted");
  EXPECT_EQ(interrupted.record.steps.size(), 1u);
  EXPECT_EQ(cut.capacity_calls, 0u);
}

TEST(AdviseLevers, EachFamilyStepsToItsNextSetting) {
  AdviseRule rule = rule_of(1);
  rule.cores = 4;
  Result base = test::fake_run("threaded", 100, {4, 4, 4}, 0.5);  // Animations 2 ms
  auto settings = [&](const AdviseConfig& config) {
    std::map<std::string, std::string> out;
    for (const LeverSetting& s : next_lever_settings(rule, config, base))
      out[s.family] = s.changes + (s.why_not.empty() ? "" : " (cannot)");
    return out;
  };
  AdviseConfig start;
  start.threads = 2;
  auto first = settings(start);
  EXPECT_EQ(first["sharing"], "--share on --share-quantum 1/60");
  EXPECT_EQ(first["update_lod"], "--update-lod on");
  EXPECT_EQ(first["mesh_lod"], "--mesh-lod on");
  EXPECT_EQ(first["anim_budget"], "--anim-budget 1");
  EXPECT_EQ(first["threads"], "--threads 4");
  EXPECT_EQ(first["vertex_format"], "--vertex-format packed");

  AdviseConfig later = start;
  later.switches = {{"share", "on"},
                    {"share_quantum", "1/60"},
                    {"update_lod", "on"},
                    {"anim_budget", "1"},
                    {"vertex_format", "packed"}};
  later.threads = 4;
  auto next = settings(later);
  EXPECT_EQ(next["sharing"], "--share-quantum 1/30");
  EXPECT_EQ(next["update_lod"], "--lod-thresholds 0.5,0.25,0.125");
  EXPECT_EQ(next["mesh_lod"], "--mesh-lod on (cannot)");  // not with sharing
  EXPECT_EQ(next["anim_budget"], "--anim-budget 0.5");
  EXPECT_EQ(next.count("threads"), 0u);
  EXPECT_EQ(next.count("vertex_format"), 0u);

  later.switches["share_quantum"] = "1/8";
  later.switches["lod_thresholds"] = "1,0.5,0.25";
  auto last = settings(later);
  EXPECT_EQ(last.count("sharing"), 0u);
  EXPECT_EQ(last.count("update_lod"), 0u);
  // Every core already (threads 0): no threads lever.
  EXPECT_EQ(settings(AdviseConfig{}).count("threads"), 0u);
}

TEST(AdviseRuleCheck, NamesTheSettingThatIsWrong) {
  AdviseRule rule = rule_of(16.7);
  EXPECT_TRUE(rule.Validate().empty());
  rule.budget_ms = 0;
  EXPECT_EQ(rule.Validate().str(), "budget must be a number of milliseconds above 0");
  rule = rule_of(16.7);
  rule.levers = {"sharing", "gpu"};
  EXPECT_NE(rule.Validate().str().find("levers 'gpu'"), std::string::npos);
  rule = rule_of(16.7);
  rule.metric.category = Category::Rasterizer;
  EXPECT_NE(rule.Validate().str().find("frame or Animations"), std::string::npos);
  rule = rule_of(16.7);
  rule.time_limit_s = 0;
  EXPECT_NE(rule.Validate().str().find("time_limit"), std::string::npos);
}

TEST(AdviceRecordCodec, RoundTripsAndNamesABadField) {
  FakeCrowd crowd;
  AdviseRun run = run_advise(rule_of(5.5), AdviseConfig{}, crowd.hooks());
  ResultDocument doc;
  doc.kind = "advise";
  doc.advice = run.record;
  doc.runs = {*run.start_run, *run.final_run};
  nlohmann::json j = result_document_to_json(doc);
  EXPECT_EQ(j["crowdprof"]["kind"], "advise");
  ResultDocument back = result_document_from_json(j, "a.json");
  ASSERT_TRUE(back.advice);
  EXPECT_EQ(advice_to_json(*back.advice), advice_to_json(run.record));
  EXPECT_EQ(back.runs.size(), 2u);

  nlohmann::json bad = j;
  bad["advice"]["steps"][0]["taken"] = 99;
  try {
    result_document_from_json(bad, "bad.json");
    FAIL() << "read an out-of-range step";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("advice.steps[0].taken"), std::string::npos) << e.what();
  }
  bad = j;
  bad["advice"]["start"]["metric_ms"]["low"] = "fast";
  EXPECT_THROW(result_document_from_json(bad, "bad.json"), InputError);
  bad = j;
  bad.erase("advice");
  EXPECT_THROW(result_document_from_json(bad, "bad.json"), InputError);
}

TEST(AdviseSearch, AStartPastTheErrorAllowedMayStillTakeALeverThatAddsNone) {
  FakeCrowd crowd;
  AdviseConfig start;
  start.switches = {{"update_lod", "on"}};  // 3 px already
  AdviseRule rule = rule_of(1);
  rule.levers = {"sharing", "vertex_format"};
  AdviseRun run = run_advise(rule, start, crowd.hooks());
  ASSERT_FALSE(run.record.steps.empty());
  EXPECT_EQ(lever(run.record.steps[0], "sharing").verdict, "past max error");  // 3.2 px: it adds 0.2
  EXPECT_EQ(lever(run.record.steps[0], "vertex_format").verdict, "taken");     // 3 px: it adds none
}

TEST(AdviseSearch, NoCopyOnScreenWeighsLeversByTimeAlone) {
  FakeCrowd crowd;
  crowd.on_screen = false;
  AdviseRun run = run_advise(rule_of(5.5), AdviseConfig{}, crowd.hooks());
  EXPECT_FALSE(run.record.start.error_measured);
  ASSERT_FALSE(run.record.steps.empty());
  for (const AdviceCandidate& c : run.record.steps[0].candidates) EXPECT_FALSE(c.error_measured) << c.lever;
  // update_lod would draw 3 px were anything drawn: here it is weighed by its saving.
  EXPECT_NE(lever(run.record.steps[0], "update_lod").verdict, "past max error");
}

TEST(AdviseSearch, ALeverFamilyWithNothingLeftSaysSo) {
  FakeCrowd crowd;
  AdviseRule rule = rule_of(1);
  rule.levers = {"threads"};  // every core already
  AdviseRun run = run_advise(rule, AdviseConfig{}, crowd.hooks());
  EXPECT_EQ(run.record.outcome, "no lever left");
  EXPECT_NE(run.record.ran_out.find("no lever of threads has a setting left to try"), std::string::npos)
      << run.record.ran_out;
  EXPECT_TRUE(run.record.steps.empty());
}
