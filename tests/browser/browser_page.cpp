// What the browser tests share (browser_page.h).
#include "browser/browser_page.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <regex>

#include "measuring/category_clock.h"

using crowdprof::Category;
using crowdprof::category_name;
using crowdprof::kCategoryCount;
using crowdprof::series_name;
using nlohmann::json;
namespace fs = std::filesystem;

namespace crowdprof::test {

namespace {

std::string attribute(const std::string& tag, const std::string& name) {
  std::smatch m;
  if (std::regex_search(tag, m, std::regex(" " + name + "=\"([^\"]*)\""))) return m[1].str();
  return "";
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

}  // namespace

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

}  // namespace crowdprof::test
