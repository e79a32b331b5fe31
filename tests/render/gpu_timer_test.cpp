// GPU time from GL timer queries: every measured frame gets its own, read a
// frame or more later (never the frame just drawn, so never a stall), in the
// table and CSV/JSON beside the categories; where no timer exists the report
// says so, with no number.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "asset/gltf_loader.h"
#include "frame/compare.h"
#include "frame/run_bench.h"
#include "gen/humanoid.h"
#include "reports/compare_report.h"
#include "reports/html_report.h"
#include "reports/report_charts.h"
#include "reports/profile_table.h"
#include "render/framebuffer.h"
#include "render/gpu_timer.h"
#include "result/result_codec.h"
#include "render_support.h"
#include "test_support.h"
#include "characters.h"

using namespace crowdprof;
using namespace crowdprof::test;

namespace {

using test::small_humanoid;

BenchConfig config_for(const std::string& mode, FrameRenderer* renderer) {
  BenchConfig config;
  config.mode = find_mode(mode)->switches;
  config.mode_name = mode;
  config.threads = 2;
  config.crowd.copies = 6;
  config.renderer = renderer;
  return config;
}

RendererConfig small_frame(const std::string& hide = {}) {
  RendererConfig rc;
  rc.width = kWidth;
  rc.height = kHeight;
  rc.hide_features = hide;
  return rc;
}

}  // namespace

TEST(GpuTimer, EveryFrameGetsItsOwnTimeReadLater) {
  OPEN_GL_OR_SKIP(context);
  GlCrowdRenderer renderer(*context, small_humanoid(), 6, small_frame());
  ASSERT_EQ(renderer.gpu_timing_missing(), "") << "llvmpipe has GL_TIME_ELAPSED";
  CrowdBench bench(small_humanoid(), config_for("instanced", &renderer));
  std::vector<uint64_t> seen;
  for (uint64_t frame = 0; frame < 6; ++frame) {
    bench.step();
    for (const GpuTime& t : bench.gpu_times()) {
      EXPECT_LT(t.frame, frame) << "the frame just drawn is never read: that could stall";
      EXPECT_GT(t.ms, 0.0);
      seen.push_back(t.frame);
    }
  }
  bench.collect_gpu_times();
  for (const GpuTime& t : bench.gpu_times()) seen.push_back(t.frame);
  EXPECT_EQ(seen, (std::vector<uint64_t>{0, 1, 2, 3, 4, 5})) << "each frame once, in order";
}

TEST(GpuTimer, ReportsShowGpuTimeBesideTheCategories) {
  OPEN_GL_OR_SKIP(context);
  GlCrowdRenderer renderer(*context, small_humanoid(), 6, small_frame());
  CrowdBench bench(small_humanoid(), config_for("hwskin", &renderer));
  RunOptions options;
  options.frames = 5;
  options.warmup = 2;
  Result report = run_bench(bench, "humanoid", options);
  ASSERT_EQ(report.frame_records.size(), 5u);
  for (const FrameRecord& f : report.frame_records) EXPECT_TRUE(std::isfinite(f.gpu_ms) && f.gpu_ms > 0) << f.gpu_ms;
  std::string table = format_profile(report);
  EXPECT_NE(table.find("\nGPU time   : "), std::string::npos) << table;
  EXPECT_NE(table.find("median of 5 frames, GL timer queries"), std::string::npos) << table;
  EXPECT_LT(table.find("GPU Latency:"), table.find("GPU time   :")) << "beside the categories";
  nlohmann::json j = result_to_json(report);
  EXPECT_EQ(j["gpu_time"]["available"], true);
  EXPECT_GT(j["gpu_time"]["median_ms"].get<double>(), 0.0);
  ASSERT_EQ(j["samples"]["gpu_ms"].size(), 5u);
  std::stringstream csv;
  write_csv(report, csv);
  std::string header;
  std::getline(csv, header);
  EXPECT_NE(header.find(",gpu_latency_ms,poses_updated,"), std::string::npos) << "earlier columns never move";
  // gpu_ms follows the last counter (issue 13 appended counters after gpu_palette_bytes).
  EXPECT_TRUE(
      header.ends_with(",gpu_palette_bytes,copies_updated,copies_held,updates_every_1,updates_every_2,"
                       "updates_every_4,updates_every_8,updates_every_16,updates_every_32,updates_every_64,"
                       "lod0_copies,lod1_copies,lod2_copies,lod3_copies,lod0_vertices,lod1_vertices,"
                       "lod2_vertices,lod3_vertices,lod0_triangles,lod1_triangles,lod2_triangles,"
                       "lod3_triangles,vertices_drawn,actions_sampled,fades,joints_blended,"
                       "palette_bytes_uploaded,record_bytes_uploaded,gpu_ms,cpu_ms,animation_sampling_ms,"
                       "animation_blending_ms,animation_local_to_model_ms,animation_skinning_ms,layers"))
      << header;
  std::string row;
  std::getline(csv, row);
  EXPECT_EQ(row.find("n/a"), std::string::npos) << row;
  HtmlReportInput page;
  add_document(page, result_document_from_json(j, "gpu.json"), "gpu.json");
  std::string html = html_report(page);
  // Two decimals, more under a millisecond (the profile table's cells).
  const double gpu = j["gpu_time"]["median_ms"].get<double>();
  const int decimals = gpu == 0 || gpu >= 1 ? 2 : gpu >= 0.1 ? 3 : 4;
  std::string cell = "GPU time (median)</td><td>" + report_number(gpu, decimals) + "</td>";
  EXPECT_NE(html.find(cell), std::string::npos) << "the HTML report's table too";
}

TEST(GpuTimer, WithoutTimerQueriesTheReportSaysSoAndPrintsNoNumber) {
  OPEN_GL_OR_SKIP(context);
  GlCrowdRenderer renderer(*context, small_humanoid(), 6, small_frame("timer-query"));
  EXPECT_NE(renderer.gpu_timing_missing().find("no GL_TIME_ELAPSED timer"), std::string::npos);
  CrowdBench with_gl(small_humanoid(), config_for("hwskin", &renderer));
  CrowdBench without_gl(small_humanoid(), config_for("threaded", nullptr));
  RunOptions options;
  options.frames = 3;
  options.warmup = 1;
  for (CrowdBench* bench : {&with_gl, &without_gl}) {
    Result report = run_bench(*bench, "humanoid", options);
    for (const FrameRecord& f : report.frame_records) EXPECT_TRUE(std::isnan(f.gpu_ms));
    std::string why = bench == &with_gl ? "no GL_TIME_ELAPSED timer" : "no GL backend";
    std::string table = format_profile(report);
    EXPECT_NE(table.find("GPU time   :      n/a     "), std::string::npos) << table;
    EXPECT_NE(table.find(why), std::string::npos) << table;
    nlohmann::json j = result_to_json(report);
    EXPECT_EQ(j["gpu_time"]["available"], false);
    EXPECT_TRUE(j["gpu_time"]["median_ms"].is_null());
    EXPECT_NE(j["gpu_time"]["reason"].get<std::string>().find(why), std::string::npos);
    EXPECT_TRUE(j["samples"]["gpu_ms"].is_null());
    std::stringstream csv;
    write_csv(report, csv);
    std::string header, row;
    std::getline(csv, header);
    std::getline(csv, row);
    EXPECT_NE(row.find(",n/a,"), std::string::npos) << "gpu_ms, then cpu_ms: " << row;
    HtmlReportInput page;
    add_document(page, result_document_from_json(j, "none.json"), "none.json");
    std::string html = html_report(page);
    size_t at = html.find("GPU time (median)</td><td>n/a</td><td class=\"name\">");
    ASSERT_NE(at, std::string::npos) << "the HTML report's table too";
    EXPECT_LT(html.find(why, at), html.find("</tr>", at)) << "with the reason";
  }
}

TEST(GpuTimer, ItsResolutionIsMeasuredOnTheFirstFrame) {
  OPEN_GL_OR_SKIP(context);
  GlCrowdRenderer renderer(*context, small_humanoid(), 6, small_frame());
  EXPECT_EQ(renderer.gpu_timer_resolution_ms(), 0.0) << "nothing measured before a frame";
  CrowdBench bench(small_humanoid(), config_for("hwskin", &renderer));
  RunOptions options;
  options.frames = 2;
  options.warmup = 0;
  Result report = run_bench(bench, "humanoid", options);
  double resolution = report.run.gpu_timer_resolution_ms;
  EXPECT_GT(resolution, 0.0);
  EXPECT_LT(resolution, 1.0) << "a timer that cannot tell a millisecond is no timer";
  EXPECT_EQ(result_to_json(report)["gpu_time"]["resolution_ms"].get<double>(), resolution);
}

// A GPU time the timer cannot tell from nothing is shown as such, by the
// timer's measured resolution (whatever the renderer is called).
TEST(GpuTimer, ATimeBelowTheTimersResolutionIsNotShownAsMeasured) {
  CrowdBench bench(small_humanoid(), config_for("threaded", nullptr));
  RunOptions options;
  options.frames = 3;
  options.warmup = 0;
  Result report = run_bench(bench, "humanoid", options);
  report.run.gpu_timing_missing.clear();
  report.run.gpu_timer_resolution_ms = 0.002;
  for (FrameRecord& f : report.frame_records) f.gpu_ms = 0.0004;
  std::string table = format_profile(report);
  EXPECT_NE(table.find("GPU time   :        -     below the timer's resolution (0.002 ms)"), std::string::npos)
      << table;
  EXPECT_EQ(table.find("0.00ms   median"), std::string::npos) << table;
  record_samples(report);
  nlohmann::json j = result_to_json(report);
  EXPECT_EQ(j["gpu_time"]["below_resolution"], true);
  HtmlReportInput page;
  add_document(page, result_document_from_json(j, "tiny.json"), "tiny.json");
  EXPECT_NE(html_report(page).find("below the timer's resolution"), std::string::npos);
  Comparison comparison;
  comparison.runs = {report};
  EXPECT_NE(format_comparison(comparison).find("<0.0020"), std::string::npos) << format_comparison(comparison);
  // Above it, the number.
  for (FrameRecord& f : report.frame_records) f.gpu_ms = 0.5;
  table = format_profile(report);
  EXPECT_NE(table.find("GPU time   :     0.50ms   median of 3 frames"), std::string::npos) << table;
  record_samples(report);
  EXPECT_EQ(result_to_json(report)["gpu_time"]["below_resolution"], false);
  // Above it but below 0.01 ms: in microseconds, never 0.00ms.
  for (FrameRecord& f : report.frame_records) f.gpu_ms = 0.0042;
  table = format_profile(report);
  EXPECT_NE(table.find("GPU time   :      4.2us   median of 3 frames"), std::string::npos) << table;
}

TEST(GpuTimer, InterleavedModesSharingOneRendererEachGetTheirFramesTimes) {
  OPEN_GL_OR_SKIP(context);
  GlCrowdRenderer renderer(*context, small_humanoid(), 6, small_frame());
  std::vector<std::unique_ptr<CrowdBench>> owned;
  std::vector<CrowdBench*> benches;
  for (const char* mode : {"threaded", "hwskin", "buffer", "instanced"}) {
    owned.push_back(std::make_unique<CrowdBench>(small_humanoid(), config_for(mode, &renderer)));
    benches.push_back(owned.back().get());
  }
  RunOptions options;
  options.frames = 7;
  options.warmup = 2;
  std::vector<Result> reports = run_interleaved(benches, "humanoid", options, 3);
  for (const Result& report : reports) {
    ASSERT_EQ(report.frame_records.size(), 7u);
    for (const FrameRecord& f : report.frame_records)
      EXPECT_TRUE(std::isfinite(f.gpu_ms) && f.gpu_ms > 0) << report.run.mode;
  }
  // compare's table shows it beside the categories; without a timer, no column.
  Comparison comparison;
  comparison.runs = reports;
  std::string table = format_comparison(comparison);
  EXPECT_NE(table.find("gpu_latency_ms  gpu_ms"), std::string::npos) << table;
  for (Result& report : comparison.runs)
    for (FrameRecord& f : report.frame_records) f.gpu_ms = std::nan("");
  EXPECT_EQ(format_comparison(comparison).find("gpu_ms"), std::string::npos);
}

TEST(GpuTimer, QueriesNobodyTakesAreDroppedOldestFirst) {
  OPEN_GL_OR_SKIP(context);
  context->make_current();
  Framebuffer target(16, 16);
  target.bind();
  GpuTimer timer;
  int owner = 0, other = 0;
  // More frames than the ring holds, none taken: the oldest go, the rest stay.
  for (uint64_t frame = 0; frame < GpuTimer::kRing + 3; ++frame) {
    timer.begin(&owner, frame);
    glClear(GL_COLOR_BUFFER_BIT);
    timer.end();
  }
  std::array<GpuTime, GpuTimer::kRing> out{};
  EXPECT_EQ(timer.take(&other, 100, out, true), 0u) << "another owner's frames are not its";
  ASSERT_EQ(timer.take(&owner, 100, out, true), GpuTimer::kRing);
  for (size_t i = 0; i < GpuTimer::kRing; ++i) EXPECT_EQ(out[i].frame, i + 3);
  EXPECT_EQ(timer.take(&owner, 100, out, true), 0u) << "each taken once";
}
