// `crowdprof advise` end to end on a tiny crowd. Only facts that do not depend
// on time: the final scene file, run by bench, gives the plan's counters,
// digest and drawn error exactly; the outputs' shapes; exit statuses; bad input.
#include <gtest/gtest.h>

#include <algorithm>

#include <nlohmann/json.hpp>

#include "test_support.h"

using nlohmann::json;

namespace {

const char* kTinyRun = " -n 40 --frames 6 --warmup 2 --block 3 --time-limit 300 ";

}  // namespace

TEST(AdviseCli, TheFinalSceneFileReproducesThePlan) {
  auto dir = crowdprof::test::scratch_dir("advise_cli");
  const std::string plan = (dir / "plan.json").string(), csv = (dir / "plan.csv").string(),
                    scene = (dir / "fitted.json").string(), again = (dir / "again.json").string();
  // A budget nothing meets: the search goes until no lever saves time.
  auto r = crowdprof::test::run_cli("advise '" + crowdprof::test::humanoid_glb() + "'" + kTinyRun +
                                    "--budget 0.0001 --levers sharing,update_lod,mesh_lod,vertex_format --json '" +
                                    plan + "' --csv '" + csv + "' --scene-out '" + scene + "'");
  ASSERT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.out.find("NOT MET"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("left out: GPU levers"), std::string::npos) << r.out;
  json j = crowdprof::test::read_json(plan);
  EXPECT_EQ(j["crowdprof"]["kind"], "advise");
  const json& advice = j["advice"];
  EXPECT_EQ(advice["met"], false);
  EXPECT_GE(advice["configurations_measured"].get<size_t>(), 2u);
  ASSERT_EQ(j["runs"].size(), 2u);
  const json& final_run = j["runs"][1];
  EXPECT_EQ(advice["final"]["digest"], final_run["digest"]);

  auto b = crowdprof::test::run_cli("bench '" + scene + "' --frames 6 --warmup 2 --json '" + again + "'");
  ASSERT_EQ(b.status, 0) << b.err;
  json rerun = crowdprof::test::read_json(again);
  EXPECT_EQ(rerun["digest"], final_run["digest"]);
  EXPECT_EQ(rerun["counters"], final_run["counters"]);
  EXPECT_EQ(rerun["drawn_error"], final_run["drawn_error"]);
  EXPECT_EQ(rerun["switches"], final_run["switches"]);

  // One CSV row per configuration of every step.
  size_t configurations = 0;
  for (const json& step : advice["steps"]) configurations += step["candidates"].size();
  std::string rows = crowdprof::test::read_file(csv);
  EXPECT_EQ(rows.rfind("step,lever,changes,verdict,", 0), 0u) << rows;
  EXPECT_EQ(static_cast<size_t>(std::count(rows.begin(), rows.end(), '\n')), configurations + 1) << rows;
}

TEST(AdviseCli, ABudgetMetAtTheStartExitsZeroWithNoStep) {
  auto dir = crowdprof::test::scratch_dir("advise_met");
  const std::string plan = (dir / "plan.json").string();
  auto r = crowdprof::test::run_cli("advise '" + crowdprof::test::humanoid_glb() + "'" + kTinyRun +
                                    "--budget 100000 --quiet --json '" + plan + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;  // --quiet with --json: nothing on stdout
  json advice = crowdprof::test::read_json(plan)["advice"];
  EXPECT_EQ(advice["met"], true);
  EXPECT_TRUE(advice["steps"].empty());
  EXPECT_EQ(advice["outcome"], "met");
  ASSERT_EQ(advice["capacities"].size(), 1u);
  EXPECT_EQ(advice["capacities"][0]["configuration"], "start and final");
}

TEST(AdviseCli, RefusesBadInputWithOneLine) {
  const std::string q = "'" + crowdprof::test::humanoid_glb() + "'";
  for (const std::string bad :
       {"", "--budget 0", "--budget nan", "--budget 16 --metric Rasterizer", "--budget 16 --metric fps",
        "--budget 16 --levers sharing,gpu", "--budget 16 --max-error -1", "--budget 16 --time-limit 0",
        "--budget 16 --block 0", "--budget 16 --mode master --threads 2"}) {
    auto r = crowdprof::test::run_cli("advise " + q + kTinyRun + bad);
    EXPECT_EQ(r.status, 2) << bad << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << bad << "\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << bad;
  }
}
