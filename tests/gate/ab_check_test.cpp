// The A/B gate without a process: the paired statistics against values worked
// by hand (and scipy's conventions), the judgement of ABBA groups, and the
// verdict's reporters.
#include <gtest/gtest.h>

#include <cmath>

#include "gate/ab_check.h"
#include "gate/paired_test.h"
#include "reports/verdict_report.h"

namespace {

using namespace crowdprof;

TEST(SignedRank, ExactWithoutTies) {
  // All ten positive: the one most extreme arrangement of 2^10, both tails.
  std::vector<double> all_up = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  SignedRank up = wilcoxon_signed_rank(all_up);
  EXPECT_TRUE(up.exact);
  EXPECT_EQ(up.w_plus, 55);
  EXPECT_NEAR(up.p, 2.0 / 1024, 1e-12);
  // W- = 1 + 4 = 5: 10 subsets of 1..10 sum to 5 or less (0,1,2,3,3,4,4,5,5,5).
  std::vector<double> mostly_up = {-1, 2, 3, -4, 5, 6, 7, 8, 9, 10};
  SignedRank mostly = wilcoxon_signed_rank(mostly_up);
  EXPECT_EQ(mostly.w_plus, 50);
  EXPECT_NEAR(mostly.p, 20.0 / 1024, 1e-12);
  // The sign does not matter, only the balance.
  std::vector<double> mostly_down = {1, -2, -3, 4, -5, -6, -7, -8, -9, -10};
  EXPECT_NEAR(wilcoxon_signed_rank(mostly_down).p, 20.0 / 1024, 1e-12);
}

TEST(SignedRank, NormalApproximationWithTies) {
  // |d| 1 x5 (rank 3), 2 x4 (7.5), 3 x3 (11); W+ = 67.5, mean 39,
  // variance 12*13*25/24 - (120 + 60 + 24)/48 = 158.25; z = 28/sqrt(158.25).
  std::vector<double> d = {1, 1, 1, 1, -1, 2, 2, 2, -2, 3, 3, 3};
  SignedRank test = wilcoxon_signed_rank(d);
  EXPECT_FALSE(test.exact);
  EXPECT_EQ(test.w_plus, 67.5);
  EXPECT_NEAR(test.p, std::erfc(28 / std::sqrt(158.25) / std::sqrt(2.0)), 1e-12);
  EXPECT_NEAR(test.p, 0.02603, 1e-4);
}

TEST(SignedRank, ZerosAreDroppedAndNothingLeftIsNoEvidence) {
  std::vector<double> zeros = {0, 0, 0};
  EXPECT_EQ(wilcoxon_signed_rank(zeros).p, 1);
  EXPECT_EQ(wilcoxon_signed_rank(zeros).n, 0u);
  std::vector<double> some = {0, 0, 1, 2, 3};
  EXPECT_EQ(wilcoxon_signed_rank(some).n, 3u);
  EXPECT_NEAR(wilcoxon_signed_rank(some).p, 2.0 / 8, 1e-12);
}

TEST(BootstrapMedian, SeededAndAroundTheMedian) {
  std::vector<double> values = {0.9, 1.0, 1.1, 1.05, 0.95, 1.2, 0.98, 1.02, 1.01, 0.99};
  MedianInterval a = bootstrap_median(values), b = bootstrap_median(values);
  EXPECT_EQ(a.low, b.low);
  EXPECT_EQ(a.high, b.high);
  EXPECT_NEAR(a.median, 1.005, 1e-12);
  EXPECT_LE(a.low, a.median);
  EXPECT_GE(a.high, a.median);
  EXPECT_GE(a.low, 0.9);
  EXPECT_LE(a.high, 1.2);
  std::vector<double> one = {3};
  EXPECT_EQ(bootstrap_median(one).low, 3);
  EXPECT_EQ(bootstrap_median(one).high, 3);
}

TEST(Holm, StepDown) {
  std::vector<double> p = {0.01, 0.04, 0.03};
  std::vector<double> adjusted = holm_adjust(p);
  EXPECT_NEAR(adjusted[0], 0.03, 1e-12);  // smallest x3
  EXPECT_NEAR(adjusted[2], 0.06, 1e-12);  // next x2
  EXPECT_NEAR(adjusted[1], 0.06, 1e-12);  // x1 = 0.04, made monotone
}

AbProcess process(double frame_ms, const std::string& digest = "d", uint64_t skinned = 100) {
  AbProcess p;
  p.median_ms = {{"frame_ms", frame_ms}, {"cpu_ms", frame_ms * 2}};
  p.digest = digest;
  p.counters.values.vertices_skinned = skinned;
  p.counters.present.fill(true);
  return p;
}

// Ten groups whose machine level moves by half between groups: the ratio
// inside each group is what the gate sees.
std::vector<AbGroup> groups(double current_over_base, double level_swing = 0.5) {
  std::vector<AbGroup> out;
  for (int g = 0; g < 10; ++g) {
    double level = 1 + level_swing * ((g * 7) % 10) / 10.0;
    double jitter = 1 + 0.004 * ((g * 3) % 5 - 2);
    AbGroup group;
    group.base_first = g % 2 == 0;
    group.base[0] = process(level);
    group.base[1] = process(level * 1.002);
    group.current[0] = process(level * current_over_base * jitter);
    group.current[1] = process(level * current_over_base * jitter * 0.999);
    out.push_back(group);
  }
  return out;
}

TEST(AbGate, PairingCancelsTheMachinesLevel) {
  AbOptions options;
  AbResult same = judge_ab(groups(1.0), options);
  ASSERT_EQ(same.metrics.size(), 1u);
  EXPECT_NEAR(same.metrics[0].change.median, 0, 0.01);
  EXPECT_FALSE(same.metrics[0].regressed);
  EXPECT_FALSE(same.regressed());
  EXPECT_TRUE(same.work.equal);

  AbResult slower = judge_ab(groups(1.10), options);
  EXPECT_NEAR(slower.metrics[0].change.median, 0.10, 0.01);
  EXPECT_LT(slower.metrics[0].change.low, 0.10);
  EXPECT_GT(slower.metrics[0].change.high, 0.09);
  EXPECT_TRUE(slower.metrics[0].significant);
  EXPECT_TRUE(slower.metrics[0].regressed);
  EXPECT_TRUE(slower.regressed());

  AbResult faster = judge_ab(groups(0.85), options);
  EXPECT_TRUE(faster.metrics[0].improved);
  EXPECT_FALSE(faster.regressed());

  // Within the tolerance: significant, yet not a failure.
  AbResult small = judge_ab(groups(1.03), options);
  EXPECT_TRUE(small.metrics[0].significant);
  EXPECT_FALSE(small.metrics[0].regressed);
}

TEST(AbGate, OtherWorkFailsWhateverTheTimes) {
  std::vector<AbGroup> g = groups(1.0);
  g[3].current[1] = process(1.0, "d", 120);
  AbResult result = judge_ab(g, {});
  EXPECT_FALSE(result.work.equal);
  EXPECT_EQ(result.work.inconsistent, "current");
  EXPECT_TRUE(result.regressed());

  std::vector<AbGroup> other = groups(1.0);
  for (AbGroup& group : other)
    for (AbProcess& p : group.current) p = process(p.median_ms["frame_ms"], "e", 150);
  AbResult changed = judge_ab(other, {});
  ASSERT_EQ(changed.work.counters.size(), 1u);
  EXPECT_EQ(changed.work.counters[0].baseline, 100u);
  EXPECT_EQ(changed.work.counters[0].current, 150u);
  EXPECT_EQ(changed.work.current_digest, "e");
  EXPECT_TRUE(changed.regressed());

  AbOptions timings_only;
  timings_only.compare_work = false;
  EXPECT_FALSE(judge_ab(other, timings_only).regressed());
}

// A base built before the bench ordered vertices by their joints hashed them
// in the file's order: its digest is not compared, and the verdict says why;
// its counters are.
TEST(AbGate, DigestsOfOtherVertexOrdersAreNotCompared) {
  std::vector<AbGroup> g = groups(1.0);
  for (AbGroup& group : g)
    for (AbProcess& p : group.base) {
      p.digest = "file-order";
      p.vertex_order = "file";
    }
  AbResult reordered = judge_ab(g, {});
  EXPECT_TRUE(reordered.work.equal);
  EXPECT_FALSE(reordered.regressed());
  GateTable table = ab_verdict_table(reordered, {});
  EXPECT_NE(table.work_detail.find("not compared: the baseline hashed its vertices in the file's order"),
            std::string::npos)
      << table.work_detail;
  for (AbGroup& group : g)
    for (AbProcess& p : group.current) p.counters.values.vertices_skinned = 101;
  EXPECT_TRUE(judge_ab(g, {}).regressed());
  // Palettes (every character GPU-skinned) have no vertex order: compared.
  for (AbGroup& group : g) {
    for (AbProcess& p : group.base) p.digest_cpu_vertices = false;
    for (AbProcess& p : group.current) p.digest_cpu_vertices = false, p.counters.values.vertices_skinned = 100;
  }
  EXPECT_FALSE(judge_ab(g, {}).work.equal);
}

TEST(AbGate, MetricsAreHolmCorrectedTogether) {
  AbOptions options;
  options.metrics = {"frame_ms", "cpu_ms"};
  AbResult result = judge_ab(groups(1.10), options);
  ASSERT_EQ(result.metrics.size(), 2u);
  EXPECT_GE(result.metrics[0].p_adjusted, result.metrics[0].test.p);
  EXPECT_THROW(judge_ab({}, options), std::invalid_argument);
  options.metrics = {"animations_ms"};
  EXPECT_THROW(judge_ab(groups(1.0), options), std::invalid_argument);
}

TEST(VerdictReport, JUnitMarkdownAndText) {
  AbOptions options;
  GateTable table = ab_verdict_table(judge_ab(groups(1.10), options), options);
  table.command = "crowdprof check --against";
  table.scene = "thesis.json × 160, threaded";
  table.seconds = 12.25;
  table.title = "A/B <of> two & builds\n  base:    crowdprof 1\n  current: crowdprof 2";
  table.reproduce = "crowdprof check scene.glb --against base";
  std::string xml = verdict_junit(table);
  EXPECT_NE(xml.find("<testsuites name=\"crowdprof\" tests=\"2\" failures=\"1\" time=\"12.250\">"), std::string::npos)
      << xml;
  EXPECT_NE(xml.find("<testsuite name=\"crowdprof check --against (thesis.json × 160, threaded)\""), std::string::npos)
      << xml;
  EXPECT_NE(xml.find("<testcase classname=\"crowdprof check --against (thesis.json × 160, threaded)\" name=\"frame\" "
                     "time=\"12.250\">"),
            std::string::npos)
      << xml;
  EXPECT_NE(xml.find("<failure message=\"frame +"), std::string::npos) << xml;
  // The title's lines: one line in the property, as lines in the suite's text.
  EXPECT_NE(xml.find("value=\"A/B &lt;of&gt; two &amp; builds; base: crowdprof 1; current: crowdprof 2\""),
            std::string::npos)
      << xml;
  EXPECT_NE(xml.find("<system-out>A/B &lt;of&gt; two &amp; builds\n  base:    crowdprof 1\n"), std::string::npos)
      << xml;
  EXPECT_EQ(xml.find("<of>"), std::string::npos);
  std::string markdown = verdict_markdown(table);
  EXPECT_EQ(markdown.rfind("### crowdprof check --against (thesis.json × 160, threaded): FAILED", 0), 0u) << markdown;
  EXPECT_NE(markdown.find("| frame |"), std::string::npos);
  EXPECT_NE(markdown.find("**slower**"), std::string::npos);
  EXPECT_NE(markdown.find("crowdprof check scene.glb --against base"), std::string::npos);
  std::string text = verdict_text(table);
  EXPECT_NE(text.find("slower"), std::string::npos);
  EXPECT_NE(text.find("work: the same (digest d)"), std::string::npos) << text;
  EXPECT_NE(text.find("reproduce: crowdprof check"), std::string::npos);

  GateTable passed = ab_verdict_table(judge_ab(groups(1.0), options), options);
  EXPECT_NE(verdict_junit(passed).find("failures=\"0\""), std::string::npos);
  EXPECT_EQ(verdict_markdown(passed).rfind("### crowdprof check: passed", 0), 0u) << "no scene: the command alone";
  EXPECT_EQ(verdict_text(passed).find("reproduce:"), std::string::npos);
}

// A work failure's detail takes lines: the message is one line, the detail
// the failure's text.
TEST(VerdictReport, JUnitAttributesAreOneLine) {
  GateTable table;
  table.scene = "a\nb.json × 2, master";
  table.title = "line one\nline two";
  table.work_compared = true;
  table.work_equal = false;
  table.work_detail = "digest 1 -> 2\n  the runs differ: frames";
  const std::string xml = verdict_junit(table);
  bool in_tag = false, in_value = false;
  for (char c : xml) {
    if (!in_value && c == '<') in_tag = true;
    if (!in_value && c == '>') in_tag = false;
    if (in_tag && c == '"') in_value = !in_value;
    EXPECT_FALSE(in_value && c == '\n') << "a newline inside an attribute: " << xml;
  }
  EXPECT_NE(xml.find("message=\"the work changed: digest 1 -&gt; 2; the runs differ: frames\""), std::string::npos)
      << xml;
  EXPECT_NE(xml.find(">digest 1 -&gt; 2\n  the runs differ: frames</failure>"), std::string::npos) << xml;
}

}  // namespace

// Base, current and change are one computation: current is the base's median
// times the paired change, so the three agree in the text, Markdown and JUnit
// even when the builds' own medians moved the other way (issue 50: "frame
// 0.1336 0.1338 -0.4%"). Here the current build's processes ran at a slower
// moment of the machine (its median is higher) while every pair says it is 2%
// faster.
TEST(AbGate, BaseCurrentAndChangeAgreeWhereTheMediansDrifted) {
  std::vector<AbGroup> g;
  for (int k = 0; k < 10; ++k) {
    AbGroup group;
    const double base_level = 1.0 + 0.01 * k, current_level = 1.2 + 0.01 * k;  // current's processes: later, slower
    group.base[0] = process(base_level);
    group.base[1] = process(current_level);
    group.current[0] = process(base_level * 0.98);
    group.current[1] = process(current_level * 0.98 * 1.3);  // its moment was slower still
    g.push_back(group);
  }
  // Each group's ratio: sqrt(0.98 * 0.98 * 1.3) = 1.117 ... the paired change,
  // while the medians of each build moved by another amount.
  const AbResult result = judge_ab(g, AbOptions{});
  const AbMetric& m = result.metrics[0];
  EXPECT_NEAR(m.current_ms / m.base_ms - 1, m.change.median, 1e-12);
  EXPECT_GT(std::fabs(m.current_median_ms / m.base_ms - 1 - m.change.median), 0.02) << "the medians drifted apart";
  const GateTable table = ab_verdict_table(result, AbOptions{});
  ASSERT_EQ(table.metrics.size(), 1u);
  const GateRow& row = table.metrics[0];
  EXPECT_NEAR(row.current_ms / row.base_ms - 1, row.change, 1e-12);
  // The reporters print the same three numbers.
  char base[32], current[32];  // as the reporters print milliseconds
  std::snprintf(base, sizeof base, row.base_ms < 1 ? "%.4f" : "%.3f", row.base_ms);
  std::snprintf(current, sizeof current, row.current_ms < 1 ? "%.4f" : "%.3f", row.current_ms);
  for (const std::string& text : {verdict_text(table), verdict_markdown(table), verdict_junit(table)}) {
    EXPECT_NE(text.find(base), std::string::npos) << text;
    EXPECT_NE(text.find(current), std::string::npos) << text;
  }
}
