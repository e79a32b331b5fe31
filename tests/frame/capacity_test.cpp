// `capacity`: the search over the crowd size against fake cost curves (the
// exact N found, the sizes tried, the cap, nothing fitting, costs that do not
// grow with N), the rounds of several modes, the report (table, JSON, SVG) and
// the CLI on a tiny crowd: bad input, the JSON's schema (^C: interrupt_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "fake_run.h"
#include "frame/capacity.h"
#include "reports/capacity_report.h"
#include "reports/profile_table.h"
#include "measuring/stats.h"
#include "test_support.h"

using namespace crowdprof;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

using Cost = std::function<double(size_t)>;

CapacityPoint point(size_t n, double ms) {
  CapacityPoint p;
  p.n = n;
  p.median_ms = ms;
  p.frame_median_ms = ms;
  return p;
}

// Runs one search against a cost curve, as run_capacity would, returning the
// sizes tried in order.
std::vector<size_t> search(const CapacityRule& rule, const Cost& cost, std::vector<CapacityPoint>& tried) {
  std::vector<size_t> order;
  for (size_t n; (n = next_capacity_n(rule, tried)) != 0;) {
    EXPECT_LT(order.size(), 100u) << "the search does not end";
    if (order.size() >= 100) break;
    order.push_back(n);
    tried.push_back(point(n, cost(n)));
  }
  return order;
}

CapacityRule rule_of(double budget, size_t start, size_t cap, double resolution) {
  CapacityRule rule;
  rule.budget_ms = budget;
  rule.start = start;
  rule.cap = cap;
  rule.resolution = resolution;
  return rule;
}

}  // namespace

TEST(CapacitySearch, FindsTheExactSizeOfALinearCost) {
  // 0.125 ms a character (exact in binary): 160 characters take 20 ms.
  CapacityRule rule = rule_of(20.0, 10, 100'000, 0.0);
  std::vector<CapacityPoint> tried;
  std::vector<size_t> order = search(
      rule, [](size_t n) { return 0.125 * static_cast<double>(n); }, tried);
  EXPECT_EQ(order, (std::vector<size_t>{10, 20, 40, 80, 160, 320, 240, 200, 180, 170, 165, 162, 161}));
  CapacityResult result = capacity_result(rule, tried);
  ASSERT_TRUE(result.fit && result.fail);
  EXPECT_EQ(result.fit->n, 160u);
  EXPECT_DOUBLE_EQ(result.fit->median_ms, 20.0);
  EXPECT_EQ(result.fail->n, 161u);
  EXPECT_FALSE(result.capped);
  EXPECT_FALSE(result.non_monotonic);
}

TEST(CapacitySearch, StopsWithinTheResolution) {
  // An affine cost whose capacity is 1,234: 5% of the fit bounds the bracket.
  Cost cost = [](size_t n) { return 1.0 + 0.01 * static_cast<double>(n); };  // 1,234 → 13.34 ms
  CapacityRule rule = rule_of(13.345, 10, 100'000, 0.05);
  std::vector<CapacityPoint> tried;
  std::vector<size_t> order = search(rule, cost, tried);
  CapacityResult result = capacity_result(rule, tried);
  ASSERT_TRUE(result.fit && result.fail);
  EXPECT_LE(result.fit->n, 1234u);
  EXPECT_GT(result.fail->n, 1234u);
  size_t gap = result.fail->n - result.fit->n;
  EXPECT_LE(gap, static_cast<size_t>(std::floor(0.05 * static_cast<double>(result.fit->n))));
  // Bisection halves a bracket wider than that: it would have gone on.
  EXPECT_GT(2 * gap, static_cast<size_t>(std::floor(0.05 * static_cast<double>(result.fit->n))));
  EXPECT_LT(order.size(), 16u);  // 8 doublings to 1,280, then a few halvings of 640
}

TEST(CapacitySearch, CapAndNothingFitting) {
  CapacityRule rule = rule_of(16.6, 10, 100, 0.05);
  std::vector<CapacityPoint> tried;
  EXPECT_EQ(search(
                rule, [](size_t) { return 1.0; }, tried),
            (std::vector<size_t>{10, 20, 40, 80, 100}));
  CapacityResult result = capacity_result(rule, tried);
  EXPECT_TRUE(result.capped);
  ASSERT_TRUE(result.fit);
  EXPECT_EQ(result.fit->n, 100u);
  EXPECT_FALSE(result.fail);

  // Not even one character: bisection down to 1.
  tried.clear();
  EXPECT_EQ(search(
                rule, [](size_t n) { return 20.0 + static_cast<double>(n); }, tried),
            (std::vector<size_t>{10, 5, 2, 1}));
  result = capacity_result(rule, tried);
  EXPECT_FALSE(result.fit);
  ASSERT_TRUE(result.fail);
  EXPECT_EQ(result.fail->n, 1u);
  EXPECT_FALSE(result.capped);

  // The start above the cap starts at the cap.
  tried.clear();
  EXPECT_EQ(search(
                rule_of(16.6, 500, 100, 0.05), [](size_t) { return 1.0; }, tried),
            (std::vector<size_t>{100}));
}

TEST(CapacitySearch, ACostThatDoesNotGrowWithTheCrowd) {
  // A spike at 20 (another job started), still under the budget: the search
  // finds the boundary as before and says the medians were not monotonic.
  CapacityRule rule = rule_of(20.0, 10, 100'000, 0.0);
  std::vector<CapacityPoint> tried;
  search(
      rule, [](size_t n) { return n == 20 ? 15.0 : 0.125 * static_cast<double>(n); }, tried);
  CapacityResult result = capacity_result(rule, tried);
  ASSERT_TRUE(result.fit && result.fail);
  EXPECT_EQ(result.fit->n, 160u);
  EXPECT_EQ(result.fail->n, 161u);
  EXPECT_TRUE(result.non_monotonic);

  // A spike over the budget: the search ends on the first boundary it brackets.
  tried.clear();
  search(
      rule, [](size_t n) { return n >= 18 && n <= 25 ? 50.0 : 0.125 * static_cast<double>(n); }, tried);
  result = capacity_result(rule, tried);
  ASSERT_TRUE(result.fit && result.fail);
  EXPECT_EQ(result.fit->n, 17u);
  EXPECT_EQ(result.fail->n, 18u);

  // A history where a larger crowd fit than one that did not: the bracket is
  // below the smallest that did not fit, and the result says so.
  std::vector<CapacityPoint> odd = {point(10, 5.0), point(20, 30.0), point(40, 10.0)};
  EXPECT_EQ(next_capacity_n(rule, odd), 15u);
  result = capacity_result(rule, odd);
  EXPECT_EQ(result.fit->n, 10u);
  EXPECT_EQ(result.fail->n, 20u);
  EXPECT_TRUE(result.non_monotonic);
}

TEST(CapacitySearch, PartialPointsAreLeftOut) {
  CapacityRule rule = rule_of(20.0, 10, 1000, 0.0);
  std::vector<CapacityPoint> tried = {point(10, 1.0), point(20, 99.0)};
  tried.back().partial = true;  // cut short by ^C: its median means nothing
  EXPECT_EQ(next_capacity_n(rule, tried), 20u);
  CapacityResult result = capacity_result(rule, tried);
  EXPECT_EQ(result.fit->n, 10u);
  EXPECT_FALSE(result.fail);
}

TEST(CapacitySearch, RulesAndMetrics) {
  EXPECT_EQ(rule_of(16.6, 10, 100, 0.05).Validate().str(), "");
  EXPECT_NE(rule_of(0, 10, 100, 0.05).Validate().str(), "");
  EXPECT_NE(rule_of(-1, 10, 100, 0.05).Validate().str(), "");
  EXPECT_NE(rule_of(NAN, 10, 100, 0.05).Validate().str(), "");
  EXPECT_NE(rule_of(INFINITY, 10, 100, 0.05).Validate().str(), "");
  EXPECT_NE(rule_of(16.6, 0, 100, 0.05).Validate().str(), "");
  EXPECT_NE(rule_of(16.6, 200, 100, 0.05).Validate().str(), "");
  EXPECT_NE(rule_of(16.6, 10, 100, 1.0).Validate().str(), "");
  EXPECT_NE(rule_of(16.6, 10, 100, -0.1).Validate().str(), "");

  EXPECT_FALSE(parse_capacity_metric("frame")->category);
  EXPECT_EQ(parse_capacity_metric("Animations")->category, Category::Animations);
  EXPECT_EQ(parse_capacity_metric("animations")->category, Category::Animations);
  EXPECT_EQ(parse_capacity_metric("gpu_latency")->category, Category::GpuLatency);
  EXPECT_EQ(parse_capacity_metric("GPU Latency")->name(), "GPU Latency");
  EXPECT_FALSE(parse_capacity_metric("fps"));
  EXPECT_FALSE(parse_capacity_metric(""));
}

TEST(CapacityRun, RoundsMeasureEveryModeStillSearchingSideBySide) {
  // Mode 0 costs 1 ms a character, mode 1 0.25 ms; a category metric reads
  // Animations, half of each frame here.
  std::vector<ModeCapacity> modes(2);
  modes[0].mode = "slow";
  modes[1].mode = "fast";
  for (ModeCapacity& m : modes) m.rule = rule_of(10.0, 4, 1000, 0.0);
  std::vector<std::vector<size_t>> rounds;
  CapacityMeasure measure = [&](std::span<const size_t> active, std::span<const size_t> ns) {
    std::vector<Result> reports;
    rounds.emplace_back(ns.begin(), ns.end());
    for (size_t k = 0; k < active.size(); ++k) {
      double per = active[k] == 0 ? 2.0 : 0.5;  // frame ms per character; Animations gets half
      reports.push_back(
          test::fake_run(modes[active[k]].mode, ns[k], {per * static_cast<double>(ns[k]), 1e6, 0.0}, 0.5));
    }
    return reports;
  };
  CapacityRun run = run_capacity(modes, *parse_capacity_metric("Animations"), measure);
  EXPECT_FALSE(run.partial);
  ASSERT_EQ(run.modes.size(), 2u);
  // slow: Animations = N ms: 10 fits, 11 does not. fast: N / 4 ms: 40 and 41.
  EXPECT_EQ(run.modes[0].result.fit->n, 10u);
  EXPECT_EQ(run.modes[0].result.fail->n, 11u);
  EXPECT_EQ(run.modes[1].result.fit->n, 40u);
  EXPECT_EQ(run.modes[1].result.fail->n, 41u);
  EXPECT_DOUBLE_EQ(run.modes[1].result.fit->median_ms, 10.0);
  EXPECT_DOUBLE_EQ(run.modes[1].result.fit->frame_median_ms, 20.0);
  // Both modes in the first rounds; the slow one finished first.
  EXPECT_EQ(rounds[0], (std::vector<size_t>{4, 4}));
  EXPECT_EQ(rounds[1], (std::vector<size_t>{8, 8}));
  EXPECT_EQ(rounds.back().size(), 1u);
  EXPECT_EQ(run.modes[0].tried.front().round, 1u);
  EXPECT_EQ(run.modes[1].tried.back().round, rounds.size());
  // The reports at the bracket's ends are kept, for the JSON's runs and the page.
  ASSERT_TRUE(run.modes[1].fit_run && run.modes[1].fail_run);
  EXPECT_EQ(run.modes[1].fit_run->run.characters, 40u);
  EXPECT_EQ(run.modes[1].fail_run->run.characters, 41u);

  // A round cut short ends the run: its points are kept, marked, and left out.
  size_t calls = 0;
  CapacityMeasure interrupted = [&](std::span<const size_t> active, std::span<const size_t> ns) {
    std::vector<Result> reports = measure(active, ns);
    if (++calls == 3)
      for (Result& r : reports) r.partial = true;
    return reports;
  };
  run = run_capacity(modes, CapacityMetric{}, interrupted);
  EXPECT_TRUE(run.partial);
  EXPECT_EQ(calls, 3u);
  EXPECT_EQ(run.modes[0].tried.size(), 3u);
  EXPECT_TRUE(run.modes[0].tried.back().partial);
  // slow's frame is 2 ms a character: 4 fit, 8 did not, 6 was cut short.
  EXPECT_EQ(run.modes[0].tried[2].n, 6u);
  EXPECT_EQ(run.modes[0].result.fit->n, 4u);
  EXPECT_EQ(run.modes[0].result.fail->n, 8u);
  // Its table says so before and after (issue 55): not capacities, the cut
  // round left out, and its points those measured whole: 2 of 3, beside "2
  // whole rounds" (it said 3 points beside 2 rounds).
  std::string table = format_capacity(run);
  const std::string said =
      "INTERRUPTED: partial search, not capacities: round 3 was cut short and left out; the table holds the 2 whole "
      "rounds before it (points: those measured whole)\n";
  EXPECT_EQ(table.rfind(said, 0), 0u) << table;
  EXPECT_EQ(table.size() - table.rfind(said), said.size()) << table;
  std::istringstream lines(table.substr(said.size()));
  std::string header, row;
  std::getline(lines, header);
  std::getline(lines, row);
  EXPECT_EQ(row.substr(row.find_last_of(' ') + 1), "2") << table;
}

TEST(CapacityReport, TableJsonAndChart) {
  CapacityRun run;
  run.block = 5;
  run.frames = 3;
  run.warmup = 1;
  run.first = test::fake_run("master", 4, {1.0});
  run.first->run.character = "humanoid";
  ModeCapacity a;
  a.mode = "master";
  a.rule = rule_of(20.0, 10, 1000, 0.0);
  std::vector<CapacityPoint> tried;
  search(
      a.rule, [](size_t n) { return 0.125 * static_cast<double>(n); }, tried);
  a.tried = tried;
  a.result = capacity_result(a.rule, a.tried);
  ModeCapacity b;
  b.mode = "threaded";
  b.threads = 2;
  b.rule = rule_of(20.0, 10, 40, 0.0);
  b.tried = {point(10, 1.0), point(20, 2.0), point(40, 4.0)};
  b.result = capacity_result(b.rule, b.tried);
  run.modes = {a, b};

  std::string table = format_capacity(run);
  EXPECT_EQ(table.rfind("mode      threads  fits_n  fits_frame_ms  over_n  over_frame_ms  points\n", 0), 0u) << table;
  EXPECT_NE(table.find("\nmaster          1     160         20.000     161         20.125      13\n"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("\nthreaded        2      40          4.000       -              -       3\n"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("threaded: the cap of 40 characters fits"), std::string::npos) << table;

  json j = capacity_to_json(run);
  EXPECT_EQ(j["crowdprof"]["kind"], "capacity");
  EXPECT_DOUBLE_EQ(j["budget_ms"].get<double>(), 20.0);
  EXPECT_EQ(j["metric"], "frame");
  EXPECT_EQ(j["frames_per_point"], 3);
  EXPECT_EQ(j["partial"], false);
  ASSERT_EQ(j["modes"].size(), 2u);
  EXPECT_EQ(j["modes"][0]["points"].size(), 13u);
  EXPECT_EQ(j["modes"][0]["largest_fit"]["characters"], 160);
  EXPECT_EQ(j["modes"][0]["first_over"]["characters"], 161);
  EXPECT_EQ(j["modes"][0]["first_over"]["fits"], false);
  EXPECT_TRUE(j["modes"][1]["first_over"].is_null());
  EXPECT_EQ(j["modes"][1]["capped"], true);
  EXPECT_EQ(j["modes"][1]["threads"], 2);
  EXPECT_FALSE(j["scene"].contains("characters"));

  std::string svg = capacity_svg(run);
  EXPECT_EQ(test::occurrences(svg, "<g class=\"series\""), 2u);
  EXPECT_NE(svg.find("data-name=\"master\" data-geometry=\"line\" data-points=\"13\""), std::string::npos);
  EXPECT_NE(svg.find("data-name=\"threaded\" data-geometry=\"line\" data-points=\"3\""), std::string::npos);
  EXPECT_EQ(test::occurrences(svg, "<g class=\"budget\" data-value=\"20"), 1u) << svg;
}

TEST(CapacityCli, SearchesATinyCrowdAndWritesItsResults) {
  auto dir = test::scratch_dir("capacity_cli");
  std::string js = (dir / "c.json").string(), svg = (dir / "c.svg").string(), html = (dir / "c.html").string();
  // A budget nothing reaches: every mode is capped at 16 (4, 8, 16).
  auto r = test::run_cli("capacity '" + test::humanoid_glb() +
                         "' --budget 100000 --modes master,threaded --threads 2 --start 4 "
                         "--max-characters 16 --frames 2 --warmup 0 --block 1 --json '" +
                         js + "' --svg '" + svg + "' --html '" + html + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.rfind("mode ", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("\nmaster "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("the cap of 16 characters fits"), std::string::npos) << r.out;
  EXPECT_TRUE(r.err.empty()) << r.err;
  json j = json::parse(test::read_file(js));
  EXPECT_EQ(j["crowdprof"]["kind"], "capacity");
  EXPECT_EQ(j["scene"]["character"], "humanoid");
  ASSERT_EQ(j["modes"].size(), 2u);
  for (const json& m : j["modes"]) {
    EXPECT_EQ(m["capped"], true);
    EXPECT_EQ(m["largest_fit"]["characters"], 16);
    ASSERT_EQ(m["points"].size(), 3u);
    for (const json& p : m["points"]) {
      EXPECT_EQ(p["frames"], 2);
      for (const char* key : {"median_ms", "p95_ms", "p99_ms", "min_ms", "max_ms", "frame_median_ms"})
        EXPECT_GT(p[key].get<double>(), 0.0) << key;
      EXPECT_LE(p["p95_ms"].get<double>(), p["max_ms"].get<double>());
    }
  }
  EXPECT_EQ(j["modes"][1]["threads"], 2);
  std::string chart = test::read_file(svg);
  EXPECT_EQ(test::occurrences(chart, "<g class=\"series\""), 2u);
  EXPECT_EQ(test::occurrences(chart, "<g class=\"budget\""), 1u);
  // The bench result at each mode's capacity, and every size as compare's sweep.
  ASSERT_EQ(j["runs"].size(), 2u);
  EXPECT_EQ(j["runs"][0]["mode"], "master");
  EXPECT_EQ(j["runs"][1]["scene"]["characters"], 16);
  EXPECT_EQ(j["sweep"].size(), 6u);

  // The page: the runs at capacity, and the sizes tried with the budget; the
  // JSON makes the same page with `report`.
  std::string page = test::read_file(html);
  EXPECT_NE(page.find("data-chart=\"sweep\""), std::string::npos);
  EXPECT_EQ(test::occurrences(page, "<g class=\"budget\" data-value=\"100000"), 1u);
  EXPECT_NE(page.find("data-name=\"threaded\" data-geometry=\"line\" data-points=\"3\""), std::string::npos);
  // It leads with the capacity: budget, metric, and each mode's largest crowd
  // (capped here, so none was found over).
  size_t lead = page.find("<section id=\"capacity\">");
  ASSERT_NE(lead, std::string::npos);
  EXPECT_LT(lead, page.find("<section id=\"profile\">"));
  EXPECT_NE(page.find("fits 100000.000 ms</h2>", lead), std::string::npos);
  EXPECT_EQ(test::occurrences(page, "<td><b>16</b></td>"), 2u);
  EXPECT_EQ(test::occurrences(page, "over 16 (the cap fits)"), 2u);
  EXPECT_NE(page.find("capacity within 100000.000 ms of frame</title>"), std::string::npos);
  std::string again = (dir / "again.html").string();
  r = test::run_cli("report '" + js + "' -o '" + again + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(test::read_file(again).find("data-chart=\"sweep\""), std::string::npos);

  // A budget nothing fits: bisection down to one character, then no fit.
  r = test::run_cli("capacity '" + test::humanoid_glb() +
                    "' --budget 0.000001 --modes threaded --start 4 --frames 1 --warmup 0 "
                    "--metric Animations --json '" +
                    js + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  j = json::parse(test::read_file(js));
  EXPECT_EQ(j["metric"], "Animations");
  EXPECT_TRUE(j["modes"][0]["largest_fit"].is_null());
  EXPECT_EQ(j["modes"][0]["first_over"]["characters"], 1);
  EXPECT_NE(r.out.find("threaded: not even 1 character fits"), std::string::npos) << r.out;
}

TEST(CapacityCli, RefusesBadInputWithOneLine) {
  auto dir = test::scratch_dir("capacity_bad");
  std::string q = "'" + test::humanoid_glb() + "'";
  for (const std::string& bad :
       {std::string("--budget 0"), std::string("--budget -3"), std::string("--budget nan"), std::string(""),
        std::string("--budget 16.6 --metric fps"), std::string("--budget 16.6 --modes master,fastest"),
        std::string("--budget 16.6 --modes master,master"), std::string("--budget 16.6 --precision 1"),
        std::string("--budget 16.6 --start 0"), std::string("--budget 16.6 --start 50 --max-characters 20"),
        std::string("--budget 16.6 --block 0"), std::string("--budget 16.6 -n 10"),
        std::string("--budget 16.6 --modes hwskin --backend none"), "--budget 16.6 --svg " + q,
        "--budget 16.6 --json '" + (dir / "missing" / "c.json").string() + "'"}) {
    auto r = test::run_cli("capacity " + q + " --frames 1 --warmup 0 " + bad);
    EXPECT_EQ(r.status, 2) << bad << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << bad << "\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << bad;
  }
}

// A capacity point's median is the run's median frame: the capacity table, the
// runs table and the profile table (that frame's categories) give one value
// (issue 50: one run's median read 6.985 ms in one table and 6.94 in another,
// the mean of the two middle frames against the lower of them).
TEST(CapacityReport, APointsMedianIsTheProfileTablesMedianFrame) {
  for (const std::vector<double>& frames :
       {std::vector<double>{1.0, 2.0, 3.0, 10.0}, std::vector<double>{5.0, 4.0, 9.0}}) {
    const Result report = test::fake_run("threaded", 40, frames, 0.5);
    const CapacityPoint p = capacity_point(report, CapacityMetric{}, 40, 1);
    const double median_frame_ms = report.frame_records[median_frame(report.frame_records)].times.total_ms();
    EXPECT_DOUBLE_EQ(p.median_ms, median_frame_ms);
    EXPECT_DOUBLE_EQ(p.frame_median_ms, median_frame_ms);
    std::vector<double> totals;
    for (const FrameRecord& f : report.frame_records) totals.push_back(f.times.total_ms());
    EXPECT_DOUBLE_EQ(quantile(totals, 0.5), median_frame_ms) << "the runs table's median";
    char frametime[64];
    std::snprintf(frametime, sizeof frametime, "Frametime : %8.2fms", median_frame_ms);
    EXPECT_NE(format_profile(report).find(frametime), std::string::npos) << format_profile(report);
  }
}
