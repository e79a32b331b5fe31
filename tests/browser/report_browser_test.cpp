// The HTML report in a real browser: Debian's chromium, headless, loads each
// kind of report (bench, several results, compare with a sweep, check, a
// screenshot) and this test reads back the DOM after the page's scripts ran.
// It fails on a script error, on a chart missing, and on a chart whose series
// or points, as the browser parsed and drew them, differ from the result file.
// Skips, saying why, when chromium is not installed (./setup.sh test installs it).
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <map>
#include <regex>
#include <set>

#include <nlohmann/json.hpp>

#include "advice_fixture.h"
#include "measuring/category_clock.h"
#include "result/result_document.h"
#include "test_support.h"

using crowdprof::Category;
using crowdprof::category_name;
using crowdprof::kCategoryCount;
using crowdprof::series_name;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

std::string find_chromium() {
  if (const char* given = std::getenv("CROWDPROF_CHROMIUM")) return given;
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  for (size_t start = 0; start <= dirs.size();) {
    size_t end = dirs.find(':', start);
    if (end == std::string::npos) end = dirs.size();
    for (const char* name : {"chromium", "chromium-browser"}) {
      fs::path candidate = fs::path(dirs.substr(start, end - start)) / name;
      if (!candidate.parent_path().empty() && access(candidate.c_str(), X_OK) == 0) return candidate.string();
    }
    start = end + 1;
  }
  return "";
}

#define REQUIRE_CHROMIUM()                                                                                 \
  do {                                                                                                     \
    if (find_chromium().empty())                                                                           \
      GTEST_SKIP() << "chromium not found on PATH (or CROWDPROF_CHROMIUM): the HTML report is not loaded " \
                      "in a browser; ./setup.sh test installs it (apt-get install chromium)";              \
  } while (0)

// The page's DOM after its scripts ran, as headless chromium serialises it.
std::string dump_dom(const fs::path& page) {
  fs::path dir = page.parent_path();
  fs::path out = dir / (page.filename().string() + ".dom"), err = dir / (page.filename().string() + ".err");
  std::string command = "timeout 120 '" + find_chromium() +
                        "' --headless --disable-gpu --no-sandbox --no-first-run --window-size=1280,2000 " +
                        "--user-data-dir='" + (dir / "chromium-profile").string() + "' --dump-dom 'file://" +
                        fs::absolute(page).string() + "' >'" + out.string() + "' 2>'" + err.string() + "'";
  int raw = std::system(command.c_str());
  EXPECT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 0) << command << "\n" << crowdprof::test::read_file(err);
  return crowdprof::test::read_file(out);
}

std::string attribute(const std::string& tag, const std::string& name) {
  std::smatch m;
  if (std::regex_search(tag, m, std::regex(" " + name + "=\"([^\"]*)\""))) return m[1].str();
  return "";
}

struct DrawnChart {
  std::string id;
  std::string drawn_series;
  std::vector<std::pair<std::string, std::string>> series;  // name, drawn points
  std::vector<std::string> bar_segments;                    // drawn segments per bar
};

// Every chart of the DOM with what the page's script counted the browser drew.
std::vector<DrawnChart> drawn_charts(const std::string& dom) {
  std::vector<DrawnChart> charts;
  const std::string start = "<g class=\"chart ";
  for (size_t at = dom.find(start); at != std::string::npos;) {
    size_t next = dom.find(start, at + 1);
    std::string part = dom.substr(at, next == std::string::npos ? std::string::npos : next - at);
    std::string tag = part.substr(0, part.find('>'));
    DrawnChart chart{attribute(tag, "data-chart"), attribute(tag, "data-drawn-series"), {}, {}};
    for (size_t s = part.find("<g class=\"series\""); s != std::string::npos;
         s = part.find("<g class=\"series\"", s + 1)) {
      std::string series = part.substr(s, part.find('>', s) - s);
      chart.series.push_back({attribute(series, "data-name"), attribute(series, "data-drawn-points")});
    }
    for (size_t b = part.find("<g class=\"bar\""); b != std::string::npos; b = part.find("<g class=\"bar\"", b + 1))
      chart.bar_segments.push_back(attribute(part.substr(b, part.find('>', b) - b), "data-drawn-segments"));
    charts.push_back(chart);
    at = next;
  }
  return charts;
}

std::vector<const DrawnChart*> charts_named(const std::vector<DrawnChart>& charts, const std::string& id) {
  std::vector<const DrawnChart*> out;
  for (const DrawnChart& chart : charts)
    if (chart.id == id) out.push_back(&chart);
  return out;
}

// No script error, and the page's own check of its charts passed.
void expect_clean_page(const std::string& dom, const std::string& what) {
  std::smatch m;
  EXPECT_FALSE(std::regex_search(dom, m, std::regex("data-js-errors=\"([^\"]*)\""))) << what << ": " << m[1].str();
  ASSERT_TRUE(std::regex_search(dom, m, std::regex("data-report-check=\"([^\"]*)\"")))
      << what << ": the page's script never ran";
  EXPECT_EQ(m[1].str().rfind("ok ", 0), 0u) << what << ": " << m[1].str();
}

std::vector<std::string> categories_with_time(const json& run) {
  std::vector<std::string> out;
  for (size_t c = 0; c < kCategoryCount; ++c) {
    const std::string name(category_name(static_cast<Category>(c)));
    const json& samples = run["samples"][series_name(static_cast<Category>(c))];
    if (std::any_of(samples.begin(), samples.end(), [](const json& v) { return v.get<double>() > 0; }))
      out.push_back(name);
  }
  return out;
}

// The frame-time chart has a line per run with a point per frame, and each
// run's categories chart a layer per category that took time, a point per frame.
void expect_runs_drawn(const std::vector<DrawnChart>& charts, const std::vector<json>& runs, const std::string& what) {
  auto frame_time = charts_named(charts, "frame-time");
  ASSERT_EQ(frame_time.size(), 1u) << what;
  EXPECT_EQ(frame_time[0]->drawn_series, std::to_string(runs.size())) << what;
  ASSERT_EQ(frame_time[0]->series.size(), runs.size()) << what;
  auto categories = charts_named(charts, "categories");
  ASSERT_EQ(categories.size(), runs.size()) << what;
  for (size_t r = 0; r < runs.size(); ++r) {
    std::string frames = std::to_string(runs[r]["frames"].get<size_t>());
    EXPECT_EQ(frame_time[0]->series[r].second, frames) << what << ": run " << r;
    std::vector<std::string> layers = categories_with_time(runs[r]);
    EXPECT_EQ(categories[r]->drawn_series, std::to_string(layers.size())) << what << ": run " << r;
    ASSERT_EQ(categories[r]->series.size(), layers.size()) << what;
    for (size_t l = 0; l < layers.size(); ++l) {
      EXPECT_EQ(categories[r]->series[l].first, layers[l]) << what;
      EXPECT_EQ(categories[r]->series[l].second, frames) << what << ": " << layers[l];
    }
  }
}

// Where `needle` first occurs in the DOM; npos-safe for comparisons in tests.
size_t first_at(const std::string& dom, const std::string& needle) {
  return dom.find(needle);
}

// The page's answer (a table found by `lead`) comes before its first chart.
void expect_leads(const std::string& dom, const std::string& lead, const std::string& what) {
  size_t at = first_at(dom, lead), chart = first_at(dom, "<svg");
  ASSERT_NE(at, std::string::npos) << what << ": no " << lead;
  ASSERT_NE(chart, std::string::npos) << what << ": no chart";
  EXPECT_LT(at, chart) << what << ": " << lead << " after the first chart";
}

// What the page's check said, "ok ..." or "failed: ...", as the DOM holds it
// (quotes as &quot;).
std::string page_check(const std::string& dom) {
  std::smatch m;
  return std::regex_search(dom, m, std::regex("data-report-check=\"([^\"]*)\"")) ? m[1].str() : "";
}

struct Fixture {
  fs::path dir;
  std::string scene = (crowdprof::test::source_dir() / "scenes" / "humanoid.glb").string();
  std::string small = "-n 4 --frames 8 --warmup 1 -q";
  std::string run(const std::string& args) {
    auto r = crowdprof::test::run_cli(args);
    EXPECT_EQ(r.status, 0) << args << "\n" << r.err;
    return r.err;
  }
  std::string path(const std::string& name) const { return (dir / name).string(); }
};

}  // namespace

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

// An advise search's page: its plan leads, its path is drawn on the cost
// against error chart beside every lever measured, and the page passes its
// own check. The search's record is made up (tests/advice_fixture.h); its
// runs, the start's and the final one's, are real benches.
TEST(ReportInBrowser, AnAdviseReportLeadsWithThePlan) {
  REQUIRE_CHROMIUM();
  Fixture f{crowdprof::test::scratch_dir("browser_advise")};
  crowdprof::ResultDocument doc;
  doc.kind = "advise";
  for (const char* name : {"start.json", "final.json"}) {
    f.run("bench '" + f.scene + "' " + f.small + " --mode threaded --json '" + f.path(name) + "'");
    doc.runs.push_back(crowdprof::read_result_document(f.path(name)).runs.front());
  }
  doc.advice = crowdprof::test::sample_advice(true);
  std::ofstream(f.path("advise.json")) << crowdprof::result_document_to_json(doc).dump();
  f.run("report '" + f.path("advise.json") + "' -o '" + f.path("advise.html") + "'");
  std::string dom = dump_dom(f.path("advise.html"));
  expect_clean_page(dom, "advise");
  expect_leads(dom, "id=\"advise\"", "advise");
  EXPECT_LT(first_at(dom, "data-chart=\"advice\""), first_at(dom, "id=\"headline\"")) << "the path before the runs";
  auto charts = drawn_charts(dom);
  auto advice = charts_named(charts, "advice");
  ASSERT_EQ(advice.size(), 1u);
  EXPECT_EQ(advice[0]->drawn_series, "4") << "the path, sharing, update_lod, mesh_lod";
  std::map<std::string, std::string> points(advice[0]->series.begin(), advice[0]->series.end());
  EXPECT_EQ(points["the path taken"], "3");
  EXPECT_EQ(points["update_lod"], "2");
  expect_runs_drawn(
      charts, {json::parse(std::ifstream(f.path("start.json"))), json::parse(std::ifstream(f.path("final.json")))},
      "advise");
  EXPECT_NE(dom.find("advise: 16.7 ms budget on frame: met</title>"), std::string::npos);
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
