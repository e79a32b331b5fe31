// The one reader and writer of results: what it writes it reads back to the
// same document, it keeps reading every format it ever wrote, and it refuses
// what it cannot read with an error naming the file and the field.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "base/errors.h"
#include "fake_run.h"
#include "reports/profile_table.h"
#include "result/result_codec.h"
#include "test_support.h"

namespace crowdprof {
namespace {

using nlohmann::json;

std::filesystem::path results_dir() {
  return test::source_dir() / "tests" / "data" / "results";
}

std::string refusal(const json& doc) {
  try {
    (void)result_from_json(doc, "r.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ResultCodec, WhatItWritesItReadsBackToTheSameDocument) {
  Result report = test::fake_run("threaded", 40, {2.0, 2.5, 2.2, 2.1}, 0.25);
  report.frame_records[1].gpu_ms = 0.5;  // one frame timed on the GPU, the others not read back
  report.run.gpu_timer_resolution_ms = 0.001;
  report.run.lens = LensRecord{35.0, 32.0, 18.0, "auto"};
  report.run.gpu_skinning = GpuSkinningRecord{"baked", 4096, BakeRecord{30.0, 120, 1.5, 0.01, 0.002}};
  report.animation = AnimationRecord{{40, 0, 0, 0, 0, 0, 0}, 1, 0, 0.25, 0.01, 40, 3};
  report.mesh_lod =
      MeshLodRecord{{{2, 0, 0, 0}, {10, 0.001, 0.0005, 0.1}, {20, 0.003, 0.0015, 0.2}, {8, 0.006, 0.0035, 0.3}}};
  report.culling_audit = CullingAudit{16, 160, 1, 1800, 700, 60, {}, 0};
  for (size_t b = 0; b < kCullBoxes; ++b)
    report.culling_audit->boxes[b] = CullBoxAudit{2000, 3 + b, 130, 1, 12, 4.5, 9.0};
  report.drawn_error = DrawnErrorRecord{100, 40, 495100, 1, 0.15, 0.02, 0.08, 0.01, 3.5, 0.4, 0.006, 12.5};
  report.partial = true;
  report.frames_planned = 10;
  record_samples(report);
  json written = result_to_json(report);
  Result read = result_from_json(written, "r.json");
  EXPECT_EQ(result_to_json(read), written);
  EXPECT_EQ(read.frames(), 4u);
  EXPECT_EQ(read.run.mode, "threaded");
  ASSERT_EQ(read.samples.gpu_ms.size(), 4u);
  EXPECT_TRUE(std::isnan(read.samples.gpu_ms[0]));
  EXPECT_DOUBLE_EQ(read.samples.gpu_ms[1], 0.5);
  ASSERT_TRUE(read.run.gpu_skinning && read.run.gpu_skinning->bake);
  EXPECT_EQ(read.run.gpu_skinning->bake->samples, 120u);
  ASSERT_TRUE(read.animation);
  EXPECT_EQ(read.animation->copies_deviating, 3u);
  ASSERT_TRUE(read.mesh_lod);
  EXPECT_EQ(read.mesh_lod->levels[2].copies, 20u);
  EXPECT_DOUBLE_EQ(read.mesh_lod->levels[3].error_px, 0.3);
  ASSERT_TRUE(read.drawn_error);
  EXPECT_DOUBLE_EQ(read.drawn_error->switches_per_second, 12.5);
  EXPECT_EQ(read.drawn_error->vertices, 495100u);
  ASSERT_TRUE(read.culling_audit);
  ASSERT_EQ(read.culling_audit->boxes.size(), 4u);
  EXPECT_EQ(read.culling_audit->boxes[1].false_culls, 4u) << "in the strategies' own order";
  EXPECT_EQ(read.culling_audit->boxes[3].worst_frame_missed_culls, 12u);
  EXPECT_TRUE(read.partial);
  EXPECT_EQ(read.frames_planned, 10u);
}

TEST(ResultCodec, GpuPassesAndPipelineStatisticsReadBack) {
  Result report = test::fake_run("hwskin", 40, {2.0, 2.5, 2.2}, 0.25);
  report.run.switches.passes = 3;  // prepass, one cascade, colour
  report.run.pipeline_statistics_missing = "";
  for (size_t f = 0; f < report.frame_records.size(); ++f) {
    FrameRecord& frame = report.frame_records[f];
    frame.gpu_ms = 1.0 + 0.1 * static_cast<double>(f);
    frame.gpu_passes.ms = {0.1, 0.2, 0.3, 0.35};
    for (size_t p = 0; p < kGpuPassCount; ++p)
      for (size_t s = 0; s < kPipelineStatCount; ++s)
        frame.gpu_passes.stats[p][s] = static_cast<double>(100 * p + s + f);
  }
  report.frame_records[0].gpu_passes.ms[3] = std::nan("");
  report.run.gpu_memory =
      GpuMemoryRecord{"NVX_gpu_memory_info", uint64_t{80} << 30, std::nullopt,
                      uint64_t{2} << 30};  // read back without its colour pass: impossible, kept as null
  record_samples(report);
  json written = result_to_json(report);
  ASSERT_TRUE(written["gpu_time"].contains("passes"));
  EXPECT_EQ(written["gpu_time"]["passes"].size(), 4u) << "skinning, prepass, shadows, colour";
  EXPECT_NEAR(written["gpu_time"]["pass_coverage"].get<double>(), (0.1 + 0.2 + 0.3 + 0.35) / 1.1, 1e-9);
  EXPECT_EQ(written["gpu_time"]["passes"][3]["statistics"]["vertices_submitted"], 301) << "the median of 300, 301, 302";
  EXPECT_TRUE(written["samples"]["gpu_colour_ms"][0].is_null());
  Result read = result_from_json(written, "r.json");
  EXPECT_EQ(result_to_json(read), written);
  ASSERT_TRUE(read.pipeline_statistics);
  EXPECT_EQ((*read.pipeline_statistics)[1][static_cast<size_t>(PipelineStat::VertexShaderInvocations)], 103);
  EXPECT_DOUBLE_EQ(read.samples.gpu_pass_ms[2][1], 0.3);
  ASSERT_TRUE(read.run.gpu_memory);
  EXPECT_EQ(read.run.gpu_memory->total_bytes, uint64_t{80} << 30);
  EXPECT_FALSE(read.run.gpu_memory->free_bytes);
  EXPECT_EQ(read.run.gpu_memory->max_storage_block_bytes, uint64_t{2} << 30);

  // A GL without the statistics: the times, and why there are no statistics.
  for (FrameRecord& frame : report.frame_records)
    for (auto& pass : frame.gpu_passes.stats) pass.fill(std::nan(""));
  report.run.pipeline_statistics_missing = "llvmpipe lacks ARB_pipeline_statistics_query";
  record_samples(report);
  written = result_to_json(report);
  EXPECT_EQ(written["gpu_time"]["statistics_reason"], "llvmpipe lacks ARB_pipeline_statistics_query");
  EXPECT_FALSE(written["gpu_time"]["passes"][0].contains("statistics"));
  read = result_from_json(written, "r.json");
  EXPECT_FALSE(read.pipeline_statistics);
  EXPECT_EQ(result_to_json(read), written);
  // A pass the codec does not know is refused, naming it.
  written["gpu_time"]["passes"][0]["pass"] = "bloom";
  EXPECT_NE(refusal(written).find("no pass 'bloom'"), std::string::npos) << refusal(written);
}

TEST(GpuPassMedians, EachDrawnPassOverTheFramesThatTimedIt) {
  const double none = GpuPassFigures::kNone;
  std::array<std::vector<double>, kGpuPassCount> ms = {
      std::vector<double>{1.0, none, 3.0, 2.0},  // skinning: a frame not timed is left out
      {0.5, 0.5, 0.5, 0.5},                      // prepass: not drawn at 1 pass
      {},                                        // shadows: not drawn
      {none, none, none, none}};                 // colour: drawn, never timed
  GpuPassMedians one = gpu_pass_medians(ms, 1);
  EXPECT_EQ(one.median[0], 2.0);
  EXPECT_FALSE(one.median[1]);
  EXPECT_FALSE(one.median[2]);
  EXPECT_FALSE(one.median[3]);
  EXPECT_DOUBLE_EQ(one.sum, 2.0);
  GpuPassMedians two = gpu_pass_medians(ms, 2);
  EXPECT_EQ(two.median[1], 0.5);
  EXPECT_DOUBLE_EQ(two.sum, 2.5);
}

TEST(ResultCodec, ReadsEveryFormatItEverWrote) {
  size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(results_dir())) {
    if (entry.path().extension() != ".json") continue;
    ++files;
    SCOPED_TRACE(entry.path().filename().string());
    Result read = read_result(entry.path().string());
    EXPECT_EQ(read.format, entry.path().filename().string().starts_with("format2") ? 2 : 1);
    // Either format's categories are found by their series.
    ASSERT_NE(metric_samples(read, "animations_ms"), nullptr);
    EXPECT_GT(metric_median(read, "animations_ms"), 0.0);
    EXPECT_EQ(read.run.characters, 4u);
    EXPECT_EQ(read.run.mode, "culled");
    EXPECT_TRUE(read.run.switches.animation_culling);
    EXPECT_EQ(read.frames(), 3u);
    EXPECT_FALSE(read.digest.empty());
    // Written again, it reads back to the same document.
    json again = result_to_json(read);
    EXPECT_EQ(result_to_json(result_from_json(again, "again.json")), again);
  }
  EXPECT_EQ(files, 3u);
  // The early one lacks what came later within format 1, and says so.
  Result early = read_result((results_dir() / "format1-early.json").string());
  EXPECT_EQ(metric_samples(early, "cpu_ms"), nullptr);
  EXPECT_FALSE(early.counters.present[8]) << kCounterFields[8].name;
  EXPECT_TRUE(early.counters.present[0]);
  EXPECT_FALSE(early.run.lens.has_value());
}

TEST(ResultCodec, AnotherFormatIsRefusedWithTheFormatItReads) {
  json doc = result_to_json(test::fake_run("culled", 4, {1.0, 1.0, 1.0}));
  doc["crowdprof"]["format"] = 3;
  EXPECT_NE(refusal(doc).find("result format 3"), std::string::npos) << refusal(doc);
  EXPECT_NE(refusal(doc).find("this crowdprof reads formats 1 to 2"), std::string::npos) << refusal(doc);
  doc["crowdprof"]["format"] = 0;
  EXPECT_NE(refusal(doc).find("result format 0"), std::string::npos) << refusal(doc);
}

TEST(ResultCodec, ABadFieldIsNamed) {
  json good = result_to_json(test::fake_run("culled", 4, {1.0, 1.0, 1.0}));
  ASSERT_EQ(refusal(good), "");
  struct Case {
    const char* pointer;
    json value;
    const char* words;
  };
  const Case cases[] = {
      {"/scene/characters", json(-4), "\"scene.characters\" should be a whole number"},
      {"/samples/frame_ms", json::array({1.0, 1.0}), "has 2 values for 3 frames"},
      {"/samples/animations_ms/0", json(-1.0), "finite, non-negative milliseconds"},
      {"/counters/draw_calls", json("none"), "\"counters.draw_calls\" should be a whole number"},
      {"/scene/lens", json("wide"), "\"scene.lens\" should be an object"},
      {"/instructions", json::object({{"per_frame", "many"}}), "\"instructions.per_frame\" should be a number"},
      {"/switches/culling", json(7), "culling '7'"},
      {"/mesh_lod",
       json::object({{"copies", {1, 2}}, {"error", {0.0}}, {"error_fraction", {0.0}}, {"error_px", {0.0}}}),
       "\"mesh_lod\" should be arrays of one to four levels, all as long"},
      {"/mesh_lod", json::object({{"copies", {1}}, {"error", {-1.0}}, {"error_fraction", {0.0}}, {"error_px", {0.0}}}),
       "\"mesh_lod.error\" should be an array of distances"},
      {"/culling_audit",
       json::object({{"frames", 1},
                     {"copies", 1},
                     {"copy_stride", 1},
                     {"in_view", 1},
                     {"outside", 0},
                     {"undecided", 0},
                     {"boxes", {{"a/b", json::object()}}}}),
       "\"culling_audit.boxes\" should be an object of bind_pose"},
      {"/culling_audit", json::object({{"frames", -1}}), "\"culling_audit.frames\" should be a whole number"},
      {"/drawn_error",
       json::object({{"copies_checked", 1},
                     {"copies_deviating", 0},
                     {"vertices", 3},
                     {"copy_stride", 0},
                     {"max", 0},
                     {"rms", 0},
                     {"max_fraction", 0},
                     {"rms_fraction", 0},
                     {"max_px", 0},
                     {"rms_px", 0},
                     {"mesh_max", 0},
                     {"switches_per_second", 0}}),
       "\"drawn_error.copy_stride\" should be a whole number, 1 or more"},
      {"/drawn_error",
       json::object({{"copies_checked", 1},
                     {"copies_deviating", 0},
                     {"vertices", 3},
                     {"copy_stride", 1},
                     {"max", -1.0},
                     {"rms", 0},
                     {"max_fraction", 0},
                     {"rms_fraction", 0},
                     {"max_px", 0},
                     {"rms_px", 0},
                     {"mesh_max", 0},
                     {"switches_per_second", 0}}),
       "\"drawn_error.max\" should be a number, 0 or more"},
  };
  for (const Case& c : cases) {
    json bad = good;
    bad[json::json_pointer(c.pointer)] = c.value;
    std::string why = refusal(bad);
    EXPECT_NE(why.find(c.words), std::string::npos) << c.pointer << ": " << why;
    EXPECT_EQ(why.rfind("r.json: ", 0), 0u) << why;
  }
  json no_digest = good;
  no_digest.erase("digest");
  EXPECT_NE(refusal(no_digest).find("no \"digest\""), std::string::npos);
}

// Whether the digest hashes CPU-skinned vertices: written and read back; a
// result from before the field reads as true (it may have); not a flag: named.
TEST(ResultCodec, WhetherTheDigestHashesCpuVerticesReadsBack) {
  json doc = result_to_json(test::fake_run("hwskin", 4, {1.0, 3.0, 2.0}, 0.5));
  EXPECT_EQ(doc.at("digest_cpu_vertices"), true);
  doc["digest_cpu_vertices"] = false;
  EXPECT_FALSE(result_from_json(doc, "r.json").digest_cpu_vertices);
  EXPECT_EQ(result_to_json(result_from_json(doc, "r.json")).at("digest_cpu_vertices"), false);
  doc.erase("digest_cpu_vertices");
  EXPECT_TRUE(result_from_json(doc, "r.json").digest_cpu_vertices);
  doc["digest_cpu_vertices"] = "no";
  try {
    result_from_json(doc, "r.json");
    ADD_FAILURE() << "a string was read as a flag";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("digest_cpu_vertices"), std::string::npos) << e.what();
  }
}

// The order the digest hashed vertices in: "joints" from this build, read
// back; a result from before the field reads as the file's order; anything
// else is named.
TEST(ResultCodec, TheVertexOrderReadsBack) {
  json doc = result_to_json(test::fake_run("threaded", 4, {1.0, 3.0, 2.0}, 0.5));
  EXPECT_EQ(doc.at("vertex_order"), "joints");
  EXPECT_EQ(result_from_json(doc, "r.json").vertex_order, "joints");
  doc.erase("vertex_order");
  EXPECT_EQ(result_from_json(doc, "r.json").vertex_order, "file");
  EXPECT_EQ(result_to_json(result_from_json(doc, "r.json")).at("vertex_order"), "file");
  for (const json& bad : {json("sorted"), json(1)}) {
    doc["vertex_order"] = bad;
    try {
      result_from_json(doc, "r.json");
      ADD_FAILURE() << bad << " was read as an order";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("vertex_order"), std::string::npos) << e.what();
      if (bad.is_string()) {
        EXPECT_NE(std::string(e.what()).find("\"sorted\""), std::string::npos) << e.what();
      }
    }
  }
}

TEST(ResultCodec, BytesUploadedPerCopyOnScreenIsTheMedianFrameAndReadsBack) {
  Result run = test::fake_run("instanced", 40, {1.0, 1.0, 1.0, 1.0});
  // 800 bytes for 10 copies, 900 for 30, none on screen, 700 for 7: 80, 30, -, 100.
  const uint64_t bytes[] = {800, 900, 500, 700}, on_screen[] = {10, 30, 0, 7};
  for (size_t f = 0; f < 4; ++f) {
    run.frame_records[f].counters.bytes_uploaded = bytes[f];
    run.frame_records[f].counters.copies_visible = on_screen[f];
  }
  record_samples(run);
  ASSERT_TRUE(run.bytes_uploaded_per_copy_on_screen);
  EXPECT_DOUBLE_EQ(*run.bytes_uploaded_per_copy_on_screen, 80.0) << "the middle of 30, 80 and 100";
  json doc = result_to_json(run);
  EXPECT_DOUBLE_EQ(doc.at("bytes_uploaded_per_copy_on_screen").get<double>(), 80.0);
  EXPECT_EQ(result_from_json(doc, "r.json").bytes_uploaded_per_copy_on_screen, 80.0);
  // A result from before the field reads without it, and writes without it.
  doc.erase("bytes_uploaded_per_copy_on_screen");
  EXPECT_FALSE(result_from_json(doc, "r.json").bytes_uploaded_per_copy_on_screen);
  EXPECT_FALSE(result_to_json(result_from_json(doc, "r.json")).contains("bytes_uploaded_per_copy_on_screen"));
  doc["bytes_uploaded_per_copy_on_screen"] = -1;
  EXPECT_THROW(result_from_json(doc, "r.json"), InputError);
  // No copy on screen in any frame: 0, not a division by zero.
  Result empty = test::fake_run("instanced", 40, {1.0});
  EXPECT_EQ(empty.bytes_uploaded_per_copy_on_screen, 0.0);
}

// Issue 52: palettes and records apart, each its own median, beside the total.
TEST(ResultCodec, TheAnimationSplitReadsBackAndIsOptional) {
  Result report = test::fake_run("threaded", 40, {2.0, 2.5, 2.2}, 1.0);
  report.run.threads = 2;
  report.run.switches.parallel = true;
  for (size_t f = 0; f < report.frame_records.size(); ++f)
    report.frame_records[f].animation_stages.ms = {0.5 + 0.1 * static_cast<double>(f), 0.25, 0.5, 2.0};
  record_samples(report);
  const std::optional<AnimationSplit> split = animation_split(report);
  ASSERT_TRUE(split);
  EXPECT_EQ(split->threads, 2);
  EXPECT_DOUBLE_EQ(split->median_ms[0], 0.6);
  EXPECT_DOUBLE_EQ(split->share[3], 2.0 / 3.35);
  // Per frame 3.25/4, 3.35/5 and 3.45/4.4 of Animations x 2 threads: the median is frame 2's.
  EXPECT_DOUBLE_EQ(split->coverage, 3.45 / 4.4);
  json written = result_to_json(report);
  EXPECT_DOUBLE_EQ(written["animations_split"]["stages"]["skinning"]["median_ms"].get<double>(), 2.0);
  Result read = result_from_json(written, "r.json");
  EXPECT_EQ(read.samples.animation_stage_ms, report.samples.animation_stage_ms);
  EXPECT_EQ(result_to_json(read), written);

  // Results from before the split have none, and say nothing of it.
  written["samples"].erase("animation_sampling_ms");
  written["samples"].erase("animation_blending_ms");
  written["samples"].erase("animation_local_to_model_ms");
  written["samples"].erase("animation_skinning_ms");
  written.erase("animations_split");
  Result old = result_from_json(written, "r.json");
  EXPECT_FALSE(animation_split(old));
  EXPECT_FALSE(result_to_json(old).contains("animations_split"));
  EXPECT_EQ(format_profile(old).find("Animations by stage"), std::string::npos);
}

TEST(ResultCodec, PaletteAndRecordBytesPerCopyOnScreenReadBackAndAreOptional) {
  Result run = test::fake_run("instanced", 40, {1.0, 1.0, 1.0});
  // Frame 0 sends the placements too (in the total only): 16-byte records throughout.
  const uint64_t total[] = {4000, 360, 680}, palettes[] = {320, 200, 520}, records[] = {160, 160, 160},
                 on_screen[] = {10, 10, 10};
  for (size_t f = 0; f < 3; ++f) {
    Counters& k = run.frame_records[f].counters;
    k.bytes_uploaded = total[f];
    k.palette_bytes_uploaded = palettes[f];
    k.record_bytes_uploaded = records[f];
    k.copies_visible = on_screen[f];
  }
  record_samples(run);
  EXPECT_DOUBLE_EQ(*run.bytes_uploaded_per_copy_on_screen, 68.0);
  EXPECT_DOUBLE_EQ(*run.palette_bytes_per_copy_on_screen, 32.0);
  EXPECT_DOUBLE_EQ(*run.record_bytes_per_copy_on_screen, 16.0);
  json doc = result_to_json(run);
  EXPECT_DOUBLE_EQ(doc.at("palette_bytes_per_copy_on_screen").get<double>(), 32.0);
  EXPECT_DOUBLE_EQ(doc.at("record_bytes_per_copy_on_screen").get<double>(), 16.0);
  const Result back = result_from_json(doc, "r.json");
  EXPECT_EQ(back.palette_bytes_per_copy_on_screen, 32.0);
  EXPECT_EQ(back.record_bytes_per_copy_on_screen, 16.0);
  EXPECT_EQ(result_to_json(back), doc);
  // A result from before them reads without them, and writes without them.
  for (const char* key : {"palette_bytes_per_copy_on_screen", "record_bytes_per_copy_on_screen"}) {
    json old = doc;
    old.erase(key);
    EXPECT_FALSE(result_to_json(result_from_json(old, "r.json")).contains(key)) << key;
    old[key] = -16;
    EXPECT_THROW(result_from_json(old, "r.json"), InputError) << key;
  }
}

TEST(ResultCodec, MetricsAreFoundByTheirSampleKeys) {
  Result r = result_from_json(result_to_json(test::fake_run("culled", 4, {1.0, 3.0, 2.0}, 0.5)), "r.json");
  ASSERT_NE(metric_samples(r, "frame_ms"), nullptr);
  ASSERT_NE(metric_samples(r, "animations_ms"), nullptr);
  EXPECT_EQ(metric_samples(r, "gpu_ms"), nullptr);      // nothing timed on the GPU
  EXPECT_EQ(metric_samples(r, "Animations"), nullptr);  // series, not the names users type
  EXPECT_DOUBLE_EQ(metric_median(r, "frame_ms"), 2.0);
  EXPECT_DOUBLE_EQ(metric_median(r, "animations_ms"), 1.0);
  std::vector<std::string> keys = recorded_metrics(r);
  EXPECT_EQ(keys.front(), "frame_ms");
  EXPECT_EQ(std::count(keys.begin(), keys.end(), "gpu_ms"), 0);
}

}  // namespace
}  // namespace crowdprof
