// `compare`: modes run interleaved in blocks, each gets its own report, the
// table's medians and speedups are right, and the CLI says what it skips.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "gen/humanoid.h"
#include "frame/compare.h"
#include "fake_run.h"
#include "reports/compare_report.h"
#include "measuring/trace.h"
#include "reports/profile_table.h"
#include "test_support.h"
#include "characters.h"

using namespace crowdprof;
using crowdprof::test::fake_run;

namespace {

using test::small_humanoid;

BenchConfig compare_config(const std::string& mode, int threads = 1) {
  BenchConfig config;
  config.mode = find_mode(mode)->switches;
  config.mode_name = mode;
  config.threads = threads;
  config.crowd.copies = 12;
  return config;
}

}  // namespace

TEST(Compare, ModesRunInBlocksAndEachGetsItsFrames) {
  std::vector<BenchConfig> configs = {compare_config("master"), compare_config("culled"),
                                      compare_config("threaded", 2)};
  Tracer tracer;
  std::vector<std::unique_ptr<CrowdBench>> owned;
  std::vector<CrowdBench*> benches;
  for (size_t m = 0; m < configs.size(); ++m) {
    configs[m].tracer = &tracer;
    configs[m].trace_pid = static_cast<int>(m + 1);
    owned.push_back(std::make_unique<CrowdBench>(small_humanoid(), configs[m]));
    benches.push_back(owned.back().get());
  }
  RunOptions options;
  options.frames = 7;
  options.warmup = 2;
  size_t progress = 0;
  options.progress = [&](size_t done, size_t total) {
    EXPECT_EQ(done, ++progress);
    EXPECT_EQ(total, 27u);
  };
  std::vector<Result> reports = run_interleaved(benches, "humanoid", options, 3);
  ASSERT_EQ(reports.size(), 3u);
  for (size_t m = 0; m < 3; ++m) {
    EXPECT_EQ(reports[m].run.mode, configs[m].mode_name);
    EXPECT_EQ(reports[m].frames(), 7u);
    EXPECT_EQ(reports[m].run.warmup, 2u);
    EXPECT_EQ(benches[m]->frames_run(), 9u);
  }
  // Every mode computes the same poses for the copies it draws.
  EXPECT_EQ(reports[0].digest, reports[1].digest);
  EXPECT_EQ(reports[0].digest, reports[2].digest);
  EXPECT_LT(reports[1].frame_records[0].counters.poses_updated, reports[0].frame_records[0].counters.poses_updated);

  // The frames, in the order they ran: 3 of master, 3 of culled, 3 of
  // threaded, then again; the last block is what is left of 9.
  std::vector<TraceSpan> spans = tracer.spans();
  std::vector<TraceSpan> frames;
  std::copy_if(spans.begin(), spans.end(), std::back_inserter(frames),
               [](const TraceSpan& s) { return s.category == "frame"; });
  std::sort(frames.begin(), frames.end(),
            [](const TraceSpan& a, const TraceSpan& b) { return a.start_ns < b.start_ns; });
  std::string order;
  for (const TraceSpan& s : frames) order += static_cast<char>('0' + s.pid);
  EXPECT_EQ(order, "111222333111222333111222333");
}

TEST(Compare, MediansAndSpeedups) {
  Comparison comparison;
  comparison.runs = {fake_run("master", 10, {8, 10, 12}), fake_run("culled", 10, {4, 5, 60}),
                     fake_run("threaded", 10, {2, 2.5, 3})};
  std::vector<ModeMedians> medians = mode_medians(comparison.runs);
  ASSERT_EQ(medians.size(), 3u);
  EXPECT_DOUBLE_EQ(medians[0].frame_ms, 10.0);
  EXPECT_DOUBLE_EQ(medians[1].frame_ms, 5.0);  // the median shrugs off the slow frame
  EXPECT_DOUBLE_EQ(medians[1].speedup, 2.0);
  EXPECT_DOUBLE_EQ(medians[2].speedup, 4.0);
  std::vector<Category> shown = shown_categories(medians);
  ASSERT_EQ(shown.size(), 1u);
  EXPECT_EQ(shown[0], Category::Animations);

  std::string table = format_comparison(comparison);
  std::istringstream lines(table);
  std::string header;
  std::getline(lines, header);
  for (const char* column :
       {"mode", "characters", "threads", "frame_ms", "animations_ms", "speedup_x", "copies_culled", "digest"})
    EXPECT_NE(header.find(column), std::string::npos) << column << "\n" << table;
  EXPECT_EQ(header.find("physics_ms"), std::string::npos) << "zero categories are left out\n" << table;
  EXPECT_NE(table.find("4.00"), std::string::npos) << table;

  // A sweep adds rows, with speedups against the first mode of the same size.
  comparison.sweep = {fake_run("master", 20, {20}), fake_run("threaded", 20, {4}), fake_run("master", 40, {40}),
                      fake_run("threaded", 40, {5})};
  std::vector<ModeMedians> sweep = mode_medians(comparison.sweep);
  EXPECT_DOUBLE_EQ(sweep[1].speedup, 5.0);
  EXPECT_DOUBLE_EQ(sweep[3].speedup, 8.0);
  EXPECT_NE(format_comparison(comparison).find("sweep: median frame time by crowd size"), std::string::npos);

  std::ostringstream csv;
  write_comparison_csv(comparison, csv);
  std::string text = csv.str();
  EXPECT_EQ(text.rfind(csv_header() + "\n", 0), 0u);
  EXPECT_EQ(text.find("frame,mode", 1), std::string::npos) << "one header";
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1 + 9 + 4);

  nlohmann::json doc = comparison_to_json(comparison);
  EXPECT_EQ(doc["crowdprof"]["kind"], "compare");
  EXPECT_EQ(doc["modes"], nlohmann::json({"master", "culled", "threaded"}));
  EXPECT_DOUBLE_EQ(doc["summary"][2]["speedup"].get<double>(), 4.0);
  EXPECT_EQ(doc["sweep"].size(), 4u);
  EXPECT_EQ(doc["runs"][1]["samples"]["frame_ms"].size(), 3u);
}

TEST(CompareCli, PrintsATableAndRefusesBadModes) {
  std::string scene = (test::source_dir() / "scenes" / "humanoid.glb").string();
  auto dir = test::scratch_dir("compare_cli");
  auto r = test::run_cli("compare '" + scene +
                         "' -n 4 --frames 4 --warmup 1 --modes master,threaded --threads 2 "
                         "--sweep n=2,4 --json '" +
                         (dir / "c.json").string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.rfind("mode ", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("\nmaster "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\nthreaded "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("speedup_x"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n         2  master  "), std::string::npos) << r.out;
  EXPECT_TRUE(r.err.empty()) << r.err;

  // By default every mode runs that can: hwskin needs GL, and says so.
  r = test::run_cli("compare '" + scene + "' -n 2 --frames 2 --warmup 0 --backend none -q");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(r.out.empty());
  EXPECT_NE(r.err.find("skipping mode hwskin"), std::string::npos) << r.err;

  for (const char* bad : {"--modes master,fastest", "--modes master,master", "--sweep n=ten", "--sweep n=0,4",
                          "--sweep passes=0,2", "--sweep passes=11", "--sweep draws=2", "--block 0", "--mode master",
                          "--modes hwskin --backend none", "--modes threaded --sweep passes=1,2 --backend none"}) {
    r = test::run_cli("compare '" + scene + "' -n 2 --frames 2 " + bad);
    EXPECT_EQ(r.status, 2) << bad << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  // Every mode skipped at a sweep's point: why, not only that none can run.
  r = test::run_cli("compare '" + scene + "' -n 2 --frames 2 --sweep passes=1,2 --backend none");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("crowdprof: none of the modes can run here (the first: --passes 2 draws the crowd several "
                       "times a frame, which needs a GL backend"),
            std::string::npos)
      << r.err;
}

TEST(CompareCli, SweepsPassesWhereTheGlAllows) {
  if (!test::have_gl()) GTEST_SKIP() << "no GL backend on this machine";
  std::string scene = (test::source_dir() / "scenes" / "humanoid.glb").string();
  auto dir = test::scratch_dir("compare_passes");
  std::string json_path = (dir / "c.json").string(), csv = (dir / "s.csv").string(), html = (dir / "c.html").string();
  auto r = test::run_cli("compare '" + scene +
                         "' -n 4 --frames 2 --warmup 0 --block 1 --backend egl "
                         "--modes hwskin,compute --sweep passes=1,3 --json '" +
                         json_path + "' --summary-csv '" + csv + "' --html '" + html + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("sweep: median frame time by passes"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n     3  compute  "), std::string::npos) << r.out;
  std::ifstream in(json_path);
  nlohmann::json doc = nlohmann::json::parse(in);
  EXPECT_EQ(doc["sweep_axis"], "passes");
  ASSERT_EQ(doc["sweep"].size(), 4u) << "2 modes at 1 and 3 passes";
  EXPECT_EQ(doc["sweep"][2]["passes"], 3);
  EXPECT_EQ(doc["sweep"][2]["mode"], "hwskin") << "one line per mode on the chart";
  EXPECT_EQ(doc["sweep"][0]["counters"]["draw_calls"].get<uint64_t>() * 3,
            doc["sweep"][2]["counters"]["draw_calls"].get<uint64_t>());
  std::ifstream rows(csv);
  std::vector<std::string> lines;
  for (std::string line; std::getline(rows, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 5u) << "header, 2 modes at the main point, 2 at 3 passes";
  auto field = [](const std::string& line, size_t column) {
    std::stringstream in(line);
    std::string value;
    for (size_t c = 0; c <= column && std::getline(in, value, ',');) ++c;
    return value;
  };
  const size_t passes_column = 13;
  ASSERT_EQ(field(lines[0], passes_column), "passes");
  EXPECT_EQ(field(lines[3], passes_column), "3");
  // llvmpipe counts vertex-shader invocations: the shadow pass's vertex reuse is filled in.
  EXPECT_EQ(field(lines[0], passes_column + 4), "shadows_invocations_per_vertex");
  EXPECT_FALSE(field(lines[3], passes_column + 4).empty()) << lines[3];
  std::ifstream page(html);
  std::string text((std::istreambuf_iterator<char>(page)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("Passes sweep"), std::string::npos);
  EXPECT_NE(text.find("passes (draws of the crowd a frame)"), std::string::npos);
}

TEST(CompareModes, ALayerSetByAModeKeepsItsFields) {
  // --modes splits at every comma; a layer's own commas go back to its mode.
  const std::vector<std::string> split = {"threaded",  "threaded+anim_layer=action=wave", "mask=spine_03",
                                          "falloff=1", "culled+anim-layer=action=walk",   "blend=add"};
  EXPECT_EQ(crowdprof::modes_to_run(split),
            (std::vector<std::string>{"threaded", "threaded+anim_layer=action=wave,mask=spine_03,falloff=1",
                                      "culled+anim-layer=action=walk,blend=add"}));
  // A mode named after a layer still starts a mode of its own.
  EXPECT_EQ(crowdprof::modes_to_run({"threaded+anim_layer=action=wave", "culled"}).size(), 2u);
  // Fields without a layer before them are no mode: refused by name.
  EXPECT_THROW(crowdprof::modes_to_run({"threaded", "mask=spine_03"}), crowdprof::UsageError);
}
