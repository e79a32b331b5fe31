#include "reports/svg_chart.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace crowdprof {

namespace {

// For series given no colour (chart_colours.h gives modes theirs): Okabe-Ito,
// its light colours darkened to 3:1 or more against white (WCAG 2.1 for
// graphics), as the page's self-check requires.
constexpr std::array<const char*, 8> kSeriesColours = {"#0072B2", "#D55E00", "#009E73", "#B8568F",
                                                       "#A66A00", "#6A3D9A", "#8C7A00", "#000000"};
// For stacked segments given no colour: Tableau 10, darkened likewise.
constexpr std::array<const char*, 10> kSegmentColours = {"#4E79A7", "#C9650A", "#E15759", "#2F8F89", "#59A14F",
                                                         "#9E8200", "#B07AA1", "#C4587E", "#9C755F", "#7F7F7F"};

constexpr int kPanelHeight = 380;
// The right margin holds the legend and the guides' labels ("p95 master 0.27 ms").
constexpr double kLeft = 80, kRight = 230, kTop = 44, kBottom = 56;

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

std::string signed_label(double value) {
  std::string text = label(value);
  if (value > 0) text.insert(text.begin(), '+');
  return text;
}

std::string attr(const char* name, const std::string& value) {
  return std::string(" ") + name + "=\"" + xml_escape(value) + "\"";
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
  bool log = false;            // lo and hi are powers of ten; ticks at 1, 2, 5 times them
  double at(double v) const {  // 0 at lo, 1 at hi
    return log ? (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo)) : (v - lo) / (hi - lo);
  }
  std::vector<double> ticks() const {
    std::vector<double> out;
    if (!log) {
      for (double v = lo; v <= hi + step * 1e-9; v += step) out.push_back(std::abs(v) < step * 1e-9 ? 0.0 : v);
      return out;
    }
    for (double decade = lo; decade <= hi * 1.0001; decade *= 10)
      for (double m : {1.0, 2.0, 5.0})
        if (decade * m <= hi * 1.0001) out.push_back(decade * m);
    return out;
  }
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

Axis log_axis_over(double lo, double hi) {
  if (!(lo > 0) || !std::isfinite(lo) || !std::isfinite(hi)) lo = 1, hi = 10;
  Axis a;
  a.log = true;
  a.lo = std::pow(10.0, std::floor(std::log10(lo)));
  a.hi = std::pow(10.0, std::ceil(std::log10(hi)));
  if (a.hi <= a.lo) a.hi = a.lo * 10;
  return a;
}

// The frame of a panel: title, plot area, axes with ticks and labels.
struct Panel {
  double top, width;
  double plot_w() const { return width - kLeft - kRight; }
  double plot_h() const { return kPanelHeight - kTop - kBottom; }
  double bottom() const { return top + kTop + plot_h(); }
  double px(const Axis& a, double x) const { return kLeft + a.at(x) * plot_w(); }
  double py(const Axis& a, double y) const { return bottom() - a.at(y) * plot_h(); }
};

// A margin label that fits `room` px at the charts' 12 px sans-serif (7.5 px
// a character, wide enough for DejaVu's): a long name loses its middle to
// an ellipsis and keeps its head and its end (a value, "0.10 ms"); the whole
// text stays in the element's tooltip.
std::string fit_label(const std::string& text, double room) {
  auto is_start = [&](size_t i) { return i >= text.size() || (static_cast<unsigned char>(text[i]) & 0xC0) != 0x80; };
  size_t chars = 0;
  for (size_t i = 0; i < text.size(); ++i) chars += is_start(i);
  const size_t fits = static_cast<size_t>(room / 7.5);
  if (chars <= fits || fits < 8) return text;
  const size_t keep_tail = (fits - 1) * 2 / 5, keep_head = fits - 1 - keep_tail;
  // Byte offsets of the keep_head-th character and of the last keep_tail.
  size_t head = 0, seen = 0;
  while (head < text.size() && (seen < keep_head || !is_start(head))) seen += is_start(head++) ? 1 : 0;
  size_t tail = text.size(), from_end = 0;
  while (tail > head && from_end < keep_tail) {
    --tail;
    if (is_start(tail)) ++from_end;
  }
  return text.substr(0, head) + "\u2026" + text.substr(tail);
}

// A chart's title at 16 px (10 px a character) within `room` px.
std::string fit_title(const std::string& text, double room) {
  return fit_label(text, room * 7.5 / 10.0);
}

void frame(std::string& out, const Panel& p, const std::string& title, const std::string& x_label,
           const std::string& y_label, const Axis& y, const Axis* x) {
  out += "<text class=\"title\" x=\"" + num(kLeft) + "\" y=\"" + num(p.top + 26) + "\" font-size=\"16\"><title>" +
         xml_escape(title) + "</title>" + xml_escape(fit_title(title, p.width - kLeft - 8)) + "</text>\n";
  for (double v : y.ticks()) {
    out += "<line x1=\"" + num(kLeft) + "\" x2=\"" + num(kLeft + p.plot_w()) + "\" y1=\"" + num(p.py(y, v)) +
           "\" y2=\"" + num(p.py(y, v)) + "\" stroke=\"#ddd\"/>\n";
    out += "<text x=\"" + num(kLeft - 6) + "\" y=\"" + num(p.py(y, v) + 4) + "\" text-anchor=\"end\">" + label(v) +
           "</text>\n";
  }
  if (x) {
    for (double v : x->ticks()) {
      if (x->log)
        out += "<line x1=\"" + num(p.px(*x, v)) + "\" x2=\"" + num(p.px(*x, v)) + "\" y1=\"" + num(p.top + kTop) +
               "\" y2=\"" + num(p.bottom()) + "\" stroke=\"#eee\"/>\n";
      // Low enough to clear the y axis's lowest label at the corner.
      out += "<text x=\"" + num(p.px(*x, v)) + "\" y=\"" + num(p.bottom() + 20) + "\" text-anchor=\"middle\">" +
             label(v) + "</text>\n";
    }
  }
  out += "<rect x=\"" + num(kLeft) + "\" y=\"" + num(p.top + kTop) + "\" width=\"" + num(p.plot_w()) + "\" height=\"" +
         num(p.plot_h()) + "\" fill=\"none\" stroke=\"#888\"/>\n";
  out += "<text x=\"" + num(kLeft + p.plot_w() / 2) + "\" y=\"" + num(p.bottom() + 40) + "\" text-anchor=\"middle\">" +
         xml_escape(x_label) + "</text>\n";
  double mid = p.top + kTop + p.plot_h() / 2;
  out += "<text x=\"20\" y=\"" + num(mid) + "\" text-anchor=\"middle\" transform=\"rotate(-90 20 " + num(mid) + ")\">" +
         xml_escape(y_label) + "</text>\n";
}

// Margin labels one under another: 12 px text with its descent, and a pixel
// or two between.
constexpr double kMarginStep = 16;

double legend_baseline(const Panel& p, size_t row) {
  return p.top + kTop + 8 + kMarginStep * static_cast<double>(row);
}

void legend_entry(std::string& out, const Panel& p, size_t index, const std::string& name, const std::string& colour) {
  double x = kLeft + p.plot_w() + 16, y = legend_baseline(p, index);
  out += "<g class=\"legend\"" + attr("data-for", name) + "><rect x=\"" + num(x) + "\" y=\"" + num(y - 9) +
         "\" width=\"14\" height=\"10\" fill=\"" + colour + "\"/><text x=\"" + num(x + 20) + "\" y=\"" + num(y) +
         "\"><title>" + xml_escape(name) + "</title>" + xml_escape(fit_label(name, kRight - 16 - 20 - 6)) +
         "</text></g>\n";
}

// Baselines for margin labels wanted at `wanted`: each at least kMarginStep
// below the one above it and within [top, bottom], as near its wish as that
// allows (a sweep down from the top, then one up from the bottom).
std::vector<double> spread_labels(const std::vector<double>& wanted, double top, double bottom) {
  std::vector<size_t> order(wanted.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return wanted[a] < wanted[b]; });
  std::vector<double> at(wanted.size());
  double previous = top - kMarginStep;
  for (size_t i : order) previous = at[i] = std::max(wanted[i], previous + kMarginStep);
  double next = std::max(bottom, top + kMarginStep * static_cast<double>(order.size())) + kMarginStep;
  for (auto i = order.rbegin(); i != order.rend(); ++i) next = at[*i] = std::min(at[*i], next - kMarginStep);
  return at;
}

std::string chart_open(const char* kind, const std::string& id, size_t series) {
  return std::string("<g class=\"chart ") + kind + "\"" + (id.empty() ? "" : attr("data-chart", id)) +
         " data-series=\"" + std::to_string(series) + "\">\n";
}

bool drawable(double v) {
  return std::isfinite(v) && v > 0;
}

}  // namespace

std::string xml_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        // Control characters are not allowed in XML 1.0 at all.
        if (static_cast<unsigned char>(c) >= 0x20 || c == '\t' || c == '\n') out += c;
    }
  }
  return out;
}

void SvgDocument::add(const LineChart& chart) {
  Panel p{static_cast<double>(height_), static_cast<double>(width_)};
  auto usable = [&](double x, double y) { return std::isfinite(x) && std::isfinite(y) && (!chart.log_x || x > 0); };
  double xlo = INFINITY, xhi = -INFINITY, yhi = -INFINITY;
  for (const LineSeries& s : chart.series)
    for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!usable(s.x[i], s.y[i])) continue;
      xlo = std::min(xlo, s.x[i]), xhi = std::max(xhi, s.x[i]), yhi = std::max(yhi, s.y[i]);
    }
  for (const Guide& g : chart.guides)
    if (g.fit && std::isfinite(g.y)) yhi = std::max(yhi, g.y);
  Axis x = chart.log_x ? log_axis_over(xlo, xhi) : axis_over(xlo, xhi, false), y = axis_over(0, yhi, true);
  std::string& out = body_;
  out += chart_open("line-chart", chart.id, chart.series.size());
  frame(out, p, chart.title, chart.x_label, chart.y_label, y, &x);
  // The legend first in the margin: the series, then the keys of guides
  // labelled by kind.
  size_t legend_rows = 0;
  for (size_t k = 0; k < chart.series.size(); ++k) {
    const LineSeries& s = chart.series[k];
    legend_entry(out, p, legend_rows++, s.name,
                 s.colour.empty() ? kSeriesColours[k % kSeriesColours.size()] : s.colour);
  }
  for (const LegendKey& key : chart.keys) {
    double lx = kLeft + p.plot_w() + 16, ly = legend_baseline(p, legend_rows++);
    out += "<g class=\"legend\"" + attr("data-for", key.kind) + "><line x1=\"" + num(lx) + "\" x2=\"" + num(lx + 14) +
           "\" y1=\"" + num(ly - 4) + "\" y2=\"" + num(ly - 4) + "\" stroke=\"#444\" stroke-width=\"1.5\"" +
           attr("stroke-dasharray", key.dash) + "/><text x=\"" + num(lx + 20) + "\" y=\"" + num(ly) + "\">" +
           xml_escape(key.text) + "</text></g>\n";
  }
  // Then each guide's label (or, off the scale, its note) as near its line
  // as the labels above and below it allow, joined to the line's end.
  std::vector<size_t> labelled;
  std::vector<double> wanted;
  for (size_t i = 0; i < chart.guides.size(); ++i) {
    const Guide& g = chart.guides[i];
    if (!std::isfinite(g.y) || g.label.empty()) continue;
    labelled.push_back(i);
    wanted.push_back(g.y > y.hi ? 0.0 : p.py(y, g.y) + 4);
  }
  // Within the plot's height, so that no stroke joining a label to its line
  // runs through the x axis's last label.
  std::vector<double> placed = spread_labels(wanted, legend_baseline(p, legend_rows), p.bottom() + 4);
  std::vector<double> label_y(chart.guides.size(), 0);
  for (size_t j = 0; j < labelled.size(); ++j) label_y[labelled[j]] = placed[j];
  const double right = kLeft + p.plot_w();
  for (size_t i = 0; i < chart.guides.size(); ++i) {
    const Guide& g = chart.guides[i];
    if (!std::isfinite(g.y)) continue;
    std::string tip = "<title>" + xml_escape(g.label) + "</title>";
    if (g.y > y.hi) {  // off the scale: said in the margin, no line
      if (!g.label.empty())
        out += "<text class=\"" + xml_escape(g.kind) + " above\"" + attr("data-value", label(g.y)) + " x=\"" +
               num(right + 12) + "\" y=\"" + num(label_y[i]) + "\" fill=\"" + g.colour + "\">" + tip +
               xml_escape(fit_label("\u2191 " + g.label + " (above)", kRight - 12 - 6)) + "</text>\n";
      continue;
    }
    double gy = p.py(y, g.y);
    out += "<g class=\"" + xml_escape(g.kind) + "\"" + attr("data-value", label(g.y)) + attr("data-guide", g.kind) +
           "><line x1=\"" + num(kLeft) + "\" x2=\"" + num(right) + "\" y1=\"" + num(gy) + "\" y2=\"" + num(gy) +
           "\" stroke=\"" + g.colour + "\" stroke-dasharray=\"" + g.dash + "\">" + tip + "</line>";
    if (!g.label.empty())
      out += "<line x1=\"" + num(right) + "\" x2=\"" + num(right + 8) + "\" y1=\"" + num(gy) + "\" y2=\"" +
             num(label_y[i] - 4) + "\" stroke=\"" + g.colour + "\"/><text x=\"" + num(right + 12) + "\" y=\"" +
             num(label_y[i]) + "\" fill=\"" + g.colour + "\">" + tip + xml_escape(fit_label(g.label, kRight - 12 - 6)) +
             "</text>";
    out += "</g>\n";
  }
  for (size_t k = 0; k < chart.series.size(); ++k) {
    const LineSeries& s = chart.series[k];
    std::string colour = s.colour.empty() ? kSeriesColours[k % kSeriesColours.size()] : s.colour;
    std::string points, dots;
    size_t drawn = 0;
    for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!usable(s.x[i], s.y[i])) continue;
      ++drawn;
      std::string at = num(p.px(x, s.x[i])) + "," + num(p.py(y, s.y[i]));
      points += (points.empty() ? "" : " ") + at;
      if (chart.markers || !s.joined)
        dots += "<circle cx=\"" + num(p.px(x, s.x[i])) + "\" cy=\"" + num(p.py(y, s.y[i])) + "\" r=\"" +
                (s.joined ? "3" : "4") + "\"/>";
    }
    out +=
        "<g class=\"series\"" + attr("data-name", s.name) + " data-geometry=\"" + (s.joined ? "line" : "dots") +
        "\" data-points=\"" + std::to_string(drawn) + "\" fill=\"" + colour + "\">\n" +
        (s.joined ? "<polyline points=\"" + points + "\" fill=\"none\" stroke=\"" + colour + "\" stroke-width=\"1.5\"/>"
                  : std::string()) +
        dots + "\n</g>\n";
  }
  out += "</g>\n";
  height_ += kPanelHeight;
}

void SvgDocument::add(const StackedBars& chart) {
  Panel p{static_cast<double>(height_), static_cast<double>(width_)};
  auto colour = [&](size_t s) {
    return s < chart.colours.size() ? chart.colours[s] : std::string(kSegmentColours[s % kSegmentColours.size()]);
  };
  double top = 0;
  for (const auto& bar : chart.values) {
    double sum = 0;
    for (double v : bar) sum += drawable(v) ? v : 0;
    top = std::max(top, sum);
  }
  Axis y = axis_over(0, top, true);
  std::string& out = body_;
  out += chart_open("stacked-bars", chart.id, chart.bars.size());
  frame(out, p, chart.title, "", chart.y_label, y, nullptr);
  double slot = chart.bars.empty() ? p.plot_w() : p.plot_w() / static_cast<double>(chart.bars.size());
  double bar_w = std::min(120.0, slot * 0.6);
  for (size_t b = 0; b < chart.bars.size(); ++b) {
    double cx = kLeft + slot * (static_cast<double>(b) + 0.5);
    std::string rects;
    size_t segments = 0;
    double level = 0;
    for (size_t s = 0; b < chart.values.size() && s < chart.values[b].size() && s < chart.segments.size(); ++s) {
      double v = chart.values[b][s];
      if (!drawable(v)) continue;
      double y0 = p.py(y, level), y1 = p.py(y, level + v);
      rects += "<rect x=\"" + num(cx - bar_w / 2) + "\" y=\"" + num(y1) + "\" width=\"" + num(bar_w) + "\" height=\"" +
               num(y0 - y1) + "\" fill=\"" + colour(s) + "\"><title>" + xml_escape(chart.segments[s]) + ": " +
               label(v) + "</title></rect>\n";
      level += v;
      ++segments;
    }
    out += "<g class=\"bar\"" + attr("data-name", chart.bars[b]) + " data-segments=\"" + std::to_string(segments) +
           "\">\n" + rects + "<text x=\"" + num(cx) + "\" y=\"" + num(p.bottom() + 16) +
           "\" text-anchor=\"middle\"><title>" + xml_escape(chart.bars[b]) + "</title>" +
           xml_escape(fit_label(chart.bars[b], slot - 8)) + "</text>\n</g>\n";
  }
  for (size_t s = 0; s < chart.segments.size(); ++s) legend_entry(out, p, s, chart.segments[s], colour(s));
  out += "</g>\n";
  height_ += kPanelHeight;
}

void SvgDocument::add(const StackedArea& chart) {
  Panel p{static_cast<double>(height_), static_cast<double>(width_)};
  size_t n = chart.x.size();
  auto value = [](const AreaLayer& layer, size_t i) {
    return i < layer.y.size() && drawable(layer.y[i]) ? layer.y[i] : 0.0;
  };
  double top = 0, xlo = INFINITY, xhi = -INFINITY;
  for (size_t i = 0; i < n; ++i) {
    double sum = 0;
    for (const AreaLayer& layer : chart.layers) sum += value(layer, i);
    top = std::max(top, sum);
    if (std::isfinite(chart.x[i])) xlo = std::min(xlo, chart.x[i]), xhi = std::max(xhi, chart.x[i]);
  }
  Axis x = axis_over(xlo, xhi, false), y = axis_over(0, top, true);
  std::string& out = body_;
  out += chart_open("stacked-area", chart.id, chart.layers.size());
  frame(out, p, chart.title, chart.x_label, chart.y_label, y, &x);
  std::vector<double> level(n, 0.0);
  for (size_t k = 0; k < chart.layers.size(); ++k) {
    const AreaLayer& layer = chart.layers[k];
    // The upper edge left to right, then the layer below right to left: as
    // many points below as above, so a reader can count the frames.
    std::string upper, lower;
    size_t drawn = 0;
    for (size_t i = 0; i < n; ++i) {
      if (!std::isfinite(chart.x[i])) continue;
      ++drawn;
      if (!upper.empty()) upper += ' ';
      upper += num(p.px(x, chart.x[i])) + "," + num(p.py(y, level[i] + value(layer, i)));
    }
    for (size_t i = n; i-- > 0;) {
      if (!std::isfinite(chart.x[i])) continue;
      lower += ' ';
      lower += num(p.px(x, chart.x[i])) + "," + num(p.py(y, level[i]));
      level[i] += value(layer, i);
    }
    out += "<g class=\"series\"" + attr("data-name", layer.name) + " data-geometry=\"area\" data-points=\"" +
           std::to_string(drawn) + "\">\n<polygon points=\"" + upper + lower + "\" fill=\"" + layer.colour +
           "\" stroke=\"" + layer.colour + "\" stroke-width=\"0.5\"><title>" + xml_escape(layer.name) +
           "</title></polygon>\n</g>\n";
  }
  // Legend top to bottom as the layers are stacked: the top layer first.
  for (size_t k = chart.layers.size(); k-- > 0;)
    legend_entry(out, p, chart.layers.size() - 1 - k, chart.layers[k].name, chart.layers[k].colour);
  out += "</g>\n";
  height_ += kPanelHeight;
}

void SvgDocument::add(const VerdictChart& chart) {
  Panel p{static_cast<double>(height_), static_cast<double>(width_)};
  // Changes in percent, every band and every row's change in view.
  double lo = -10, hi = 20;
  for (const VerdictRow& row : chart.rows) {
    if (std::isfinite(row.change)) lo = std::min(lo, row.change * 100), hi = std::max(hi, row.change * 100);
    if (std::isfinite(row.allowed)) lo = std::min(lo, -row.allowed * 100), hi = std::max(hi, row.allowed * 200);
  }
  Axis x = axis_over(lo, hi, false);
  std::string& out = body_;
  out += chart_open("verdicts", chart.id, chart.rows.size());
  out += "<text class=\"title\" x=\"" + num(kLeft) + "\" y=\"" + num(p.top + 26) + "\" font-size=\"16\"><title>" +
         xml_escape(chart.title) + "</title>" + xml_escape(fit_title(chart.title, p.width - kLeft - 8)) + "</text>\n";
  double row_h = std::min(40.0, p.plot_h() / std::max<double>(1.0, static_cast<double>(chart.rows.size())));
  double plot_top = p.top + kTop, plot_bottom = plot_top + row_h * static_cast<double>(chart.rows.size());
  auto at = [&](double percent) { return kLeft + 60 + x.at(percent) * (p.plot_w() - 60); };
  for (size_t r = 0; r < chart.rows.size(); ++r) {
    double allowed = std::isfinite(chart.rows[r].allowed) ? chart.rows[r].allowed * 100 : 0.0;
    out += "<rect class=\"tolerance\" x=\"" + num(at(0)) + "\" y=\"" +
           num(plot_top + row_h * static_cast<double>(r) + 2) + "\" width=\"" + num(at(allowed) - at(0)) +
           "\" height=\"" + num(row_h - 4) + "\" fill=\"#dff0d8\"><title>allowed: up to " + label(allowed) +
           "% slower</title></rect>\n";
  }
  for (double v : x.ticks()) {
    out += "<line x1=\"" + num(at(v)) + "\" x2=\"" + num(at(v)) + "\" y1=\"" + num(plot_top) + "\" y2=\"" +
           num(plot_bottom) + "\" stroke=\"" + (v == 0 ? "#888" : "#e4e4e4") + "\"/>\n";
    out += "<text x=\"" + num(at(v)) + "\" y=\"" + num(plot_bottom + 16) + "\" text-anchor=\"middle\">" +
           signed_label(v) + "%</text>\n";
  }
  out += "<text x=\"" + num(at(x.lo) + (at(x.hi) - at(x.lo)) / 2) + "\" y=\"" + num(plot_bottom + 40) +
         "\" text-anchor=\"middle\">change of the median against " + chart.against +
         " (%; the green band is the tolerance)</text>\n";
  for (size_t r = 0; r < chart.rows.size(); ++r) {
    const VerdictRow& row = chart.rows[r];
    double cy = plot_top + row_h * (static_cast<double>(r) + 0.5);
    double change = std::isfinite(row.change) ? std::clamp(row.change * 100, x.lo, x.hi) : x.hi;
    out += "<g class=\"series\"" + attr("data-name", row.name) + attr("data-verdict", row.verdict) +
           " data-geometry=\"dots\" data-points=\"1\">\n<text x=\"" + num(kLeft + 52) + "\" y=\"" + num(cy + 4) +
           "\" text-anchor=\"end\">" + xml_escape(row.name) + "</text><line x1=\"" + num(at(0)) + "\" x2=\"" +
           num(at(change)) + "\" y1=\"" + num(cy) + "\" y2=\"" + num(cy) + "\" stroke=\"" + row.colour +
           "\" stroke-width=\"3\"/><circle cx=\"" + num(at(change)) + "\" cy=\"" + num(cy) + "\" r=\"6\" fill=\"" +
           row.colour + "\"><title>" + xml_escape(row.detail) + "</title></circle><text x=\"" +
           num(kLeft + p.plot_w() + 16) + "\" y=\"" + num(cy + 4) + "\" fill=\"" + row.colour + "\">" +
           xml_escape(row.verdict) + "</text>\n</g>\n";
  }
  out += "</g>\n";
  height_ += static_cast<int>(plot_bottom - p.top + kBottom);
}

// HTML puts an inline <svg> in the SVG namespace by itself; a file needs xmlns.
static std::string svg_element(int width, int height, const std::string& body, const char* xmlns) {
  std::string w = std::to_string(width), h = std::to_string(std::max(height, 1));
  return "<svg" + std::string(xmlns) + " width=\"" + w + "\" height=\"" + h + "\" viewBox=\"0 0 " + w + " " + h +
         "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n" +
         body + "</svg>\n";
}

std::string SvgDocument::inline_svg() const {
  return svg_element(width_, height_, body_, "");
}

std::string SvgDocument::str() const {
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n" +
         svg_element(width_, height_, body_, " xmlns=\"http://www.w3.org/2000/svg\"");
}

}  // namespace crowdprof
