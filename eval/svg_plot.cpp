// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/eval/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace lmk {

namespace {

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f", v);
  return text;
}

std::string tick_label(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g", v);
  return text;
}

// The plotting area inside the margins, and the mapping of data into it.
struct Frame {
  double left = 56, right, top = 28, bottom;
  double x0, x1, y0, y1;
  bool log_x = false;
  double fx(double x) const {
    const double t = log_x ? (std::log10(x) - std::log10(x0)) / (std::log10(x1) - std::log10(x0))
                           : (x - x0) / (x1 - x0);
    return left + t * (right - left);
  }
  double fy(double y) const { return bottom - (y - y0) / (y1 - y0) * (bottom - top); }
};

std::string open_svg(int width, int height, const std::string& title) {
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(width) +
         "\" height=\"" + std::to_string(height) + "\" viewBox=\"0 0 " + std::to_string(width) +
         " " + std::to_string(height) + "\" role=\"img\" aria-label=\"" + escape_html(title) +
         "\" font-family=\"sans-serif\" font-size=\"11\">\n<title>" + escape_html(title) +
         "</title>\n<text x=\"" + std::to_string(width / 2) +
         "\" y=\"16\" text-anchor=\"middle\" font-size=\"13\">" + escape_html(title) + "</text>\n";
}

// Axes, five ticks on each, and the axis labels.
std::string axes(const Frame& f, const std::string& x_label, const std::string& y_label,
                 int height) {
  std::string s = "<g stroke=\"#444\" fill=\"none\"><path d=\"M" + number(f.left) + " " +
                  number(f.top) + " V" + number(f.bottom) + " H" + number(f.right) + "\"/></g>\n";
  for (int i = 0; i <= 4; ++i) {
    const double xv =
        f.log_x ? std::pow(10.0, std::log10(f.x0) + i * (std::log10(f.x1) - std::log10(f.x0)) / 4)
                : f.x0 + i * (f.x1 - f.x0) / 4;
    const double yv = f.y0 + i * (f.y1 - f.y0) / 4;
    s += "<text x=\"" + number(f.fx(xv)) + "\" y=\"" + number(f.bottom + 14) +
         "\" text-anchor=\"middle\">" + tick_label(xv) + "</text>\n";
    s += "<text x=\"" + number(f.left - 6) + "\" y=\"" + number(f.fy(yv) + 4) +
         "\" text-anchor=\"end\">" + tick_label(yv) + "</text>\n";
    s += "<path d=\"M" + number(f.left) + " " + number(f.fy(yv)) + " H" + number(f.right) +
         "\" stroke=\"#ddd\"/>\n";
  }
  s += "<text x=\"" + number(0.5 * (f.left + f.right)) + "\" y=\"" + std::to_string(height - 4) +
       "\" text-anchor=\"middle\">" + escape_html(x_label) + "</text>\n";
  if (!y_label.empty()) {
    s += "<text transform=\"translate(12 " + number(0.5 * (f.top + f.bottom)) +
         ") rotate(-90)\" text-anchor=\"middle\">" + escape_html(y_label) + "</text>\n";
  }
  return s;
}

}  // namespace

std::string escape_html(const std::string& text) {
  std::string out;
  for (const char c : text) {
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
      default:
        out += c;
    }
  }
  return out;
}

std::string render_svg(const LinePlot& plot, int width, int height) {
  Frame f;
  f.right = width - 150;  // room for the legend
  f.bottom = height - 34;
  f.x0 = INFINITY, f.x1 = -INFINITY;
  for (const PlotSeries& s : plot.series) {
    for (const auto& [x, y] : s.points) f.x0 = std::min(f.x0, x), f.x1 = std::max(f.x1, x);
  }
  if (!(f.x1 > f.x0)) f.x0 = 0.0, f.x1 = 1.0;
  f.y0 = plot.y_min, f.y1 = plot.y_max;
  std::string s = open_svg(width, height, plot.title) + axes(f, plot.x_label, plot.y_label, height);
  if (std::isfinite(plot.marker_x)) {
    s += "<path d=\"M" + number(f.fx(plot.marker_x)) + " " + number(f.top) + " V" +
         number(f.bottom) + "\" stroke=\"#999\" stroke-dasharray=\"2 3\"/>\n";
  }
  for (std::size_t k = 0; k < plot.series.size(); ++k) {
    const PlotSeries& series = plot.series[k];
    std::string d;
    bool pen_down = false;
    for (const auto& [x, y] : series.points) {
      if (!std::isfinite(y)) {
        pen_down = false;
        continue;
      }
      d += (pen_down ? " L" : " M") + number(f.fx(x)) + " " + number(f.fy(y));
      pen_down = true;
    }
    s += "<path d=\"" + d + "\" fill=\"none\" stroke=\"" + series.colour + "\" stroke-width=\"2\"" +
         (series.dashed ? " stroke-dasharray=\"6 3\"" : "") + "/>\n";
    const double ly = f.top + 14.0 * static_cast<double>(k);
    s += "<path d=\"M" + number(f.right + 10) + " " + number(ly) + " h20\" stroke=\"" +
         series.colour + "\" stroke-width=\"2\"" +
         (series.dashed ? " stroke-dasharray=\"6 3\"" : "") + "/>\n";
    s += "<text x=\"" + number(f.right + 34) + "\" y=\"" + number(ly + 4) + "\">" +
         escape_html(series.name) + "</text>\n";
  }
  return s + "</svg>\n";
}

std::string render_svg(const Histogram& h, int width, int height) {
  Frame f;
  f.right = width - 20;
  f.bottom = height - 34;
  f.log_x = h.log_x;
  std::vector<double> values;
  for (double v : h.values) {
    if (std::isfinite(v) && (!h.log_x || v > 0.0)) values.push_back(v);
  }
  if (values.empty()) values.push_back(h.log_x ? 1.0 : 0.0);
  f.x0 = *std::min_element(values.begin(), values.end());
  f.x1 = *std::max_element(values.begin(), values.end());
  if (!(f.x1 > f.x0)) f.x1 = h.log_x ? f.x0 * 2.0 : f.x0 + 1.0;
  const int bins = std::max(1, h.bins);
  std::vector<int> counts(static_cast<std::size_t>(bins), 0);
  for (double v : values) {
    const double t =
        h.log_x ? (std::log10(v) - std::log10(f.x0)) / (std::log10(f.x1) - std::log10(f.x0))
                : (v - f.x0) / (f.x1 - f.x0);
    ++counts[static_cast<std::size_t>(std::clamp(static_cast<int>(t * bins), 0, bins - 1))];
  }
  f.y0 = 0.0;
  f.y1 = std::max(1, *std::max_element(counts.begin(), counts.end()));
  std::string s = open_svg(width, height, h.title) + axes(f, h.x_label, "count", height);
  const double bar = (f.right - f.left) / bins;
  for (int i = 0; i < bins; ++i) {
    const double top = f.fy(counts[static_cast<std::size_t>(i)]);
    s += "<rect x=\"" + number(f.left + i * bar + 1) + "\" y=\"" + number(top) + "\" width=\"" +
         number(bar - 2) + "\" height=\"" + number(f.bottom - top) + "\" fill=\"#4477aa\"/>\n";
  }
  return s + "</svg>\n";
}

}  // namespace lmk
