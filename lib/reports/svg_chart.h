// Plain SVG charts for reports: lines (frame time per frame, the thesis's
// figure 11; median frame time against crowd size), stacked bars (where each
// mode's frame goes), stacked areas (where each frame goes) and a verdict per
// metric (check). No scripts or external fonts: a file opens in any browser and
// can be kept as a CI artifact, and the HTML report inlines the same charts.
#pragma once

#include <string>
#include <vector>

namespace crowdprof {

struct LineSeries {
  std::string name;
  std::vector<double> x, y;  // as many x as y
  std::string colour = {};   // empty: the series' place in the chart picks one
  // False: its points as dots, no line between them (data-geometry="dots"),
  // for points that are not a sequence (every lever a search measured).
  bool joined = true;
};

// A horizontal line across a line chart at `y`: a frame budget, a percentile.
struct Guide {
  double y = 0;
  // In the right margin beside the line's end, clear of the data; empty: the
  // line is named by the chart's legend key for its kind (LineChart::keys).
  std::string label;
  std::string colour = "#444";
  std::string dash = "6,4";
  std::string kind = "guide";  // the element's class and legend key, for readers and tests
  // True: the y axis stretches to show it. False: when it is above the data's
  // scale, a note in the margin says so instead of squashing the data flat.
  bool fit = true;
};

// A legend entry for a kind of guide line ("percentile p95"): a sample of its
// dash and words, for guides too many to label one by one.
struct LegendKey {
  std::string kind;  // the guides' kind it names
  std::string text;  // "p95 (each run's colour)"
  std::string dash;
};

struct LineChart {
  std::string title, x_label, y_label;  // labels carry units: "frame time (ms)"
  std::vector<LineSeries> series;       // one polyline each
  bool markers = false;                 // a dot on every point (for few points)
  bool log_x = false;                   // a log-scaled x axis (crowd sizes); x <= 0 not drawn
  std::vector<Guide> guides = {};
  std::string id = {};               // data-chart, to find the chart in a page
  std::vector<LegendKey> keys = {};  // under the series' legend
};

struct StackedBars {
  std::string title, y_label;
  std::vector<std::string> segments;        // bottom to top, e.g. category names
  std::vector<std::string> bars;            // one bar each, left to right
  std::vector<std::vector<double>> values;  // [bar][segment]
  std::vector<std::string> colours = {};    // per segment; empty: by position
  std::string id = {};
};

// Layers stacked on one another over x (categories per frame).
struct AreaLayer {
  std::string name, colour;
  std::vector<double> y;  // one per x; not finite or negative counts as 0
};
struct StackedArea {
  std::string title, x_label, y_label;
  std::vector<double> x;
  std::vector<AreaLayer> layers;  // bottom to top
  std::string id = {};
};

// One row per metric: the change of its median against the allowed band.
struct VerdictRow {
  std::string name;     // "frame", "Animations"
  double change = 0;    // a fraction: +0.2 is 20% slower
  std::string verdict;  // "ok", "REGRESSION", ...
  std::string colour;
  std::string detail;    // tooltip: medians, p-value
  double allowed = 0.1;  // the band [0, allowed] of slowdown this metric may show
};
struct VerdictChart {
  std::string title;
  std::vector<VerdictRow> rows;
  std::string id = {};
  std::string against = "the baseline";  // the axis's words: "A" for a diff
};

// Charts stacked top to bottom in one <svg>. Every chart is a
// <g class="chart ..." data-chart="ID" data-series="N">, every series a
// <g class="series" data-name="..." data-geometry="line|area|dots"
// data-points="N">, every bar a <g class="bar" data-segments="N">, every guide
// line a <g class="KIND" data-guide="KIND" data-value="Y"> and every legend
// entry a <g class="legend" data-for="NAME or KIND">, so scripts (and tests)
// can find them, count what the browser drew and see that each is named;
// names are escaped. Labels sit in the right margin, one below another, never
// over the plotted data.
class SvgDocument {
 public:
  explicit SvgDocument(int width = 960) : width_(width) {}
  void add(const LineChart& chart);
  void add(const StackedBars& chart);
  void add(const StackedArea& chart);
  void add(const VerdictChart& chart);
  // A standalone SVG file.
  std::string str() const;
  // The same <svg> element without the XML prolog, to inline in HTML.
  std::string inline_svg() const;

 private:
  int width_;
  int height_ = 0;
  std::string body_;
};

// Text made safe for XML content and attribute values.
std::string xml_escape(const std::string& text);

}  // namespace crowdprof
