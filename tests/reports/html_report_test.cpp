// The HTML report without a browser: what each kind of report holds, that it
// needs nothing from the network, one colour per category and per mode in
// every chart, and bad result files refused with exit 3 and no report left.
// tests/browser/ loads the same reports in chromium.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>

#include "base/errors.h"
#include "fake_run.h"
#include "reports/chart_colours.h"
#include "reports/compare_report.h"
#include "reports/html_report.h"
#include "result/result_codec.h"
#include "test_support.h"

using namespace crowdprof;
using nlohmann::json;

namespace {

// A run as a bench would describe it, made up from frame times.
Result fake_bench(const std::string& mode, size_t characters, const std::vector<double>& frame_ms) {
  Result run = test::fake_run(mode, characters, frame_ms, 0.25);
  run.run.switches = ModeSwitches{};
  run.run.switches.animation_culling = true;
  return run;
}

json fake_result(const std::string& mode, size_t characters, const std::vector<double>& frame_ms) {
  Result run = fake_bench(mode, characters, frame_ms);
  run.run.character = "walker";
  run.run.warmup = 2;
  run.environment.cpu = "Test CPU <9000>";
  return result_to_json(run);
}

// The fill colour of the series (or legend entry) named `name` in a chart.
std::string series_colour(const std::string& html, const std::string& name) {
  std::smatch m;
  std::regex pattern("data-name=\"" + name +
                     "\" data-geometry=\"line\" data-points=\"[0-9]+\" fill=\"(#[0-9A-Fa-f]{6})\"");
  return std::regex_search(html, m, pattern) ? m[1].str() : "";
}

}  // namespace

TEST(HtmlReport, AHeadlineLeadsAndMoreRunsThanFitGetARowEach) {
  HtmlReportInput two;
  add_document(two, result_document_from_json(fake_result("threaded", 40, {0.7, 0.8, 0.9}), "a.json"), "a.json");
  add_document(two, result_document_from_json(fake_result("master", 40, {10, 12, 11}), "b.json"), "b.json");
  std::string html = html_report(two);
  const size_t headline = html.find("id=\"headline\""), profile = html.find("id=\"profile\"");
  ASSERT_NE(headline, std::string::npos);
  EXPECT_LT(headline, profile) << "the headline comes first";
  EXPECT_NE(html.find("<td class=\"key\">800 µs</td>"), std::string::npos) << "3 digits, µs below 1 ms";
  EXPECT_NE(html.find("<td class=\"key\">11.0 ms</td>"), std::string::npos);
  EXPECT_EQ(html.find("class=\"by-run\""), std::string::npos) << "two runs: side by side";
  EXPECT_NE(html.find("<table class=\"counters\">"), std::string::npos) << "counters as a table";
  HtmlReportInput six;
  for (const char* mode : {"master", "culled", "threaded", "shared", "budget", "hwskin"})
    add_document(six, result_document_from_json(fake_result(mode, 40, {1, 2, 3}), std::string(mode) + ".json"),
                 std::string(mode) + ".json");
  html = html_report(six);
  EXPECT_NE(html.find("class=\"by-run\""), std::string::npos) << "six runs: a row each";
  EXPECT_EQ(test::occurrences(html, "<tr><td class=\"name\">shared</td>"), 5u)
      << "headline, profile, runs, counters, side by side";
}

TEST(HtmlReport, GpuTimeByPassWithStatisticsOrWhyNot) {
  Result run = test::fake_run("compute", 40, {2, 3, 4}, 0.25);
  run.run.switches.passes = 2;  // prepass and colour
  run.run.pipeline_statistics_missing = "";
  for (FrameRecord& f : run.frame_records) {
    f.gpu_ms = 2.0;
    f.gpu_passes.ms = {0.5, 0.4, 0, 0.9};
    for (auto& pass : f.gpu_passes.stats) pass.fill(1234567);
  }
  HtmlReportInput input;
  record_samples(run);
  add_document(input, result_document_from_json(result_to_json(run), "a.json"), "a.json");
  for (FrameRecord& f : run.frame_records)
    for (auto& pass : f.gpu_passes.stats) pass.fill(std::nan(""));
  run.run.pipeline_statistics_missing = "softpipe lacks ARB_pipeline_statistics_query";
  record_samples(run);
  add_document(input, result_document_from_json(result_to_json(run), "b.json"), "b.json");
  std::string html = html_report(input);
  ASSERT_NE(html.find("id=\"gpu-passes\""), std::string::npos);
  EXPECT_EQ(test::occurrences(html, ">prepass</td>"), 2u);
  EXPECT_EQ(test::occurrences(html, ">shadows</td>"), 0u) << "2 passes draw no shadows";
  EXPECT_NE(html.find("<td>1,234,567</td>"), std::string::npos);
  EXPECT_NE(html.find("unavailable: softpipe lacks ARB_pipeline_statistics_query"), std::string::npos);
  EXPECT_NE(html.find("90% of the frame's GPU time"), std::string::npos) << "0.5 + 0.4 + 0.9 of 2 ms";
  HtmlReportInput plain;
  add_document(plain, result_document_from_json(fake_result("threaded", 40, {1, 2}), "c.json"), "c.json");
  EXPECT_EQ(html_report(plain).find("id=\"gpu-passes\""), std::string::npos) << "no GPU passes, no section";
}

TEST(HtmlReport, ABenchReportHoldsEverySectionAndNeedsNoNetwork) {
  HtmlReportInput input;
  add_document(input, result_document_from_json(fake_result("threaded", 40, {1, 2, 3, 4, 5, 6, 7, 8, 9, 20}), "a.json"),
               "a.json");
  input.screenshot_png = std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16) + std::string(20, '\0');
  std::string html = html_report(input);
  for (const char* section : {"id=\"profile\"", "id=\"frame-time\"", "id=\"categories\"", "id=\"environment\"",
                              "id=\"screenshot\"", "data:image/png;base64,iVBORw0KGgo"})
    EXPECT_NE(html.find(section), std::string::npos) << section;
  EXPECT_EQ(html.find("id=\"modes\""), std::string::npos) << "one run: nothing side by side";
  EXPECT_EQ(html.find("id=\"sweep\""), std::string::npos);
  // Self-contained: no URL of any kind but the data URI.
  for (const char* outside : {"http:", "https:", "src=\"/", "href=", "@import", "url("})
    EXPECT_EQ(html.find(outside), std::string::npos) << outside;
  EXPECT_NE(html.find("Test CPU &lt;9000&gt;"), std::string::npos) << "the environment, escaped";
  EXPECT_NE(html.find("data-charts=\"2\""), std::string::npos);
  // Frame time: one series of 10 points; the 16.7 ms budget drawn (a frame of
  // 20 ms), median/p95/p99 marked; categories: Animations and Rasterizer.
  EXPECT_NE(html.find("data-chart=\"frame-time\" data-series=\"1\""), std::string::npos);
  EXPECT_NE(html.find("data-name=\"threaded\" data-geometry=\"line\" data-points=\"10\""), std::string::npos);
  EXPECT_NE(html.find("<g class=\"budget\" data-value=\"16.6667\""), std::string::npos);
  EXPECT_NE(html.find("<g class=\"budget\" data-value=\"33.3333\""), std::string::npos);
  for (const char* mark : {"percentile median", "percentile p95", "percentile p99"})
    EXPECT_EQ(test::occurrences(html, "<g class=\"" + std::string(mark) + "\""), 1u) << mark;
  EXPECT_NE(html.find("data-chart=\"categories\" data-series=\"2\""), std::string::npos);
  EXPECT_EQ(test::occurrences(html, "data-geometry=\"area\" data-points=\"10\""), 2u);
  EXPECT_NE(html.find("frame (0 = the first measured, after 2 warm-up)"), std::string::npos);
  EXPECT_NE(html.find("walker \u00d7 40, backend none"), std::string::npos)
      << "the character (no file recorded) and backend in titles";
}

TEST(HtmlReport, FastFramesNameTheBudgetsInsteadOfSquashingTheChart) {
  HtmlReportInput input;
  add_document(input, result_document_from_json(fake_result("threaded", 40, {1, 1.2, 1.1}), "a.json"), "a.json");
  std::string html = html_report(input);
  EXPECT_EQ(test::occurrences(html, "<g class=\"budget\""), 0u);
  EXPECT_EQ(test::occurrences(html, "class=\"budget above\""), 2u);
}

TEST(HtmlReport, SeveralRunsSideBySideWithASweepAndOneColourPerMode) {
  HtmlReportInput input;
  add_document(input, result_document_from_json(fake_result("threaded", 40, {3, 3, 3}), "t40.json"), "t40.json");
  add_document(input, result_document_from_json(fake_result("master", 40, {9, 9, 10}), "m40.json"), "m40.json");
  add_document(input, result_document_from_json(fake_result("threaded", 80, {6, 6, 6}), "t80.json"), "t80.json");
  add_document(input, result_document_from_json(fake_result("master", 80, {18, 19, 18}), "m80.json"), "m80.json");
  std::string html = html_report(input);
  EXPECT_NE(html.find("data-chart=\"modes\" data-series=\"4\""), std::string::npos);
  EXPECT_NE(html.find("data-chart=\"sweep\" data-series=\"2\""), std::string::npos);
  EXPECT_EQ(test::occurrences(html, "data-geometry=\"line\" data-points=\"2\""), 2u) << "two sizes per mode";
  EXPECT_NE(html.find("characters (log scale)"), std::string::npos);
  // Labels tell the runs apart; the sweep's lines carry the plain mode.
  EXPECT_NE(html.find("data-name=\"master n=80\""), std::string::npos);
  // A preset has its colour whatever else is in the report, in every chart.
  EXPECT_EQ(series_colour(html, "master"), ModeColours().colour("master"));
  EXPECT_EQ(series_colour(html, "threaded"), "#0072B2");
  EXPECT_EQ(series_colour(html, "master"), "#D55E00");
}

TEST(ChartColours, OneColourPerCategoryAndPerModeInEveryChart) {
  ModeColours a, b;
  EXPECT_STREQ(a.colour("custom"), a.colour("custom"));
  EXPECT_STRNE(a.colour("custom"), a.colour("master"));
  EXPECT_STREQ(a.colour("hwskin"), b.colour("hwskin")) << "asked in another order, the same colour";
  std::set<std::string> categories;
  for (size_t c = 0; c < kCategoryCount; ++c) categories.insert(category_colour(static_cast<Category>(c)));
  EXPECT_EQ(categories.size(), kCategoryCount);

  // The compare SVG: a mode's line and a category's bar segment have their
  // colours whichever modes and categories the chart shows.
  Comparison comparison;
  comparison.runs = {test::fake_run("hwskin", 40, {3, 3}, 0.5), test::fake_run("master", 40, {9, 9}, 1.0)};
  std::string svg = comparison_svg(comparison);
  EXPECT_NE(svg.find("data-name=\"hwskin\" data-geometry=\"line\" data-points=\"2\" fill=\"#009E73\""),
            std::string::npos);
  EXPECT_NE(svg.find("fill=\"" + std::string(category_colour(Category::Rasterizer)) + "\"><title>Rasterizer"),
            std::string::npos);
  EXPECT_NE(svg.find("fill=\"" + std::string(category_colour(Category::Animations)) + "\"><title>Animations"),
            std::string::npos);
}

TEST(HtmlReport, ACheckShowsItsVerdictPerMetricAgainstTheTolerance) {
  json base = fake_result("threaded", 40, std::vector<double>(30, 2.0));
  std::vector<double> slower(30, 3.0);
  json current = fake_result("threaded", 40, slower);
  CheckOptions options;
  options.metrics = {"frame_ms", "animations_ms", "rasterizer_ms"};
  HtmlReportInput input;
  add_document(input, result_document_from_json(current, "current"), "current");
  input.check =
      CheckSection{check_results(result_from_json(base, "base.json"), result_from_json(current, "current"), options),
                   options, "base.json"};
  std::string html = html_report(input);
  EXPECT_NE(html.find("data-chart=\"verdict\" data-series=\"3\""), std::string::npos);
  EXPECT_EQ(test::occurrences(html, "data-verdict=\"REGRESSION\""), 3u);
  EXPECT_NE(html.find("class=\"tolerance\""), std::string::npos);
  EXPECT_NE(html.find("Check against base.json: <span class=\"regression\">REGRESSION"), std::string::npos);
  EXPECT_EQ(html.find("<td>0.0000</td>"), std::string::npos) << "a tiny p-value is not 0";
  EXPECT_NE(html.find("e-"), std::string::npos) << "it is written as 1.2e-11";
}

TEST(HtmlReport, ResultFilesOfEveryKindAreReadAndBadOnesRefused) {
  auto dir = test::scratch_dir("html_report_files");
  json bench = fake_result("culled", 10, {2, 2, 3});
  HtmlReportInput input;
  add_result_file(input, test::write_json(dir / "bench.json", bench));
  EXPECT_EQ(input.runs.size(), 1u);

  Comparison comparison;
  comparison.runs = {fake_bench("master", 10, {4, 4}), fake_bench("culled", 10, {3, 3})};
  comparison.sweep = {fake_bench("master", 5, {2}), fake_bench("culled", 5, {1.5}), comparison.runs[0],
                      comparison.runs[1]};
  add_result_file(input, test::write_json(dir / "compare.json", comparison_to_json(comparison)));
  EXPECT_EQ(input.runs.size(), 3u);
  EXPECT_EQ(input.sweep.size(), 4u);

  json older = bench;
  older["crowdprof"]["format"] = 0;
  json no_samples = bench;
  no_samples.erase("samples");
  json other_kind = bench;
  other_kind["crowdprof"]["kind"] = "spreadsheet";
  json bad_sweep = comparison_to_json(comparison);
  bad_sweep["sweep"][0].erase("mode");
  std::ofstream(dir / "cut.json") << bench.dump().substr(0, 100);
  std::ofstream(dir / "words.json") << "frame,mode\n0,master\n";
  struct Bad {
    const char* name;
    json doc;
    const char* says;
  };
  for (const Bad& bad :
       {Bad{"older", older, "result format 0"}, Bad{"no_samples", no_samples, "samples"},
        Bad{"other_kind", other_kind, "'spreadsheet'"}, Bad{"array", json::array({1}), "not a crowdprof result"},
        Bad{"bad_sweep", bad_sweep, "sweep"}}) {
    HtmlReportInput fresh;
    try {
      add_result_file(fresh, test::write_json(dir / (std::string(bad.name) + ".json"), bad.doc));
      ADD_FAILURE() << bad.name << " was read";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(bad.says), std::string::npos) << bad.name << ": " << e.what();
      EXPECT_NE(std::string(e.what()).find(bad.name), std::string::npos) << "names the file: " << e.what();
    }
  }
  HtmlReportInput fresh;
  EXPECT_THROW(add_result_file(fresh, (dir / "cut.json").string()), InputError);
  EXPECT_THROW(add_result_file(fresh, (dir / "words.json").string()), InputError);
  EXPECT_THROW(require_png("GIF89a and more bytes than a PNG header needs", "x.png"), InputError);
}

TEST(ReportCli, WritesOneFileFromResultsAndNoneFromBadInput) {
  auto dir = test::scratch_dir("report_cli");
  std::string a = test::write_json(dir / "a.json", fake_result("master", 10, {2, 3, 2}));
  std::string b = test::write_json(dir / "b.json", fake_result("threaded", 10, {1, 1, 1}));
  std::string out = (dir / "report.html").string();
  auto r = test::run_cli("report '" + a + "' '" + b + "' -o '" + out + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  std::ifstream in(out);
  std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(html.find("data-chart=\"modes\" data-series=\"2\""), std::string::npos);

  json doc = json::parse(std::ifstream(a));
  std::ofstream(dir / "cut.json") << doc.dump().substr(0, doc.dump().size() / 2);
  json older = doc;
  older["crowdprof"]["format"] = 0;
  test::write_json(dir / "older.json", older);
  std::ofstream(dir / "foreign.json") << R"({"name": "some other tool", "frames": [1, 2]})";
  for (const char* bad : {"cut.json", "older.json", "foreign.json", "missing.json"}) {
    std::string target = (dir / (std::string(bad) + ".html")).string();
    r = test::run_cli("report '" + a + "' '" + (dir / bad).string() + "' -o '" + target + "'");
    EXPECT_EQ(r.status, 3) << bad << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(bad), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(target)) << bad << ": a report was left behind";
  }
  r = test::run_cli("report '" + a + "' -o '" + a + "'");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(json::parse(std::ifstream(a)), doc) << "the input is untouched";
  r = test::run_cli("report '" + a + "' -o '" + out + "' --screenshot '" + b + "'");
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_NE(r.err.find("not a PNG"), std::string::npos) << r.err;
}

TEST(ReportCli, HtmlOnBenchCompareAndCheck) {
  auto dir = test::scratch_dir("report_html_commands");
  std::string scene = (test::source_dir() / "scenes" / "humanoid.glb").string();
  std::string small = "-n 4 --frames 6 --warmup 1 -q";
  std::string bench = (dir / "bench.html").string(), json_path = (dir / "bench.json").string();
  auto r = test::run_cli("bench '" + scene + "' " + small + " --mode culled --json '" + json_path + "' --html '" +
                         bench + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  std::string html = test::read_file(bench);
  EXPECT_NE(html.find("data-name=\"culled\" data-geometry=\"line\" data-points=\"6\""), std::string::npos);
  EXPECT_NE(html.find("humanoid.glb \u00d7 4, backend none"), std::string::npos) << "the file, not the root node";
  // The page made by bench --html is the one report makes of its JSON.
  std::string again = (dir / "again.html").string();
  ASSERT_EQ(test::run_cli("report '" + json_path + "' -o '" + again + "'").status, 0);
  // The same charts (the scene path is stored relative to the JSON, so the profile's runs table differs).
  auto charts = [](const std::string& page) {
    size_t frame_time = page.find("<section id=\"frame-time\">"), profile = page.find("<section id=\"profile\">");
    return page.substr(frame_time, profile - frame_time) + page.substr(page.find("<section id=\"categories\">"));
  };
  EXPECT_EQ(charts(test::read_file(again)), charts(html));

  std::string compare = (dir / "compare.html").string();
  r = test::run_cli("compare '" + scene + "' " + small + " --modes master,threaded --sweep n=2,4 --html '" + compare +
                    "'");
  ASSERT_EQ(r.status, 0) << r.err;
  html = test::read_file(compare);
  EXPECT_NE(html.find("data-chart=\"modes\" data-series=\"2\""), std::string::npos);
  EXPECT_NE(html.find("data-chart=\"sweep\" data-series=\"2\""), std::string::npos);

  std::string base = (dir / "base.json").string(), check = (dir / "check.html").string();
  ASSERT_EQ(test::run_cli("check --spread 0 '" + scene + "' " + small + " --baseline '" + base +
                          "' --update-baseline --runs 2")
                .status,
            0);
  r = test::run_cli("check --result '" + base + "' --baseline '" + base + "' --metric frame,Animations --html '" +
                    check + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  html = test::read_file(check);
  EXPECT_NE(html.find("data-chart=\"verdict\" data-series=\"2\""), std::string::npos);
  EXPECT_EQ(test::occurrences(html, "data-verdict=\"ok\""), 2u);
  EXPECT_NE(html.find("data-name=\"baseline\""), std::string::npos);
  EXPECT_NE(html.find("data-name=\"current\""), std::string::npos);

  // --html is an output like the others: never the input, never another output.
  r = test::run_cli("bench '" + scene + "' " + small + " --json '" + bench + "' --html '" + bench + "'");
  EXPECT_EQ(r.status, 2) << r.err;
  r = test::run_cli("check --result '" + base + "' --baseline '" + base + "' --html '" + base + "'");
  EXPECT_EQ(r.status, 2) << r.err;
}

TEST(HtmlReport, SavingsAreDrawnAsCostAgainstErrorWithTheirFront) {
  HtmlReportInput input;
  json exact = fake_result("threaded", 40, {3, 3, 3}), lod = fake_result("threaded+update_lod=on", 40, {1, 1, 1}),
       slow = fake_result("master", 40, {9, 9, 9}), bent = fake_result("budget", 40, {0.5, 0.5, 0.5});
  auto error = [](double px) {
    return json{{"copies_checked", 40},
                {"copies_deviating", px > 0 ? 30 : 0},
                {"vertices", 400},
                {"copy_stride", 1},
                {"max", px / 100},
                {"rms", px / 300},
                {"max_fraction", px / 200},
                {"rms_fraction", px / 600},
                {"max_px", px},
                {"rms_px", px / 3},
                {"mesh_max", 0},
                {"switches_per_second", 0}};
  };
  exact["drawn_error"] = error(0);
  lod["drawn_error"] = error(0.5);
  bent["drawn_error"] = error(2.5);  // the fastest, past the 1 px threshold: never on the front
  add_document(input, result_document_from_json(exact, "t.json"), "t.json");
  add_document(input, result_document_from_json(lod, "l.json"), "l.json");
  add_document(input, result_document_from_json(bent, "b.json"), "b.json");
  add_document(input, result_document_from_json(slow, "m.json"), "m.json");  // no drawn error: no point
  const std::string html = html_report(input);
  // The front, then one dot per run with an error.
  EXPECT_NE(html.find("data-chart=\"cost-error\" data-series=\"4\""), std::string::npos) << html.substr(0, 400);
  EXPECT_NE(html.find("data-name=\"Pareto front\" data-geometry=\"line\" data-points=\"2\""), std::string::npos);
  EXPECT_NE(html.find("data-name=\"budget (past 1 px)\""), std::string::npos);
  // The same points as a table, right after the speedups and before any chart.
  const size_t table = html.find("<table class=\"cost-error\">");
  ASSERT_NE(table, std::string::npos);
  EXPECT_LT(html.find("id=\"speedups\""), table);
  EXPECT_LT(table, html.find("<svg"));
  EXPECT_EQ(test::occurrences(html.substr(table, html.find("</table>", table) - table), "<tr><td class=\"name\">"), 3u)
      << "a row per run with a drawn error";
  EXPECT_NE(html.find("<td class=\"name\">budget</td><td>0.500</td>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"name\">past 1 px</td>"), std::string::npos);
  HtmlReportInput one;
  add_document(one, result_document_from_json(exact, "t.json"), "t.json");
  add_document(one, result_document_from_json(slow, "m.json"), "m.json");
  EXPECT_EQ(html_report(one).find("cost-error"), std::string::npos) << "one point weighs nothing";
}

TEST(HtmlReport, AnABCheckLeadsWithItsVerdictPerMetric) {
  HtmlReportInput input;
  add_document(input, result_document_from_json(fake_result("threaded", 40, {2, 2, 2}), "base"), "base");
  add_document(input, result_document_from_json(fake_result("threaded", 40, {3, 3, 3}), "current"), "current");
  GateTable table;
  GateRow frame;
  frame.metric = "frame";
  frame.base_ms = 2;
  frame.current_ms = 3;
  frame.change = 0.5;
  frame.has_interval = true;
  frame.change_low = 0.4;
  frame.change_high = 0.6;
  frame.p = 0.001;
  frame.verdict = "slower";
  frame.failed = true;
  frame.why = "slower by more than the 5% tolerance";
  table.metrics = {frame};
  table.work_compared = true;
  input.gate = GateSection{table, 0.05, 0.95, "/builds/base/crowdprof"};
  const std::string html = html_report(input);
  const size_t verdict = html.find("<table class=\"verdict\">");
  ASSERT_NE(verdict, std::string::npos);
  EXPECT_LT(verdict, html.find("id=\"headline\"")) << "the verdict first";
  EXPECT_NE(html.find("<title>crowdprof report: walker \u00d7 40, backend none, A/B check against crowdprof: FAILED"),
            std::string::npos);
  EXPECT_NE(html.find("<td class=\"name\"><span class=\"regression\">FAILED</span> (slower)</td><td "
                      "class=\"key\">+50.0%</td><td>[+40.0%, +60.0%]</td><td>up to +5.0%</td>"),
            std::string::npos);
  EXPECT_NE(html.find("slower by more than the 5% tolerance"), std::string::npos);
}

TEST(HtmlReport, CountersAtZeroAreFoldedAway) {
  Result run = fake_bench("threaded", 40, {1, 2, 3});
  run.counters.present.fill(true);
  run.counters.values = {};
  run.counters.values.poses_updated = 40;
  HtmlReportInput input;
  add_result(input, run, "a.json");
  const std::string html = html_report(input);
  const size_t counters = html.find("id=\"counters\""), folded = html.find("<details class=\"zero-counters\">");
  ASSERT_NE(folded, std::string::npos);
  EXPECT_LT(html.find("id=\"frame-time\""), counters) << "the frame chart before the counters";
  EXPECT_LT(html.find(">poses_updated</td>"), folded) << "counted: in the table";
  EXPECT_NE(html.find("<summary>" + std::to_string(kCounterFields.size() - 1) + " counters were zero in every run"),
            std::string::npos);
}
