#include "profile/svg_chart.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace crowdprof {

namespace {

// Okabe-Ito: told apart with every common colour-vision deficiency.
constexpr std::array<const char*, 8> kSeriesColours = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                                       "#E69F00", "#56B4E9", "#F0E442", "#000000"};
// For stacked segments: categories, distinct from each other in order.
constexpr std::array<const char*, 10> kSegmentColours = {"#4E79A7", "#F28E2B", "#E15759", "#76B7B2", "#59A14F",
                                                         "#EDC948", "#B07AA1", "#FF9DA7", "#9C755F", "#BAB0AC"};

constexpr int kPanelHeight = 380;
constexpr double kLeft = 80, kRight = 170, kTop = 44, kBottom = 56;

std::string num(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", value);
  return text;
}

std::string label(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// A round step (1, 2, 2.5 or 5 times a power of ten) giving about `count` ticks.
double nice_step(double span, int count) {
  if (!(span > 0) || !std::isfinite(span)) return 1.0;
  double raw = span / count;
  double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (raw <= m * magnitude) return m * magnitude;
  return 10.0 * magnitude;
}

struct Axis {
  double lo = 0, hi = 1, step = 1;
};

Axis axis_over(double lo, double hi, bool from_zero) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) lo = 0, hi = 1;
  if (from_zero) lo = std::min(lo, 0.0);
  if (hi <= lo) hi = lo + 1;
  Axis a;
  a.step = nice_step(hi - lo, 5);
  a.lo = std::floor(lo / a.step) * a.step;
  a.hi = std::ceil(hi / a.step) * a.step;
  return a;
}

// The frame of a panel: title, plot area, axes with ticks and labels.
struct Panel {
  double top, width;
  double plot_w() const { return width - kLeft - kRight; }
  double plot_h() const { return kPanelHeight - kTop - kBottom; }
  double px(const Axis& a, double x) const { return kLeft + (x - a.lo) / (a.hi - a.lo) * plot_w(); }
  double py(const Axis& a, double y) const { return top + kTop + plot_h() - (y - a.lo) / (a.hi - a.lo) * plot_h(); }
};

void frame(std::string& out, const Panel& p, const std::string& title, const std::string& x_label,
           const std::string& y_label, const Axis& y, const Axis* x) {
  double bottom = p.top + kTop + p.plot_h();
  out += "<text class=\"title\" x=\"" + num(kLeft) + "\" y=\"" + num(p.top + 26) + "\" font-size=\"16\">" +
         xml_escape(title) + "</text>\n";
  for (double v = y.lo; v <= y.hi + y.step * 1e-9; v += y.step) {
    out += "<line x1=\"" + num(kLeft) + "\" x2=\"" + num(kLeft + p.plot_w()) + "\" y1=\"" + num(p.py(y, v)) +
           "\" y2=\"" + num(p.py(y, v)) + "\" stroke=\"#ddd\"/>\n";
    out += "<text x=\"" + num(kLeft - 6) + "\" y=\"" + num(p.py(y, v) + 4) + "\" text-anchor=\"end\">" + label(v) +
           "</text>\n";
  }
  if (x) {
    for (double v = x->lo; v <= x->hi + x->step * 1e-9; v += x->step)
      out += "<text x=\"" + num(p.px(*x, v)) + "\" y=\"" + num(bottom + 16) + "\" text-anchor=\"middle\">" +
             label(v) + "</text>\n";
  }
  out += "<rect x=\"" + num(kLeft) + "\" y=\"" + num(p.top + kTop) + "\" width=\"" + num(p.plot_w()) +
         "\" height=\"" + num(p.plot_h()) + "\" fill=\"none\" stroke=\"#888\"/>\n";
  out += "<text x=\"" + num(kLeft + p.plot_w() / 2) + "\" y=\"" + num(bottom + 40) + "\" text-anchor=\"middle\">" +
         xml_escape(x_label) + "</text>\n";
  double mid = p.top + kTop + p.plot_h() / 2;
  out += "<text x=\"20\" y=\"" + num(mid) + "\" text-anchor=\"middle\" transform=\"rotate(-90 20 " + num(mid) +
         ")\">" + xml_escape(y_label) + "</text>\n";
}

void legend_entry(std::string& out, const Panel& p, size_t index, const std::string& name, const char* colour) {
  double x = kLeft + p.plot_w() + 16, y = p.top + kTop + 8 + 20 * static_cast<double>(index);
  out += "<rect x=\"" + num(x) + "\" y=\"" + num(y - 9) + "\" width=\"14\" height=\"10\" fill=\"" + colour +
         "\"/><text x=\"" + num(x + 20) + "\" y=\"" + num(y) + "\">" + xml_escape(name) + "</text>\n";
}

}  // namespace

std::string xml_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        // Control characters are not allowed in XML 1.0 at all.
        if (static_cast<unsigned char>(c) >= 0x20 || c == '\t' || c == '\n') out += c;
    }
  }
  return out;
}

void SvgDocument::add(const LineChart& chart) {
  Panel p{static_cast<double>(height_), static_cast<double>(width_)};
  double xlo = INFINITY, xhi = -INFINITY, yhi = -INFINITY;
  for (const LineSeries& s : chart.series)
    for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      xlo = std::min(xlo, s.x[i]), xhi = std::max(xhi, s.x[i]), yhi = std::max(yhi, s.y[i]);
    }
  Axis x = axis_over(xlo, xhi, false), y = axis_over(0, yhi, true);
  std::string& out = body_;
  out += "<g class=\"chart line-chart\">\n";
  frame(out, p, chart.title, chart.x_label, chart.y_label, y, &x);
  for (size_t k = 0; k < chart.series.size(); ++k) {
    const LineSeries& s = chart.series[k];
    const char* colour = kSeriesColours[k % kSeriesColours.size()];
    std::string points, dots;
    for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      std::string at = num(p.px(x, s.x[i])) + "," + num(p.py(y, s.y[i]));
      points += (points.empty() ? "" : " ") + at;
      if (chart.markers)
        dots += "<circle cx=\"" + num(p.px(x, s.x[i])) + "\" cy=\"" + num(p.py(y, s.y[i])) + "\" r=\"3\"/>";
    }
    out += "<g class=\"series\" data-name=\"" + xml_escape(s.name) + "\" fill=\"" + colour + "\">\n<polyline points=\"" +
           points + "\" fill=\"none\" stroke=\"" + colour + "\" stroke-width=\"1.5\"/>" + dots + "\n</g>\n";
    legend_entry(out, p, k, s.name, colour);
  }
  out += "</g>\n";
  height_ += kPanelHeight;
}

void SvgDocument::add(const StackedBars& chart) {
  Panel p{static_cast<double>(height_), static_cast<double>(width_)};
  double top = 0;
  for (const auto& bar : chart.values) {
    double sum = 0;
    for (double v : bar) sum += std::isfinite(v) && v > 0 ? v : 0;
    top = std::max(top, sum);
  }
  Axis y = axis_over(0, top, true);
  std::string& out = body_;
  out += "<g class=\"chart stacked-bars\">\n";
  frame(out, p, chart.title, "", chart.y_label, y, nullptr);
  double slot = chart.bars.empty() ? p.plot_w() : p.plot_w() / static_cast<double>(chart.bars.size());
  double bar_w = std::min(120.0, slot * 0.6);
  double bottom = p.top + kTop + p.plot_h();
  for (size_t b = 0; b < chart.bars.size(); ++b) {
    double cx = kLeft + slot * (static_cast<double>(b) + 0.5);
    out += "<g class=\"bar\" data-name=\"" + xml_escape(chart.bars[b]) + "\">\n";
    double level = 0;
    for (size_t s = 0; b < chart.values.size() && s < chart.values[b].size() && s < chart.segments.size(); ++s) {
      double v = chart.values[b][s];
      if (!std::isfinite(v) || v <= 0) continue;
      double y0 = p.py(y, level), y1 = p.py(y, level + v);
      out += "<rect x=\"" + num(cx - bar_w / 2) + "\" y=\"" + num(y1) + "\" width=\"" + num(bar_w) + "\" height=\"" +
             num(y0 - y1) + "\" fill=\"" + kSegmentColours[s % kSegmentColours.size()] + "\"><title>" +
             xml_escape(chart.segments[s]) + ": " + label(v) + "</title></rect>\n";
      level += v;
    }
    out += "<text x=\"" + num(cx) + "\" y=\"" + num(bottom + 16) + "\" text-anchor=\"middle\">" +
           xml_escape(chart.bars[b]) + "</text>\n</g>\n";
  }
  for (size_t s = 0; s < chart.segments.size(); ++s)
    legend_entry(out, p, s, chart.segments[s], kSegmentColours[s % kSegmentColours.size()]);
  out += "</g>\n";
  height_ += kPanelHeight;
}

std::string SvgDocument::str() const {
  std::string w = std::to_string(width_), h = std::to_string(std::max(height_, 1));
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + w +
         "\" height=\"" + h + "\" viewBox=\"0 0 " + w + " " + h +
         "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n" +
         body_ + "</svg>\n";
}

}  // namespace crowdprof
