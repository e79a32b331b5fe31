// An advise search's page in chromium (tests/reports/advise_page_test.cpp
// checks its HTML without a browser).
#include <gtest/gtest.h>

#include <fstream>
#include <map>

#include <nlohmann/json.hpp>

#include "advice_fixture.h"
#include "browser/browser_page.h"
#include "result/result_document.h"

using namespace crowdprof::test;
using nlohmann::json;

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
