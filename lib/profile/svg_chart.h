// Plain SVG charts for reports: lines (frame time per frame, the thesis's
// figure 11; median frame time against crowd size) and stacked bars (where
// each mode's frame goes). No scripts or external fonts: the file opens in any
// browser and can be kept as a CI artifact.
#pragma once

#include <string>
#include <vector>

namespace crowdprof {

struct LineSeries {
  std::string name;
  std::vector<double> x, y;  // as many x as y
};

struct LineChart {
  std::string title, x_label, y_label;  // labels carry units: "frame time (ms)"
  std::vector<LineSeries> series;       // one polyline each, colour by position
  bool markers = false;                 // a dot on every point (for few points)
};

struct StackedBars {
  std::string title, y_label;
  std::vector<std::string> segments;         // bottom to top, e.g. category names
  std::vector<std::string> bars;             // one bar each, left to right
  std::vector<std::vector<double>> values;   // [bar][segment]
};

// Charts stacked top to bottom in one <svg>. Every series is a
// <g class="series" data-name="..."> and every bar a <g class="bar" ...>, so
// scripts (and tests) can find them; names are escaped.
class SvgDocument {
 public:
  explicit SvgDocument(int width = 960) : width_(width) {}
  void add(const LineChart& chart);
  void add(const StackedBars& chart);
  std::string str() const;

 private:
  int width_;
  int height_ = 0;
  std::string body_;
};

// Text made safe for XML content and attribute values.
std::string xml_escape(const std::string& text);

}  // namespace crowdprof
