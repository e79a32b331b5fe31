// The SVG charts: well-formed XML (checked by a small parser here, so the
// test needs no tool), one series per mode, names escaped.
#include <gtest/gtest.h>

#include <cctype>

#include "fake_run.h"
#include "reports/compare_report.h"
#include "reports/svg_chart.h"
#include "test_support.h"

using namespace crowdprof;

namespace {

// Checks the XML 1.0 rules an SVG writer can break: one root element, tags
// nested and closed, attributes quoted and not repeated, '&' only in the five
// named entities or character references, no '<' in text or attributes.
// Returns an empty string when well-formed, else what is wrong and where.
std::string xml_problem(const std::string& xml) {
  std::vector<std::string> open;
  size_t roots = 0, i = 0;
  auto fail = [&](const std::string& what) { return what + " at byte " + std::to_string(i); };
  auto check_text = [&](size_t from, size_t to) -> std::string {
    for (size_t k = from; k < to; ++k) {
      if (xml[k] == '<') return "'<' in text";
      if (xml[k] != '&') continue;
      size_t end = xml.find(';', k);
      if (end == std::string::npos) return "'&' without ';'";
      std::string entity = xml.substr(k + 1, end - k - 1);
      bool named = entity == "amp" || entity == "lt" || entity == "gt" || entity == "quot" || entity == "apos";
      bool numeric = entity.size() > 1 && entity[0] == '#';
      if (!named && !numeric) return "unknown entity &" + entity + ";";
    }
    return {};
  };
  auto is_name = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == ':' || c == '.';
  };
  if (xml.rfind("<?xml", 0) == 0) i = xml.find("?>") + 2;
  while (i < xml.size()) {
    size_t lt = xml.find('<', i);
    std::string text_problem = check_text(i, lt == std::string::npos ? xml.size() : lt);
    if (!text_problem.empty()) return fail(text_problem);
    if (lt == std::string::npos) {
      if (open.empty() && xml.find_first_not_of(" \t\r\n", i) == std::string::npos) break;
      return fail("text outside the root element");
    }
    if (open.empty() && lt > i && xml.find_first_not_of(" \t\r\n", i) < lt)
      return fail("text outside the root element");
    i = lt + 1;
    bool closing = i < xml.size() && xml[i] == '/';
    if (closing) ++i;
    size_t name_start = i;
    while (i < xml.size() && is_name(xml[i])) ++i;
    std::string name = xml.substr(name_start, i - name_start);
    if (name.empty()) return fail("a tag without a name");
    if (closing) {
      if (open.empty() || open.back() != name) return fail("</" + name + "> closes nothing open");
      open.pop_back();
      if (i >= xml.size() || xml[i] != '>') return fail("junk in </" + name + ">");
      ++i;
      continue;
    }
    std::vector<std::string> attributes;
    while (true) {
      while (i < xml.size() && std::isspace(static_cast<unsigned char>(xml[i]))) ++i;
      if (i >= xml.size()) return fail("unterminated <" + name);
      if (xml[i] == '>' || xml.compare(i, 2, "/>") == 0) break;
      size_t a = i;
      while (i < xml.size() && is_name(xml[i])) ++i;
      std::string attribute = xml.substr(a, i - a);
      if (attribute.empty() || i >= xml.size() || xml[i] != '=') return fail("a bad attribute in <" + name);
      if (std::find(attributes.begin(), attributes.end(), attribute) != attributes.end())
        return fail("attribute " + attribute + " twice in <" + name);
      attributes.push_back(attribute);
      char quote = xml[++i];
      if (quote != '"' && quote != '\'') return fail("unquoted attribute " + attribute);
      size_t end = xml.find(quote, i + 1);
      if (end == std::string::npos) return fail("unterminated attribute " + attribute);
      std::string value_problem = check_text(i + 1, end);
      if (!value_problem.empty()) return fail(value_problem + " in attribute " + attribute);
      i = end + 1;
    }
    if (open.empty() && ++roots > 1) return fail("a second root element");
    if (xml[i] == '>') {
      open.push_back(name);
      ++i;
    } else {
      i += 2;
    }
  }
  if (!open.empty()) return "<" + open.back() + "> never closed";
  if (roots != 1) return "no root element";
  return {};
}

// Frames charged 30% to Animations and 70% to Rasterizer, so the stacked bars have two layers.
Result svg_run(const std::string& mode, size_t characters, std::vector<double> frame_ms) {
  return test::fake_run(mode, characters, frame_ms, 0.3);
}

}  // namespace

TEST(Svg, TheCheckerCatchesBrokenXml) {
  EXPECT_EQ(xml_problem("<svg><g a=\"1\"/></svg>"), "");
  for (const char* broken : {"<svg><g></svg>", "<svg a=1/>", "<svg a=\"<\"/>", "<svg>a & b</svg>", "<svg/><svg/>",
                             "<svg a=\"1\" a=\"2\"/>", "<svg>", "<svg></g>", "text"})
    EXPECT_NE(xml_problem(broken), "") << broken;
}

TEST(Svg, AComparisonHasOneSeriesPerModeInEveryChart) {
  Comparison comparison;
  comparison.runs = {svg_run("master", 40, {9, 10, 11, 10}), svg_run("culled", 40, {7, 8, 7, 8}),
                     svg_run("threaded", 40, {3, 2, 3, 3})};
  std::string svg = comparison_svg(comparison);
  EXPECT_EQ(xml_problem(svg), "") << svg.substr(0, 400);
  EXPECT_EQ(test::occurrences(svg, "<g class=\"series\""), 3u);
  EXPECT_EQ(test::occurrences(svg, "<g class=\"bar\""), 3u);
  for (const char* mode : {"master", "culled", "threaded"})
    EXPECT_NE(svg.find("<g class=\"series\" data-name=\"" + std::string(mode) + "\""), std::string::npos) << mode;
  EXPECT_EQ(test::occurrences(svg, "<polyline"), 3u);

  comparison.sweep = {svg_run("master", 10, {2}),  svg_run("culled", 10, {1.8}), svg_run("threaded", 10, {1}),
                      svg_run("master", 40, {10}), svg_run("culled", 40, {7.5}), svg_run("threaded", 40, {3})};
  svg = comparison_svg(comparison);
  EXPECT_EQ(xml_problem(svg), "");
  EXPECT_EQ(test::occurrences(svg, "<g class=\"series\""), 6u) << "three per line chart";
  EXPECT_EQ(test::occurrences(svg, "<g class=\"chart"), 3u);
}

TEST(Svg, NamesAreEscapedAndOddValuesSkipped) {
  SvgDocument doc;
  LineChart chart{"a <title> & \"quotes\"", "x", "y (ms)", {}, true};
  chart.series.push_back({"mode<&>'\"", {0, 1, 2, 3}, {1, NAN, INFINITY, 2}});
  chart.series.push_back({"empty", {}, {}});
  doc.add(chart);
  doc.add(StackedBars{"bars", "ms", {"A&B", "C"}, {"x<y"}, {{1.0, -2.0}}});
  std::string svg = doc.str();
  EXPECT_EQ(xml_problem(svg), "") << svg;
  EXPECT_NE(svg.find("mode&lt;&amp;&gt;&apos;&quot;"), std::string::npos);
  EXPECT_EQ(test::occurrences(svg, "<circle"), 2u) << "NaN and infinity are not drawn";
  EXPECT_EQ(test::occurrences(svg, "<g class=\"series\""), 2u);
}
