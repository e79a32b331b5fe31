// The documents that hold results (compare and capacity --json) are read into
// types by one reader, and a comparison is written by the codec's one writer:
// what it writes it reads back to the same document, and a hostile row is
// refused naming it.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "base/errors.h"
#include "fake_run.h"
#include "gate/diff.h"
#include "reports/compare_report.h"
#include "result/result_document.h"

namespace crowdprof {
namespace {

using nlohmann::json;

Comparison two_modes_and_a_sweep() {
  Comparison c;
  c.runs = {test::fake_run("master", 40, {10, 11, 9}, 0.5), test::fake_run("threaded", 40, {5, 5, 6}, 0.5)};
  c.runs[1].frame_records[0].counters.copies_visible = 31;  // two of three frames: the median
  c.runs[1].frame_records[1].counters.copies_visible = 31;
  c.sweep = {c.runs[0], c.runs[1], test::fake_run("master", 80, {20, 21, 19}),
             test::fake_run("threaded", 80, {8, 9, 8})};
  record_samples(c.runs[1]);
  c.block = 5;
  return c;
}

TEST(ResultDocument, AComparisonReadsBackToTheSameDocument) {
  const json written = comparison_to_json(two_modes_and_a_sweep());
  const ResultDocument read = result_document_from_json(written, "c.json");
  EXPECT_EQ(read.kind, "compare");
  ASSERT_EQ(read.runs.size(), 2u);
  ASSERT_EQ(read.summary.size(), 2u);
  EXPECT_DOUBLE_EQ(read.summary[1].frame_ms, 5.0);
  EXPECT_DOUBLE_EQ(read.summary[1].speedup, 2.0);
  EXPECT_EQ(read.summary[1].counters.copies_visible, 31u) << "each counter's median over frames";
  EXPECT_EQ(read.summary[0].digest, "00000000000000aa");
  ASSERT_EQ(read.sweep.size(), 4u);
  EXPECT_EQ(read.sweep[3].characters, 80u);
  EXPECT_DOUBLE_EQ(read.sweep[3].speedup, 20.0 / 8.0);
  EXPECT_EQ(read.block_frames, 5u);
  EXPECT_EQ(result_document_to_json(read), written);
}

TEST(ResultDocument, ACapacitySearchReadsBackToTheSameDocument) {
  ResultDocument d;
  d.kind = "capacity";
  d.block_frames = 4;
  d.runs = {test::fake_run("threaded", 640, {12, 13, 12})};
  CapacityRecord& c = d.capacity.emplace();
  c.budget_ms = 16.7;
  c.metric = "frame";
  c.start = 10;
  c.precision = 0.05;
  c.frames_per_point = 3;
  c.warmup = 1;
  CapacityPoint fit{640, 12.0, 13.0, 13.0, 12.0, 13.0, 12.0, 3, 2, false, "00000000000000aa"};
  CapacityPoint over{1280, 25.0, 26.0, 26.0, 24.0, 26.0, 25.0, 3, 3, false, "00000000000000bb"};
  c.rows.push_back({"threaded", 2, 100000, false, false, fit, over, {fit, over}});
  for (const CapacityPoint& p : {fit, over}) {
    ModeMedians point;
    point.mode = "threaded";
    point.characters = p.n;
    point.frame_ms = p.frame_median_ms;
    d.sweep.push_back(point);
  }
  const json written = result_document_to_json(d);
  EXPECT_EQ(written["modes"][0]["largest_fit"]["fits"], true);
  EXPECT_EQ(written["modes"][0]["first_over"]["fits"], false);
  EXPECT_FALSE(written["scene"].contains("characters")) << "each point has its own";
  const ResultDocument read = result_document_from_json(written, "cap.json");
  ASSERT_TRUE(read.capacity);
  ASSERT_EQ(read.capacity->rows.size(), 1u);
  ASSERT_TRUE(read.capacity->rows[0].over);
  EXPECT_EQ(read.capacity->rows[0].over->digest, "00000000000000bb");
  EXPECT_EQ(read.capacity->rows[0].points.size(), 2u);
  EXPECT_EQ(result_document_to_json(read), written);
  json hostile = written;
  hostile["modes"][0]["points"][1]["partial"] = "yes";
  EXPECT_THROW(result_document_from_json(hostile, "cap.json"), InputError);
}

TEST(ResultDocument, ADiffReadsBackToTheSameDocument) {
  std::vector<Result> a = {test::fake_run("threaded", 40, {5, 5, 6})};
  std::vector<Result> b = {test::fake_run("threaded", 40, {6, 6, 7})};
  b[0].frame_records[1].counters.copies_visible = 9;
  b[0].digest = "00000000000000bb";
  record_samples(b[0]);
  const json written = diff_to_json(diff_results(a, "a.json", b, "b.json", CheckOptions{}), CheckOptions{});
  const DiffRecord read = diff_record_from_json(written, "d.json");
  ASSERT_EQ(read.pairs.size(), 1u);
  EXPECT_TRUE(read.regressed) << "other work: the counters and digest changed";
  EXPECT_EQ(read.pairs[0].digest_b, "00000000000000bb");
  ASSERT_FALSE(read.pairs[0].metrics.empty());
  EXPECT_FALSE(read.pairs[0].metrics[0].p) << "results measured apart get no p-value";
  EXPECT_EQ(diff_record_to_json(read), written);
  json hostile = written;
  hostile["pairs"][0]["metrics"][0]["a_median_ms"] = "fast";
  try {
    diff_record_from_json(hostile, "d.json");
    ADD_FAILURE() << "a string median was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("pairs[0].metrics[0].a_median_ms"), std::string::npos) << e.what();
  }
  EXPECT_THROW(diff_record_from_json(comparison_to_json(two_modes_and_a_sweep()), "c.json"), InputError);
  // Versioned as results are: a format this crowdprof does not read is refused.
  EXPECT_EQ(written["crowdprof"]["format"], kResultFormat);
  json future = written;
  future["crowdprof"]["format"] = kResultFormat + 1;
  try {
    diff_record_from_json(future, "d.json");
    ADD_FAILURE() << "a future format was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("this crowdprof reads formats"), std::string::npos) << e.what();
  }
  json compare = comparison_to_json(two_modes_and_a_sweep());
  compare["crowdprof"]["format"] = kResultFormat + 1;
  EXPECT_THROW(result_document_from_json(compare, "c.json"), InputError);
}

TEST(ResultDocument, AHostileRowIsRefusedNamingIt) {
  const json good = comparison_to_json(two_modes_and_a_sweep());
  struct Case {
    const char* list;
    const char* field;
    json value;
    const char* says;
  };
  for (const Case& c :
       {Case{"summary", "threads", "two", "a \"summary\" row whose \"threads\""},
        Case{"summary", "speedup", -1.0, "a \"summary\" row whose \"speedup\""},
        Case{"sweep", "frame_median_ms", nullptr, "a \"sweep\" row without mode, characters and frame_median_ms"},
        Case{"sweep", "counters", json::array(), "a \"sweep\" row whose \"counters\""}}) {
    json doc = good;
    doc[c.list][0][c.field] = c.value;
    try {
      result_document_from_json(doc, "c.json");
      ADD_FAILURE() << c.list << "." << c.field << " was read";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(c.says), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("c.json"), std::string::npos) << e.what();
    }
  }
  json diff = good;
  diff["crowdprof"]["kind"] = "diff";
  EXPECT_THROW(result_document_from_json(diff, "d.json"), InputError);
}

}  // namespace
}  // namespace crowdprof

TEST(ResultDocument, AnABCheckIsNotAReportsInputAndSaysWhereItsPageIs) {
  const nlohmann::json ab = {{"crowdprof", {{"version", "0.1.0"}, {"format", 2}, {"kind", "ab_check"}}}};
  try {
    crowdprof::result_document_from_json(ab, "ab.json");
    FAIL() << "read an A/B check as a result";
  } catch (const crowdprof::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("ab.json"), std::string::npos) << what;
    EXPECT_NE(what.find("check --against BASE --html FILE"), std::string::npos) << what;
  }
}
