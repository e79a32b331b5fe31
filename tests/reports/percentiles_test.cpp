// The slow frames: p50, p95, p99 and max of the frame in the profile table
// (one line), and of the frame, CPU time and every category in the JSON.
#include <gtest/gtest.h>

#include "fake_run.h"
#include "measuring/stats.h"
#include "reports/profile_table.h"
#include "result/result_codec.h"

using namespace crowdprof;

TEST(Percentiles, TheTableShowsTheSlowFramesInOneLine) {
  std::vector<double> ms;
  for (int i = 1; i <= 100; ++i) ms.push_back(i);  // 1 .. 100 ms, in order
  Result report = test::fake_run("threaded", 10, ms, 0.75);
  std::string table = format_profile(report);
  // Interpolated between order statistics: p95 at position 94.05, p99 at 98.01.
  EXPECT_NE(table.find("\nSlow frames: p95 95.05 | p99 99.01 | max 100.00 ms\n"), std::string::npos) << table;
  nlohmann::json j = result_to_json(report);
  // The median is a frame: of 100, the lower middle one (measuring/stats.h).
  EXPECT_DOUBLE_EQ(j["frame"]["p50_ms"].get<double>(), 50.0);
  EXPECT_NEAR(j["frame"]["p99_ms"].get<double>(), 99.01, 1e-9);
  EXPECT_DOUBLE_EQ(j["frame"]["max_ms"].get<double>(), 100.0);
  EXPECT_NEAR(j["categories"]["animations_ms"]["p95_ms"].get<double>(), 0.75 * 95.05, 1e-9);
  EXPECT_NEAR(j["categories"]["rasterizer_ms"]["p99_ms"].get<double>(), 0.25 * 99.01, 1e-9);
  EXPECT_DOUBLE_EQ(j["categories"]["animations_ms"]["max_ms"].get<double>(), 75.0);
  ASSERT_TRUE(j.contains("cpu"));
  EXPECT_TRUE(j["cpu"].contains("p99_ms"));
}

TEST(Percentiles, OneFrameIsItsOwnEveryPercentile) {
  Summary s = summarize(std::vector<double>{4.0});
  EXPECT_EQ(s.median, 4.0);
  EXPECT_EQ(s.p95, 4.0);
  EXPECT_EQ(s.p99, 4.0);
  EXPECT_EQ(s.max, 4.0);
}
