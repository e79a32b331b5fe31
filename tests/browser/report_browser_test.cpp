// The HTML report in a real browser: Debian's chromium, headless, loads each
// kind of report (bench, several results, compare with a sweep, check, a
// screenshot) and this test reads back the DOM after the page's scripts ran.
// It fails on a script error, on a chart missing, and on a chart whose series
// or points, as the browser parsed and drew them, differ from the result file.
// Skips, saying why, when chromium is not installed (./setup.sh test installs it).
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>

#include <nlohmann/json.hpp>

#include "browser/browser_page.h"

using namespace crowdprof::test;
using nlohmann::json;

TEST(ReportInBrowser, ABenchReport) {
  REQUIRE_CHROMIUM();
  Fixture f{crowdprof::test::scratch_dir("browser_bench")};
  f.run("bench '" + f.scene + "' " + f.small + " --json '" + f.path("b.json") + "' --html '" + f.path("b.html") + "'");
  std::string dom = dump_dom(f.path("b.html"));
  expect_clean_page(dom, "bench");
  auto charts = drawn_charts(dom);
  EXPECT_EQ(charts.size(), 2u);
  expect_runs_drawn(charts, {json::parse(std::ifstream(f.path("b.json")))}, "bench");
  // The frame chart first, the counters after it with those at zero folded away.
  size_t frame_chart = first_at(dom, "data-chart=\"frame-time\""), counters = first_at(dom, "id=\"counters\"");
  ASSERT_NE(counters, std::string::npos);
  EXPECT_LT(first_at(dom, "id=\"headline\""), frame_chart);
  EXPECT_LT(frame_chart, counters) << "the frame chart before the counters";
  EXPECT_LT(frame_chart, first_at(dom, "id=\"profile\""));
  std::smatch zero;
  ASSERT_TRUE(std::regex_search(dom, zero, std::regex("<summary>([0-9]+) counters were zero in every run</summary>")));
  EXPECT_GT(std::stoi(zero[1].str()), 0);
  EXPECT_NE(dom.find("humanoid.glb \u00d7 4, backend none"), std::string::npos) << "titles name the file";
}

TEST(ReportInBrowser, SeveralResultsSideBySideAndTheirSweep) {
  REQUIRE_CHROMIUM();
  Fixture f{crowdprof::test::scratch_dir("browser_several")};
  std::vector<json> runs;
  std::string files;
  for (const char* spec : {"master -n 2", "threaded -n 2", "master -n 4", "threaded -n 4"}) {
    std::string name = f.path("r" + std::to_string(runs.size()).append(".json"));
    f.run("bench '" + f.scene + "' --frames 8 --warmup 1 -q --mode " + spec + " --json '" + name + "'");
    runs.push_back(json::parse(std::ifstream(name)));
    files += " '" + name + "'";
  }
  f.run("report" + files + " -o '" + f.path("several.html") + "'");
  std::string dom = dump_dom(f.path("several.html"));
  expect_clean_page(dom, "several");
  auto charts = drawn_charts(dom);
  expect_runs_drawn(charts, runs, "several");
  auto modes = charts_named(charts, "modes");
  ASSERT_EQ(modes.size(), 1u);
  EXPECT_EQ(modes[0]->bar_segments.size(), runs.size());
  auto sweep = charts_named(charts, "sweep");
  ASSERT_EQ(sweep.size(), 1u);
  EXPECT_EQ(sweep[0]->drawn_series, "2") << "master and threaded";
  for (const auto& [name, points] : sweep[0]->series) EXPECT_EQ(points, "2") << name << ": two crowd sizes";
}

TEST(ReportInBrowser, ACompareReportWithASweep) {
  REQUIRE_CHROMIUM();
  Fixture f{crowdprof::test::scratch_dir("browser_compare")};
  // Five modes: more than fit side by side (the page must stay within 1280 px).
  f.run("compare '" + f.scene + "' " + f.small +
        " --modes master,culled,threaded,shared,budget --sweep n=1,2,4 --json '" + f.path("c.json") + "' --html '" +
        f.path("c.html") + "'");
  json doc = json::parse(std::ifstream(f.path("c.json")));
  // The page compare wrote and the one report makes of its JSON.
  f.run("report '" + f.path("c.json") + "' -o '" + f.path("c2.html") + "'");
  for (const char* page : {"c.html", "c2.html"}) {
    std::string dom = dump_dom(f.path(page));
    expect_clean_page(dom, page);
    // The speedups and each saving's price, as tables, before every chart.
    expect_leads(dom, "id=\"speedups\"", page);
    expect_leads(dom, "<table class=\"cost-error\">", page);
    EXPECT_LT(first_at(dom, "id=\"headline\""), first_at(dom, "id=\"speedups\"")) << page;
    auto charts = drawn_charts(dom);
    expect_runs_drawn(charts, doc["runs"].get<std::vector<json>>(), page);
    auto modes = charts_named(charts, "modes");
    ASSERT_EQ(modes.size(), 1u) << page;
    EXPECT_EQ(modes[0]->bar_segments.size(), doc["runs"].size()) << page;
    std::map<std::string, size_t> sizes_per_mode;
    for (const json& row : doc["sweep"]) ++sizes_per_mode[row["mode"].get<std::string>()];
    auto sweep = charts_named(charts, "sweep");
    ASSERT_EQ(sweep.size(), 1u) << page;
    EXPECT_EQ(sweep[0]->drawn_series, std::to_string(sizes_per_mode.size())) << page;
    for (const auto& [name, points] : sweep[0]->series)
      EXPECT_EQ(points, std::to_string(sizes_per_mode[name])) << page << ": " << name;
  }
}

// Modes named by their switches (the thesis's Fig. 8 and 9 steps) make long
// labels: they are shortened in the charts' margins and under bars, wrapped in
// the tables, and the page still passes its layout check at 1280 px.
TEST(ReportInBrowser, LongModeNamesFitThePage) {
  REQUIRE_CHROMIUM();
  Fixture f{crowdprof::test::scratch_dir("browser_long_names")};
  f.run("compare '" + f.scene + "' " + f.small +
        " --modes master,master+lookups=bundled,master+lookups=bundled+pose=per-copy+parallel=on+skinning=animations,"
        "threaded+share=on+share-quantum=0.05,culled+update-lod=on --html '" +
        f.path("long.html") + "'");
  const std::string dom = dump_dom(f.path("long.html"));
  expect_clean_page(dom, "long.html");
  // The whole name stays in the label's tooltip.
  EXPECT_NE(dom.find("<title>master+lookups=bundled+pose=per-copy+parallel=on+skinning=animations</title>"),
            std::string::npos);
}

TEST(ReportInBrowser, ACapacityReportLeadsWithTheCapacities) {
  REQUIRE_CHROMIUM();
  Fixture f{crowdprof::test::scratch_dir("browser_capacity")};
  f.run("capacity '" + f.scene +
        "' --budget 0.3 --modes master,threaded --frames 6 --warmup 1 --start 2 --max-characters 64 -q --json '" +
        f.path("cap.json") + "' --html '" + f.path("cap.html") + "'");
  std::string dom = dump_dom(f.path("cap.html"));
  expect_clean_page(dom, "capacity");
  expect_leads(dom, "id=\"capacity\"", "capacity");
  EXPECT_EQ(charts_named(drawn_charts(dom), "sweep").size(), 1u);
  EXPECT_NE(dom.find("<title>crowdprof report: humanoid.glb \u00d7 "), std::string::npos);
}

// check --against: the A/B's verdict per metric (passed or FAILED, change,
// interval, tolerance) opens the page, named by the scene's file.
TEST(ReportInBrowser, AnABCheckReportLeadsWithItsVerdict) {
  REQUIRE_CHROMIUM();
  Fixture f{crowdprof::test::scratch_dir("browser_ab")};
  auto r = crowdprof::test::run_cli("check '" + f.scene + "' " + f.small + " --against '" + CROWDPROF_CLI +
                                    "' --groups 6 --html '" + f.path("ab.html") + "'");
  ASSERT_LE(r.status, 1) << r.err;  // one build against itself: the verdict is the timer's
  std::string dom = dump_dom(f.path("ab.html"));
  expect_clean_page(dom, "A/B");
  expect_leads(dom, "<table class=\"verdict\">", "A/B");
  const std::string verdict = r.status == 0 ? "passed" : "FAILED";
  EXPECT_NE(dom.find("<title>crowdprof report: humanoid.glb \u00d7 4, backend none, A/B check against crowdprof: " +
                     verdict + "</title>"),
            std::string::npos);
  std::smatch row;
  ASSERT_TRUE(std::regex_search(
      dom, row,
      std::regex(
          "<tr><td class=\"name\">frame</td><td class=\"name\"><span class=\"[a-z]+\">(passed|FAILED)</span>[^<]*"
          "</td><td class=\"key\">[-+][0-9.]+%</td><td>\\[[-+][0-9.]+%, [-+][0-9.]+%\\]</td><td>up to "
          "\\+5\\.0%</td>")))
      << "a verdict, change, interval and tolerance for the frame";
  EXPECT_EQ(row[1].str(), verdict);
}

TEST(ReportInBrowser, ACheckReport) {
  REQUIRE_CHROMIUM();
  Fixture f{crowdprof::test::scratch_dir("browser_check")};
  f.run("check '" + f.scene + "' " + f.small + " --baseline '" + f.path("base.json") + "' --update-baseline");
  json planted = json::parse(std::ifstream(f.path("base.json")));
  planted["counters"]["poses_updated"] = planted["counters"]["poses_updated"].get<uint64_t>() + 1;
  std::ofstream(f.path("changed.json")) << planted.dump();
  auto r =
      crowdprof::test::run_cli("check --result '" + f.path("changed.json") + "' --baseline '" + f.path("base.json") +
                               "' --metric frame,Animations,Rasterizer --html '" + f.path("check.html") + "'");
  EXPECT_EQ(r.status, 1) << r.err << "a changed counter is a regression";
  std::string dom = dump_dom(f.path("check.html"));
  expect_clean_page(dom, "check");
  auto charts = drawn_charts(dom);
  auto verdict = charts_named(charts, "verdict");
  ASSERT_EQ(verdict.size(), 1u);
  EXPECT_EQ(verdict[0]->drawn_series, "3");
  for (const auto& [name, points] : verdict[0]->series) EXPECT_EQ(points, "1") << name;
  expect_runs_drawn(charts, {json::parse(std::ifstream(f.path("base.json"))), planted}, "check");
  EXPECT_NE(dom.find("Counter poses_updated changed"), std::string::npos);
  expect_leads(dom, "<table class=\"verdict\">", "check");
}

TEST(ReportInBrowser, ADiffReport) {
  REQUIRE_CHROMIUM();
  Fixture f{crowdprof::test::scratch_dir("browser_diff")};
  f.run("bench '" + f.scene + "' " + f.small + " --mode culled --json '" + f.path("a.json") + "'");
  f.run("bench '" + f.scene + "' " + f.small + " --mode culled --json '" + f.path("b.json") + "'");
  auto r = crowdprof::test::run_cli("diff '" + f.path("a.json") + "' '" + f.path("b.json") + "' -q --html '" +
                                    f.path("diff.html") + "'");
  EXPECT_LE(r.status, 1) << r.err;  // two runs of the same scene: the verdict is the timer's
  std::string dom = dump_dom(f.path("diff.html"));
  expect_clean_page(dom, "diff");
  auto charts = drawn_charts(dom);
  json a = json::parse(std::ifstream(f.path("a.json"))), b = json::parse(std::ifstream(f.path("b.json")));
  expect_runs_drawn(charts, {a, b}, "diff");
  auto verdict = charts_named(charts, "verdict");
  ASSERT_EQ(verdict.size(), 1u);
  for (const auto& [name, points] : verdict[0]->series) EXPECT_EQ(points, "1") << name;
}

TEST(ReportInBrowser, AScreenshotIsShown) {
  REQUIRE_CHROMIUM();
  Fixture f{crowdprof::test::scratch_dir("browser_screenshot")};
  auto r = crowdprof::test::run_cli("bench '" + f.scene + "' " + f.small +
                                    " --backend osmesa --resolution 320x180 "
                                    "--screenshot '" +
                                    f.path("shot.png") + "' --html '" + f.path("s.html") + "'");
  if (r.status == 4) GTEST_SKIP() << "no OSMesa here: " << r.err;
  ASSERT_EQ(r.status, 0) << r.err;
  std::string dom = dump_dom(f.path("s.html"));
  expect_clean_page(dom, "screenshot");
  EXPECT_NE(dom.find("data-report-check=\"ok 2 charts, 1 images\""), std::string::npos) << "the PNG decoded, 320 wide";
}

// The test fails when the page is wrong: a point dropped from a chart, a
// script error, a chart cut out.
TEST(ReportInBrowser, ABrokenPageIsCaught) {
  REQUIRE_CHROMIUM();
  Fixture f{crowdprof::test::scratch_dir("browser_broken")};
  f.run("bench '" + f.scene + "' " + f.small + " --json '" + f.path("b.json") + "' --html '" + f.path("b.html") + "'");
  std::string page = crowdprof::test::read_file(f.path("b.html"));
  size_t polyline = page.find("<polyline points=\"");
  ASSERT_NE(polyline, std::string::npos);
  size_t last = page.rfind(' ', page.find('"', polyline + 18));
  std::string dropped = page.substr(0, last) + page.substr(page.find('"', polyline + 18));
  std::ofstream(f.path("dropped.html")) << dropped;
  std::string dom = dump_dom(f.path("dropped.html"));
  EXPECT_NE(dom.find("data-report-check=\"failed: frame-time/"), std::string::npos);
  auto charts = drawn_charts(dom);
  auto frame_time = charts_named(charts, "frame-time");
  ASSERT_EQ(frame_time.size(), 1u);
  EXPECT_EQ(frame_time[0]->series[0].second, "7") << "8 frames in the file, 7 drawn";

  std::string with_error = page;
  with_error.insert(with_error.find("</body>"), "<script>undefinedFunction();</script>");
  std::ofstream(f.path("error.html")) << with_error;
  EXPECT_NE(dump_dom(f.path("error.html")).find("data-js-errors=\"Uncaught ReferenceError"), std::string::npos);

  std::string cut = page;
  size_t chart = cut.find("<svg", cut.find("id=\"categories\""));
  cut.erase(chart, cut.find("</svg>", chart) + 6 - chart);
  std::ofstream(f.path("cut.html")) << cut;
  EXPECT_NE(dump_dom(f.path("cut.html")).find("data-report-check=\"failed: 1 charts drawn, 2 made\""),
            std::string::npos);
}

// A chart a reader cannot read is caught: a label over another, a label
// struck through by a line, a series no legend names, a colour too pale for
// the page.
TEST(ReportInBrowser, AnIllegibleChartIsCaught) {
  REQUIRE_CHROMIUM();
  Fixture f{crowdprof::test::scratch_dir("browser_illegible")};
  f.run("bench '" + f.scene + "' " + f.small + " --mode threaded --html '" + f.path("b.html") + "'");
  const std::string page = crowdprof::test::read_file(f.path("b.html"));
  expect_clean_page(dump_dom(f.path("b.html")), "as made");
  auto label_of = [&](const std::string& guide) {  // the label of a guide line: {its x, its y} as written
    std::smatch m;
    std::regex pattern("<g class=\"" + guide + "\"[^\n]*?<text x=\"([0-9.]+)\" y=\"([0-9.]+)\"");
    EXPECT_TRUE(std::regex_search(page, m, pattern)) << guide;
    return std::pair<std::string, std::string>{m[1].str(), m[2].str()};
  };
  auto rewritten = [&](const std::string& name, const std::string& from, const std::string& to) {
    size_t at = page.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    std::string changed = page;
    if (at != std::string::npos) changed.replace(at, from.size(), to);
    std::ofstream(f.path(name)) << changed;
    return page_check(dump_dom(f.path(name)));
  };
  auto [median_x, median_y] = label_of("percentile median");
  auto [p95_x, p95_y] = label_of("percentile p95");
  // p95's label moved onto median's.
  std::string check = rewritten("overlap.html", "<text x=\"" + p95_x + "\" y=\"" + p95_y + "\"",
                                "<text x=\"" + median_x + "\" y=\"" + median_y + "\"");
  EXPECT_NE(check.find("frame-time: labels overlap: &quot;median "), std::string::npos) << check;
  // median's label moved into the plot, onto its own line (the plot starts at x = 80).
  std::smatch line;
  ASSERT_TRUE(
      std::regex_search(page, line, std::regex("<g class=\"percentile median\"[^>]*><line [^>]*y1=\"([0-9.]+)\"")));
  check = rewritten("struck.html", "<text x=\"" + median_x + "\" y=\"" + median_y + "\"",
                    "<text x=\"90\" y=\"" + std::to_string(std::stod(line[1].str()) + 4) + "\"");
  EXPECT_NE(check.find("crosses the label &quot;median "), std::string::npos) << check;
  // The series' legend entry gone.
  const std::string legend = "<g class=\"legend\" data-for=\"threaded\">";
  size_t entry = page.find(legend);
  ASSERT_NE(entry, std::string::npos);
  std::string whole = page.substr(entry, page.find("</g>", entry) + 4 - entry);
  check = rewritten("unnamed.html", whole, "");
  EXPECT_NE(check.find("frame-time/threaded: a series no label or legend names"), std::string::npos) << check;
  // The series drawn in Okabe-Ito's yellow, 1.3:1 on white.
  check = rewritten("pale.html", "fill=\"none\" stroke=\"#0072B2\"", "fill=\"none\" stroke=\"#F0E442\"");
  EXPECT_NE(check.find("frame-time/threaded: colour #f0e442 has contrast 1.32:1 against the background #ffffff"),
            std::string::npos)
      << check;
}
