// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Small self-contained SVG charts for reports: line plots and histograms, no script, no external
// resource, so a report opens anywhere.

#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace lmk {

struct PlotSeries {
  std::string name;
  std::vector<std::pair<double, double>> points;  ///< (x, y); y NaN leaves a gap
  std::string colour;                             ///< any SVG colour
  bool dashed = false;
};

struct LinePlot {
  std::string title, x_label, y_label;
  std::vector<PlotSeries> series;
  double y_min = 0.0, y_max = 1.0;
  /// Draws a vertical marker at this x (e.g. the threshold in use); NaN for none.
  double marker_x = std::numeric_limits<double>::quiet_NaN();
};

/// An <svg> element of the plot with a legend.
std::string render_svg(const LinePlot& plot, int width = 560, int height = 320);

struct Histogram {
  std::string title, x_label;
  std::vector<double> values;
  int bins = 20;
  bool log_x = false;  ///< logarithmic bins (times spanning orders of magnitude)
};

std::string render_svg(const Histogram& histogram, int width = 560, int height = 280);

/// Escapes &, <, >, " for HTML and SVG text.
std::string escape_html(const std::string& text);

}  // namespace lmk
