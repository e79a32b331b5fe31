// What the browser tests share: chromium found and run headless on a page,
// the DOM it leaves after the page's scripts ran, what the page's self check
// counted of each chart, and a scratch folder to run crowdprof in. The tests
// skip, saying why, when chromium is not installed (./setup.sh test installs it).
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "test_support.h"

namespace crowdprof::test {

// chromium's path: CROWDPROF_CHROMIUM, else chromium or chromium-browser on
// PATH; empty when none.
std::string find_chromium();

#define REQUIRE_CHROMIUM()                                                                                 \
  do {                                                                                                     \
    if (crowdprof::test::find_chromium().empty())                                                          \
      GTEST_SKIP() << "chromium not found on PATH (or CROWDPROF_CHROMIUM): the HTML report is not loaded " \
                      "in a browser; ./setup.sh test installs it (apt-get install chromium)";              \
  } while (0)

// The page's DOM after its scripts ran, as headless chromium serialises it.
std::string dump_dom(const std::filesystem::path& page);

struct DrawnChart {
  std::string id;
  std::string drawn_series;
  std::vector<std::pair<std::string, std::string>> series;  // name, drawn points
  std::vector<std::string> bar_segments;                    // drawn segments per bar
};

// Every chart of the DOM with what the page's script counted the browser drew.
std::vector<DrawnChart> drawn_charts(const std::string& dom);

std::vector<const DrawnChart*> charts_named(const std::vector<DrawnChart>& charts, const std::string& id);

// No script error, and the page's own check of its charts passed.
void expect_clean_page(const std::string& dom, const std::string& what);

// The frame-time chart has a line per run with a point per frame, and each
// run's categories chart a layer per category that took time, a point per frame.
void expect_runs_drawn(const std::vector<DrawnChart>& charts, const std::vector<nlohmann::json>& runs,
                       const std::string& what);

// Where `needle` first occurs in the DOM; npos-safe for comparisons in tests.
size_t first_at(const std::string& dom, const std::string& needle);

// The page's answer (a table found by `lead`) comes before its first chart.
void expect_leads(const std::string& dom, const std::string& lead, const std::string& what);

// What the page's check said, "ok ..." or "failed: ...", as the DOM holds it
// (quotes as &quot;).
std::string page_check(const std::string& dom);

struct Fixture {
  std::filesystem::path dir;
  std::string scene = (crowdprof::test::source_dir() / "scenes" / "humanoid.glb").string();
  std::string small = "-n 4 --frames 8 --warmup 1 -q";
  std::string run(const std::string& args) {
    auto r = crowdprof::test::run_cli(args);
    EXPECT_EQ(r.status, 0) << args << "\n" << r.err;
    return r.err;
  }
  std::string path(const std::string& name) const { return (dir / name).string(); }
};

}  // namespace crowdprof::test
