// `check`: the U test against hand-worked values, noise that must not fail
// and a shift that must, exact counters and digest, and baselines that cannot
// be compared (exit 2 or 3, never a pass).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

#include "base/errors.h"
#include "gen/humanoid.h"
#include "frame/run_bench.h"
#include "gate/regression.h"
#include "reports/verdict_report.h"
#include "result/result_codec.h"
#include "result/run_match.h"
#include "test_support.h"

using namespace crowdprof;
using nlohmann::json;

namespace {

// Frame times as a loaded machine gives them: a few percent of jitter and
// now and then a frame several times slower. Box-Muller on mt19937's
// standardised output, so every platform draws the same numbers.
std::vector<double> noisy_frames(uint32_t seed, size_t count, double median_ms) {
  std::mt19937 rng(seed);
  auto uniform = [&] { return (static_cast<double>(rng()) + 0.5) / 4294967296.0; };
  std::vector<double> out;
  for (size_t i = 0; i < count; ++i) {
    double gauss = std::sqrt(-2.0 * std::log(uniform())) * std::cos(2.0 * M_PI * uniform());
    double ms = median_ms * (1.0 + 0.05 * gauss);
    if (uniform() < 0.05) ms *= 1.0 + 4.0 * uniform();  // a stall
    out.push_back(ms);
  }
  return out;
}

json small_result(const std::string& mode = "culled") {
  static const Character character = generate_humanoid({30, 800, 7});
  BenchConfig config;
  config.mode = find_mode(mode)->switches;
  config.mode_name = mode;
  config.crowd.copies = 6;
  CrowdBench bench(character, config);
  RunOptions options;
  options.frames = 10;
  options.warmup = 1;
  return result_to_json(run_bench(bench, "scenes/humanoid.glb", options));
}

}  // namespace

TEST(Check, ToleranceParsesPercentagesAndFractions) {
  EXPECT_DOUBLE_EQ(parse_tolerance("10%"), 0.10);
  EXPECT_DOUBLE_EQ(parse_tolerance("0.1"), 0.1);
  EXPECT_DOUBLE_EQ(parse_tolerance("2.5%"), 0.025);
  EXPECT_DOUBLE_EQ(parse_tolerance("0"), 0.0);
  EXPECT_DOUBLE_EQ(parse_tolerance("150%"), 1.5);
  for (const char* bad : {"ten", "-5%", "-0.1", "", "%", "10%%", "nan", "inf", "10 %", "0x10", "10", "1e400", "5000%"})
    EXPECT_THROW(parse_tolerance(bad), UsageError) << bad;
}

TEST(Check, MetricsByCategoryOrColumnName) {
  EXPECT_EQ(resolve_metric("frame"), "frame_ms");
  EXPECT_EQ(resolve_metric("Animations"), "animations_ms");
  EXPECT_EQ(resolve_metric("rasterizer"), "rasterizer_ms");
  EXPECT_EQ(resolve_metric("gpu_latency"), "gpu_latency_ms");
  EXPECT_EQ(resolve_metric("gpu_latency_ms"), "gpu_latency_ms");
  EXPECT_THROW(resolve_metric("Anim"), UsageError);
}

TEST(Check, MannWhitneyMatchesHandWorkedValues) {
  // No overlap: U = 0, mean 12.5, sigma = sqrt(25 * 11 / 12) = 4.787;
  // z = (12.5 - 0.5) / 4.787 = 2.5067, p = erfc(z / sqrt 2) = 0.012186
  // (scipy.stats.mannwhitneyu(..., method="asymptotic") gives the same).
  std::vector<double> low = {1, 2, 3, 4, 5}, high = {6, 7, 8, 9, 10};
  MannWhitney t = mann_whitney(low, high);
  EXPECT_DOUBLE_EQ(t.u, 0.0);
  EXPECT_NEAR(t.z, -2.50672, 1e-5);
  EXPECT_NEAR(t.p, 0.0121858, 1e-6);
  EXPECT_NEAR(mann_whitney(high, low).z, 2.50672, 1e-5);
  // Ties: ranks 1 | 3 3 3 | 6.5 x4 | 9.5 9.5 | 11, so R1 = 26.5 and U = 5.5;
  // sum(t^3 - t) = 24 + 60 + 6 = 90, variance = 30/12 * (12 - 90/110) = 27.95;
  // z = (9.5 - 0.5) / 5.2872 = 1.7022, p = 0.088714.
  std::vector<double> a = {1, 2, 2, 3, 3, 3}, b = {2, 3, 4, 4, 5};
  MannWhitney tied = mann_whitney(a, b);
  EXPECT_DOUBLE_EQ(tied.u, 5.5);
  EXPECT_NEAR(tied.z, -1.70222, 1e-5);
  EXPECT_NEAR(tied.p, 0.0887137, 1e-6);
  // All equal: no evidence either way.
  std::vector<double> same(10, 3.0);
  EXPECT_EQ(mann_whitney(same, same).p, 1.0);
}

TEST(Check, TwentyPercentSlowerIsFlaggedAndNoiseIsNot) {
  CheckOptions options;  // 10%, alpha 0.05
  for (uint32_t seed = 1; seed <= 20; ++seed) {
    std::vector<double> before = noisy_frames(seed, 120, 10.0);
    std::vector<double> again = noisy_frames(seed + 1000, 120, 10.0);
    std::vector<double> slower = noisy_frames(seed + 2000, 120, 12.0);
    MetricCheck noise = check_metric("frame", before, again, options);
    EXPECT_FALSE(noise.regressed) << "seed " << seed << ": " << noise.change << " p " << noise.test.p;
    MetricCheck shift = check_metric("frame", before, slower, options);
    EXPECT_TRUE(shift.regressed) << "seed " << seed << ": " << shift.change << " p " << shift.test.p;
    EXPECT_TRUE(shift.significant);
    EXPECT_NEAR(shift.change, 0.2, 0.05);
  }
}

TEST(Check, EitherConditionAloneDoesNotFail) {
  std::vector<double> before = noisy_frames(7, 200, 10.0), slower = noisy_frames(8, 200, 10.5);
  // 5% slower and significant, but within the tolerance.
  MetricCheck small = check_metric("frame", before, slower, {});
  EXPECT_TRUE(small.significant);
  EXPECT_FALSE(small.regressed);
  // 20% slower in the median of 3 frames each: beyond the tolerance, but too few
  // frames for the test, so the tolerance decides (and says so).
  std::vector<double> three = {10, 10.1, 9.9}, later = {12, 12.1, 11.9};
  MetricCheck few = check_metric("frame", three, later, {});
  EXPECT_TRUE(few.too_few_samples);
  EXPECT_TRUE(few.regressed);
  // Faster never fails.
  MetricCheck faster = check_metric("frame", slower, before, {});
  EXPECT_FALSE(faster.regressed);
}

// Significantly faster reads "faster" on the terminal and in the verdict
// table that Markdown, JUnit and the HTML page print; faster beyond the tolerance but not significant is not "within"
// it.
TEST(Check, FasterIsSaidAlikeOnEveryPage) {
  CheckOptions options;
  CheckResult result;
  result.metrics.push_back(check_metric("frame", noisy_frames(3, 120, 12.0), noisy_frames(4, 120, 10.0), options));
  ASSERT_LT(result.metrics[0].p_adjusted, options.alpha);
  EXPECT_TRUE(significantly_faster(result.metrics[0], options));
  EXPECT_NE(format_check(result, options).find("faster)"), std::string::npos) << format_check(result, options);
  EXPECT_EQ(check_verdict_table(result, options).metrics.at(0).verdict, "faster");
  EXPECT_NE(verdict_markdown(check_verdict_table(result, options)).find("| faster |"), std::string::npos)
      << verdict_markdown(check_verdict_table(result, options));
  // Three runs each: too few to test, so never called faster.
  const std::vector<double> three = {12, 12.1, 11.9}, later = {10, 10.1, 9.9};
  result.metrics[0] = check_metric("frame", three, later, options);
  EXPECT_FALSE(significantly_faster(result.metrics[0], options));
  EXPECT_NE(format_check(result, options).find("faster beyond 7% but not significant"), std::string::npos)
      << format_check(result, options);
  EXPECT_EQ(check_verdict_table(result, options).metrics.at(0).verdict, "no change");
}

TEST(Check, AResultAgainstItselfPassesAndAPlantedCounterFails) {
  Result baseline = result_from_json(small_result(), "fresh");
  CheckOptions options;
  options.metrics = {"frame_ms", "animations_ms"};
  CheckResult same = check_results(baseline, baseline, options);
  EXPECT_FALSE(same.regressed());
  EXPECT_NE(format_check(same, options).find("counters and digest match"), std::string::npos);

  Result planted = baseline;
  planted.counters.values.vertices_skinned += 800;
  CheckResult changed = check_results(baseline, planted, options);
  ASSERT_TRUE(changed.regressed());
  ASSERT_EQ(changed.counters.size(), 1u);
  EXPECT_EQ(changed.counters[0].name, "vertices_skinned");
  EXPECT_NE(format_check(changed, options).find("CHANGED counter vertices_skinned"), std::string::npos);

  Result other_digest = baseline;
  other_digest.digest = "0000000000000000";
  CheckResult digest = check_results(baseline, other_digest, options);
  EXPECT_TRUE(digest.regressed());
  EXPECT_NE(format_check(digest, options).find("CHANGED digest"), std::string::npos);

  // Targets of different arithmetics give other digests by design: not
  // compared (and said so), while the counters still are. Of one arithmetic,
  // or with a target not recorded, compared as before.
  Result avx3 = baseline, sse4 = other_digest;
  avx3.environment.simd = "AVX3";
  avx3.environment.fused_multiply_add = true;
  sse4.environment.simd = "SSE4";
  sse4.environment.fused_multiply_add = false;
  CheckResult across = check_results(avx3, sse4, options);
  EXPECT_FALSE(across.digest_differs());
  EXPECT_FALSE(across.regressed());
  EXPECT_NE(format_check(across, options).find("not compared: AVX3 fused multiply-adds, SSE4 did not"),
            std::string::npos)
      << format_check(across, options);
  EXPECT_NE(format_check(across, options).find("counters match, digest not compared"), std::string::npos);
  sse4.counters.values.vertices_skinned += 1;
  EXPECT_TRUE(check_results(avx3, sse4, options).regressed());
  Result avx2 = other_digest;
  avx2.environment.simd = "AVX2";
  avx2.environment.fused_multiply_add = true;
  EXPECT_TRUE(check_results(avx3, avx2, options).digest_differs());
  // A result from before the kernels fused records no field: separate, like SSE4.
  Result before = baseline;
  before.environment.simd = "AVX3";
  before.environment.fused_multiply_add = false;
  EXPECT_TRUE(check_results(before, sse4, options).digest_differs());
  EXPECT_FALSE(check_results(before, avx2, options).digest_differs());
  // Where both renderers skinned every character (hwskin, buffer, instanced,
  // compute, baked) the digest hashes palettes and records, which no SIMD
  // kernel computes: compared across arithmetics too.
  Result gpu_avx3 = avx3, gpu_sse4 = sse4;
  gpu_sse4.counters = gpu_avx3.counters;
  gpu_avx3.digest_cpu_vertices = gpu_sse4.digest_cpu_vertices = false;
  EXPECT_TRUE(check_results(gpu_avx3, gpu_sse4, options).digest_differs());
  EXPECT_NE(format_check(check_results(gpu_avx3, gpu_sse4, options), options).find("CHANGED digest"),
            std::string::npos);
  gpu_sse4.digest = gpu_avx3.digest;
  EXPECT_FALSE(check_results(gpu_avx3, gpu_sse4, options).regressed());
  // One of them skinned on the CPU (hwskin's fallback), or is older than the
  // field: not compared.
  gpu_sse4.digest = "0000000000000000";
  gpu_sse4.digest_cpu_vertices = true;
  EXPECT_FALSE(check_results(gpu_avx3, gpu_sse4, options).digest_differs());

  // A baseline from before the bench ordered vertices by their joints (no
  // vertex_order: the file's order) hashed them in another order: not
  // compared, and said so; the counters still are.
  Result file_order = baseline, joint_order = other_digest;
  file_order.vertex_order = "file";
  joint_order.vertex_order = "joints";
  CheckResult reordered = check_results(file_order, joint_order, options);
  EXPECT_FALSE(reordered.digest_differs());
  EXPECT_FALSE(reordered.regressed());
  EXPECT_NE(
      format_check(reordered, options)
          .find("not compared: the baseline hashed its vertices in the file's order, this run ordered by their joints"),
      std::string::npos)
      << format_check(reordered, options);
  EXPECT_NE(format_check(reordered, options).find("counters match, digest not compared (other vertex order)"),
            std::string::npos)
      << format_check(reordered, options);
  // Both reasons at once: both said.
  Result file_sse4 = file_order;
  file_sse4.environment.simd = "SSE4";
  file_sse4.environment.fused_multiply_add = false;
  Result joints_avx3 = joint_order;
  joints_avx3.environment.simd = "AVX3";
  joints_avx3.environment.fused_multiply_add = true;
  const std::string both = format_check(check_results(file_sse4, joints_avx3, options), options);
  EXPECT_NE(both.find("AVX3 fused multiply-adds, SSE4 did not (their last bits differ); the baseline hashed"),
            std::string::npos)
      << both;
  EXPECT_NE(both.find("(other arithmetic and vertex order)"), std::string::npos) << both;
  joint_order.counters.values.vertices_skinned += 1;
  EXPECT_TRUE(check_results(file_order, joint_order, options).regressed());
  // Palettes have no vertex order: GPU-skinned digests are compared.
  Result gpu_file = file_order, gpu_joints = other_digest;
  gpu_joints.vertex_order = "joints";
  gpu_file.digest_cpu_vertices = gpu_joints.digest_cpu_vertices = false;
  EXPECT_TRUE(check_results(gpu_file, gpu_joints, options).digest_differs());
}

TEST(Check, ResultsOfAnotherRunAreRefused) {
  Result baseline = result_from_json(small_result(), "base.json");
  json changed = small_result();
  changed["scene"]["characters"] = 7;
  Result other = result_from_json(changed, "other.json");
  try {
    require_same_run(baseline, other, "base.json");
    FAIL() << "another crowd size was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("characters 6 there, 7 here"), std::string::npos) << e.what();
  }
  Result threaded = result_from_json(small_result("threaded"), "threaded.json");
  EXPECT_THROW(require_same_run(baseline, threaded, "base.json"), InputError);
  Result elsewhere = baseline;
  elsewhere.run.file = "/elsewhere/scenes/humanoid.glb";  // the same file name: the same scene
  EXPECT_NO_THROW(require_same_run(baseline, elsewhere, "base.json"));
  // A build from before --index-order ran in file order: the same run when
  // nothing is drawn, another when a GL draws the triangles.
  Result older = baseline, newer = baseline;
  older.run.switches.index_order = IndexOrder::File;
  newer.run.switches.index_order = IndexOrder::Optimized;
  older.run.backend = newer.run.backend = "none";
  EXPECT_NO_THROW(require_same_run(older, newer, "base.json"));
  older.run.backend = newer.run.backend = "egl";
  EXPECT_THROW(require_same_run(older, newer, "base.json"), InputError);
  // Other switches are named as options, those that differ alone (issue 55:
  // it printed both "switches" objects as JSON).
  Result culled = baseline;
  culled.run.switches.animation_culling = !baseline.run.switches.animation_culling;
  try {
    require_same_run(baseline, culled, "base.json");
    FAIL() << "other switches were accepted";
  } catch (const InputError& e) {
    const std::string on = baseline.run.switches.animation_culling ? "on" : "off";
    const std::string off = baseline.run.switches.animation_culling ? "off" : "on";
    EXPECT_NE(std::string(e.what()).find("mode switches --culling " + on + " there, --culling " + off + " here"),
              std::string::npos)
        << e.what();
    EXPECT_EQ(std::string(e.what()).find('{'), std::string::npos) << e.what();
  }
}

TEST(Check, BrokenBaselinesAreInputErrors) {
  auto dir = test::scratch_dir("check_broken");
  json good = small_result();
  std::string text = good.dump();
  std::ofstream(dir / "truncated.json") << text.substr(0, text.size() / 2);
  std::ofstream(dir / "words.json") << "baseline: fast";
  std::ofstream(dir / "empty.json") << "";
  json future = good;
  future["crowdprof"]["format"] = 3;
  json short_samples = good;
  short_samples["samples"]["animations_ms"].erase(0);
  json negative = good;
  negative["samples"]["frame_ms"][0] = -1.0;
  json no_digest = good;
  no_digest.erase("digest");
  json counter_text = good;
  counter_text["counters"]["draw_calls"] = "none";
  for (const auto& [name, doc] : std::vector<std::pair<std::string, json>>{{"future", future},
                                                                           {"short", short_samples},
                                                                           {"negative", negative},
                                                                           {"no_digest", no_digest},
                                                                           {"counter_text", counter_text},
                                                                           {"array", json::array({1, 2})}})
    test::write_json(dir / (name + ".json"), doc);
  for (const char* name :
       {"truncated", "words", "empty", "future", "short", "negative", "no_digest", "counter_text", "array", "missing"})
    EXPECT_THROW(read_result((dir / (std::string(name) + ".json")).string()), InputError) << name;
  EXPECT_NO_THROW(read_result(test::write_json(dir / "good.json", good)));
}

TEST(CheckCli, OwnBaselinePassesAPlantedChangeFailsBadInputExits2Or3) {
  auto dir = test::scratch_dir("check_cli");
  std::string scene = (test::source_dir() / "scenes" / "humanoid.glb").string();
  std::string base = (dir / "base.json").string();
  auto r = test::run_cli("check --spread 0 '" + scene + "' -n 4 --frames 10 --warmup 1 --mode culled --baseline '" +
                         base + "' --update-baseline");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("baseline written"), std::string::npos) << r.out;
  // A baseline's luck counts against every later check: 20 runs by default.
  EXPECT_NE(r.out.find("the median of 20 runs by calibrated"), std::string::npos) << r.out;
  EXPECT_EQ(nlohmann::json::parse(std::ifstream(base))["runs"]["count"], 20);

  r = test::run_cli("check --result '" + base + "' --baseline '" + base + "'");
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  EXPECT_EQ(r.out.rfind("ok calibrated", 0), 0u) << r.out;

  // Recording a baseline writes no verdict: --junit - leaves stdout to its
  // line, while --json - takes stdout whole (the declared outputs decide).
  r = test::run_cli("check --result '" + base + "' --baseline '" + (dir / "again.json").string() +
                    "' --update-baseline --junit -");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.rfind("baseline written: ", 0), 0u) << r.out;
  r = test::run_cli("check --result '" + base + "' --baseline '" + (dir / "again.json").string() +
                    "' --update-baseline --json -");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.find("baseline written"), std::string::npos) << r.out;
  EXPECT_NO_THROW((void)json::parse(r.out)) << r.out;

  // A fresh run with the baseline's options (taken from it): the counters and
  // digest must match exactly; the timing's tolerance is wide, as a loaded
  // machine may be slower now than a second ago.
  r = test::run_cli("check --spread 0 '" + scene + "' --baseline '" + base + "' --tolerance 900%");
  EXPECT_EQ(r.status, 0) << r.out << r.err;

  json planted = json::parse(std::ifstream(base));
  planted["counters"]["poses_updated"] = planted["counters"]["poses_updated"].get<uint64_t>() + 1;
  std::string changed = test::write_json(dir / "planted.json", planted);
  r = test::run_cli("check --result '" + changed + "' --baseline '" + base + "'");
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("poses_updated"), std::string::npos) << r.out;

  for (const char* tolerance : {"ten", "-5%"}) {
    r = test::run_cli("check --result '" + base + "' --baseline '" + base + "' --tolerance " + tolerance);
    EXPECT_EQ(r.status, 2) << tolerance;
    EXPECT_NE(r.err.find("--tolerance"), std::string::npos) << r.err;
  }
  std::ofstream(dir / "cut.json") << json::parse(std::ifstream(base)).dump().substr(0, 200);
  r = test::run_cli("check --result '" + base + "' --baseline '" + (dir / "cut.json").string() + "'");
  EXPECT_EQ(r.status, 3);
  EXPECT_NE(r.err.find("cut.json: truncated JSON"), std::string::npos) << r.err;
  json bigger = json::parse(std::ifstream(base));
  bigger["scene"]["vertices"] = 12345;
  r = test::run_cli("check --result '" + base + "' --baseline '" + test::write_json(dir / "other.json", bigger) + "'");
  EXPECT_EQ(r.status, 3);
  EXPECT_NE(r.err.find("vertices"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}
