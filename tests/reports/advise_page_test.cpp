// The page of an advise search (issue 57 item 4), without a browser: the plan
// leads (met or not, the start's and the final options, the capacities, a
// table per step with the lever taken highlighted and the noise marked), the
// cost-against-error chart draws the path, the runs follow as "start" and
// "final"; its document survives a round trip and a bad one is refused naming
// the file. tests/browser/ loads the page in chromium.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>

#include "advice_fixture.h"
#include "base/errors.h"
#include "fake_run.h"
#include "reports/html_report.h"
#include "result/result_codec.h"
#include "test_support.h"

using namespace crowdprof;
using nlohmann::json;

namespace {

// An advise document: the start's run and the final one's, both of mode
// threaded (advise's levers are switches, not presets).
ResultDocument advise_document(bool met) {
  ResultDocument d;
  d.kind = "advise";
  for (const std::vector<double>& frames : {std::vector<double>{24, 25, 23}, std::vector<double>{16, 15, 17}}) {
    Result run = test::fake_run("threaded", 160, frames, 0.5);
    run.run.character = "walker";
    d.runs.push_back(result_document_from_json(result_to_json(run), "run.json").runs.front());
  }
  d.advice = test::sample_advice(met);
  return d;
}

std::string advise_page(bool met) {
  HtmlReportInput input;
  add_document(input, advise_document(met), "advise.json");
  input.sources.push_back("advise.json");
  return html_report(input);
}

// The attributes of the series named `name` in the chart.
std::string advice_series(const std::string& html, const std::string& name) {
  std::smatch m;
  return std::regex_search(html, m,
                           std::regex("data-name=\"" + name + "\" data-geometry=\"([a-z]+)\" data-points=\"([0-9]+)\""))
             ? m[1].str() + " " + m[2].str()
             : "";
}

// An option as the page shows it: kept on one line.
std::string option(const std::string& text) {
  return "<span class=\"option\">" + text + "</span>";
}

// An interval under its median, on one line.
std::string interval(const std::string& text) {
  return "<br><span class=\"interval\">" + text + "</span>";
}

}  // namespace

TEST(AdvisePage, ThePlanLeadsThenThePathThenTheRuns) {
  const std::string html = advise_page(true);
  EXPECT_NE(html.find("<title>crowdprof report of advise.json: walker × 160, backend none, advise: 16.7 ms budget on "
                      "frame: met</title>"),
            std::string::npos)
      << html.substr(0, 600);
  const size_t plan = html.find("id=\"advise\""), chart = html.find("data-chart=\"advice\""),
               headline = html.find("id=\"headline\""), profile = html.find("id=\"profile\"");
  ASSERT_NE(plan, std::string::npos);
  ASSERT_NE(chart, std::string::npos);
  EXPECT_LT(plan, html.find("<svg")) << "the plan before every chart";
  EXPECT_LT(chart, headline) << "the path before the runs";
  EXPECT_LT(headline, profile);
  EXPECT_NE(html.find("<span class=\"ok\">met</span>"), std::string::npos);
  // The start's and the final options, the final one adding its levers.
  EXPECT_NE(html.find("<td class=\"name\">start</td><td class=\"name\"><code>" + option("--mode threaded") + "</code>"),
            std::string::npos);
  EXPECT_NE(html.find("<td class=\"name\">final</td><td class=\"name\"><code>" + option("--mode threaded") + " " +
                      option("--sharing on") + " " + option("--update_lod on") + "</code>"),
            std::string::npos);
  // Capacities measured at the start and the end, and estimated.
  EXPECT_NE(html.find("<td><b>110</b></td><td>112</td><td>7</td><td>111</td></tr>"), std::string::npos)
      << "start: measured 110, estimated 160 x 16.7 / 24";
  EXPECT_NE(html.find("<td><b>165</b></td><td>168</td><td>8</td><td>168</td></tr>"), std::string::npos)
      << "final: measured 165, estimated 160 x 16.7 / 15.9";
  EXPECT_NE(html.find("capacity (estimated)"), std::string::npos);
  EXPECT_NE(html.find("7 configurations measured"), std::string::npos);
  EXPECT_NE(html.find("<li>GPU levers (hwskin, passes): timed on llvmpipe they would give wrong advice</li>"),
            std::string::npos);
  // A table per step: the lever taken highlighted, the noise marked.
  EXPECT_EQ(test::occurrences(html, "<table class=\"advice-step\">"), 2u);
  EXPECT_NE(html.find("<tr class=\"taken\"><td class=\"name\">sharing</td><td class=\"name\"><code>" +
                      option("--sharing on") + "</code></td><td>19.0" + interval("[18.7, 19.4]") + "</td><td>5.00" +
                      interval("[4.60, 5.30]") +
                      "</td><td>0.40</td>"
                      "<td>1.20</td><td>0.200</td>"),
            std::string::npos);
  EXPECT_NE(html.find("<tr class=\"noise\"><td class=\"name\">update_lod</td>"), std::string::npos);
  EXPECT_NE(html.find("<td>23.8" + interval("[23.1, 24.4]") + "</td><td>0.200" + interval("[-0.100, 0.500]") + "</td>"),
            std::string::npos)
      << "the noise's saving: 0 inside its interval";
  EXPECT_NE(html.find("noise: 0 is inside the saving's interval"), std::string::npos);
  EXPECT_NE(html.find("<h3>Step 1: from 24.0 ms, took sharing</h3>"), std::string::npos);
  EXPECT_NE(html.find("<h3>Step 2: from 19.1 ms, took update_lod</h3>"), std::string::npos);
  EXPECT_EQ(test::occurrences(html, "<tr class=\"taken\">"), 2u);
  EXPECT_NE(html.find("<td class=\"name\">past max error</td>"), std::string::npos);
  EXPECT_NE(html.find("<td>-</td><td>-</td><td>-</td>"), std::string::npos) << "a lever that cannot run: no numbers";
  // The chart: the path through the start and two levers taken, a dot per
  // lever measured (not the one that could not run), the budget.
  EXPECT_EQ(advice_series(html, "the path taken"), "line 3");
  EXPECT_EQ(advice_series(html, "sharing"), "dots 1");
  EXPECT_EQ(advice_series(html, "update_lod"), "dots 2");
  EXPECT_EQ(advice_series(html, "mesh_lod"), "dots 1");
  EXPECT_NE(html.find("data-value=\"16.7\" data-guide=\"budget\""), std::string::npos);
  EXPECT_NE(html.find("<body data-charts=\"5\">"), std::string::npos)
      << "advice, frame time, 2 categories, modes (the runs carry no drawn error)";
  // The runs named by their place in the search, not by their equal modes.
  EXPECT_NE(html.find("<tr><td class=\"name\">start</td>"), std::string::npos);
  EXPECT_NE(html.find("<tr><td class=\"name\">final</td>"), std::string::npos);
  EXPECT_EQ(html.find("<tr><td class=\"name\">threaded</td>"), std::string::npos);
}

TEST(AdvisePage, NotMetSaysWhy) {
  const std::string html = advise_page(false);
  EXPECT_NE(html.find("advise: 16.7 ms budget on frame: not met</title>"), std::string::npos);
  EXPECT_NE(html.find("<span class=\"regression\">not met</span>"), std::string::npos);
  EXPECT_NE(html.find("Outcome: <b>noise</b>. the best saving, sharing&apos;s 0.3 ms, reaches 0"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"name\">final</td><td class=\"name\"><code>" + option("--mode threaded") + "</code>"),
            std::string::npos)
      << "nothing taken: the final configuration is the start";
  EXPECT_NE(html.find("<td>not measured</td>"), std::string::npos) << "no capacities";
  EXPECT_EQ(html.find("<tr class=\"taken\">"), std::string::npos);
  EXPECT_EQ(advice_series(html, "the path taken"), "line 1");
}

TEST(AdvisePage, TheDocumentRoundTrips) {
  const ResultDocument d = advise_document(true);
  const ResultDocument back = result_document_from_json(result_document_to_json(d), "advise.json");
  ASSERT_EQ(back.kind, "advise");
  ASSERT_TRUE(back.advice);
  EXPECT_EQ(back.runs.size(), 2u);
  const AdviceRecord &a = *d.advice, &b = *back.advice;
  // Every field, as its JSON says it; then a few by hand, in case both ways
  // dropped one alike.
  EXPECT_EQ(advice_to_json(b), advice_to_json(a));
  EXPECT_EQ(b.final_options, "--mode threaded --sharing on --update_lod on");
  EXPECT_EQ(b.added_options, "--sharing on --update_lod on");
  ASSERT_EQ(b.steps.size(), 2u);
  EXPECT_EQ(b.steps[0].taken, std::optional<size_t>(1));
  ASSERT_EQ(b.steps[0].candidates.size(), 4u);
  EXPECT_EQ(b.steps[0].candidates[2].verdict, "noise");
  EXPECT_EQ(b.steps[0].candidates[2].saved.low, -0.1);
  EXPECT_EQ(b.steps[1].candidates[1].capacity_estimate, 168u);
  ASSERT_EQ(b.capacities.size(), 2u);
  EXPECT_EQ(b.capacities[1].fit, std::optional<size_t>(165));
  EXPECT_EQ(b.capacities[1].over, std::optional<size_t>(168));
}

TEST(AdvisePage, ABadAdviseDocumentIsRefusedNamingTheFile) {
  auto dir = test::scratch_dir("advise_page_bad");
  const json good = result_document_to_json(advise_document(true));
  json taken = good;
  taken["advice"]["steps"][0]["taken"] = 9;
  json missing = good;
  missing.erase("advice");
  struct Bad {
    const char* name;
    json doc;
    const char* says;
  };
  for (const Bad& bad :
       {Bad{"taken_out_of_range", taken, "advice.steps[0].taken"}, Bad{"no_advice", missing, "without \"advice\""}}) {
    HtmlReportInput input;
    try {
      add_result_file(input, test::write_json(dir / (std::string(bad.name) + ".json"), bad.doc));
      ADD_FAILURE() << bad.name << " was read";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(bad.says), std::string::npos) << bad.name << ": " << e.what();
      EXPECT_NE(std::string(e.what()).find(bad.name), std::string::npos) << "names the file: " << e.what();
    }
  }
}

TEST(ReportCli, AnAdvisePage) {
  auto dir = test::scratch_dir("report_cli_advise");
  const std::string file = test::write_json(dir / "advise.json", result_document_to_json(advise_document(true)));
  const std::string out = (dir / "page.html").string();
  auto r = test::run_cli("report '" + file + "' -o '" + out + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream in(out);
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_LT(html.find("id=\"advise\""), html.find("id=\"headline\""));
  json bad = result_document_to_json(advise_document(true));
  bad["advice"]["steps"][1]["taken"] = 3;
  const std::string bad_file = test::write_json(dir / "bad_advise.json", bad);
  r = test::run_cli("report '" + bad_file + "' -o '" + (dir / "bad.html").string() + "'");
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_NE(r.err.find("bad_advise.json"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.html"));
}

TEST(AdvisePage, AnAdviseResultIsReportedAlone) {
  // One plan leads a page: a second, or other results beside it, would have
  // it show one plan's verdict over another's runs.
  HtmlReportInput input;
  add_document(input, advise_document(true), "a.json");
  EXPECT_THROW(add_document(input, advise_document(false), "b.json"), InputError);
  EXPECT_THROW(add_result(input, input.runs.front().result, "c.json"), InputError);
}
