// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/eval/evaluation_report.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "lmk/eval/evaluation_table.h"
#include "lmk/eval/failure_pictures.h"
#include "lmk/eval/internal/evaluation_document_json.h"
#include "lmk/eval/internal/explanation_json.h"
#include "lmk/eval/internal/rows_json.h"
#include "lmk/eval/risk_coverage.h"
#include "lmk/eval/svg_plot.h"
#include "lmk/geometry/atomic_file.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/version.h"

namespace lmk {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const char* const kColours[] = {"#4477aa", "#ee6677", "#228833", "#ccbb44", "#66ccee", "#aa3377"};

const std::string kAssumptionsNote =
    "Assumptions: 1, all pairs; 2, in-context pairs; 3, in-context pairs, best match only. Errors "
    "are medians over true positives; '-' is undefined (no output, or nothing to find).";

// The assumption the curves show: 1 when every pair was searched, else 2.
int curve_assumption(const Evaluation& e) { return e.settings.in_context_only ? 2 : 1; }

// How the evaluation's metric shows its errors.
const ErrorDisplay& shown_errors(const Evaluation& e) {
  return find_error_metric(e.settings.find.selection.metric).display;
}

// One line per pair: what was there, what was found, how good the best match was, how long.
TextTable pair_table(const Evaluation& e) {
  const double threshold = *e.settings.find.selection.threshold;
  const ErrorDisplay& shown = shown_errors(e);
  TextTable t;
  t.header = {
      "scene",  "landmark", "in context", "truth", "found", "correct", "best error " + shown.label,
      "seconds"};
  t.numeric = {false, false, false, true, true, true, true, true};
  for (const PairResult& p : e.pairs) {
    const PairInput in = matches_within(p, threshold, e.settings.find.selection.min_confidence);
    const Counts c = count_all_matches(in, e.settings.tolerance);
    std::optional<double> best;
    if (!p.found.empty()) best = p.found.front().error;
    t.rows.push_back({p.scene, p.landmark, p.in_context ? "yes" : "no",
                      std::to_string(p.truth.size()), std::to_string(in.found.size()),
                      std::to_string(c.tp), format_optional(best, 2, shown.scale),
                      format_optional(p.seconds, 3)});
  }
  return t;
}

// A TextTable as an HTML table.
std::string html_table(const TextTable& t) {
  std::string s = "<table>\n<thead><tr>";
  for (std::size_t i = 0; i < t.header.size(); ++i) {
    const bool num = i < t.numeric.size() && t.numeric[i];
    s += std::string("<th") + (num ? " class=\"num\"" : "") + ">" + escape_html(t.header[i]) +
         "</th>";
  }
  s += "</tr></thead>\n<tbody>\n";
  for (const auto& row : t.rows) {
    s += "<tr>";
    for (std::size_t i = 0; i < row.size(); ++i) {
      const bool num = i < t.numeric.size() && t.numeric[i];
      s += std::string("<td") + (num ? " class=\"num\"" : "") + ">" + escape_html(row[i]) + "</td>";
    }
    s += "</tr>\n";
  }
  return s + "</tbody>\n</table>\n";
}

std::string threshold_plot(const Evaluation& e) {
  LinePlot plot;
  plot.title = "Precision (solid) and recall (dashed) against the threshold, assumption " +
               std::to_string(curve_assumption(e));
  const ErrorDisplay& shown = shown_errors(e);
  const double scale = shown.scale;  // plotted as the metric shows its errors
  plot.x_label = "error threshold (" + shown.label + ")";
  plot.marker_x = scale * *e.settings.find.selection.threshold;
  std::size_t k = 0;
  for (const std::string& setting : evaluation_settings(e)) {
    const std::string colour = kColours[k++ % (sizeof(kColours) / sizeof(kColours[0]))];
    PlotSeries precision{setting + " P", {}, colour, false};
    PlotSeries recall{setting + " R", {}, colour, true};
    for (const ThresholdPoint& p : threshold_curve(e, setting, curve_assumption(e))) {
      precision.points.push_back({scale * p.threshold, p.precision.value_or(NAN)});
      recall.points.push_back({scale * p.threshold, p.recall.value_or(NAN)});
    }
    plot.series.push_back(precision);
    plot.series.push_back(recall);
  }
  return render_svg(plot, 640, 340);
}

std::string times_plot(const Evaluation& e) {
  Histogram h;
  h.title = "Seconds per search (" + std::to_string(e.pairs.size()) + " searches, 1 thread each)";
  h.x_label = "seconds (log scale)";
  h.log_x = true;
  for (const PairResult& p : e.pairs) h.values.push_back(p.seconds);
  return render_svg(h, 640, 280);
}

constexpr const char* kRangeNote =
    "The same counts split by the distance from the sensor to each ground-truth instance (true "
    "positives, false negatives) or to each false match, in 0.5 m bins; assumptions 1 and 2.";

constexpr const char* kHiddenNote =
    "Recall by the fraction of each ground-truth instance that the scene's sensor does not see, in "
    "20% bins; false matches hide nothing and count in no row; assumptions 1 and 2.";

constexpr const char* kConfidenceNote =
    "What the confidence is worth (docs/evaluation.md, \"Confidence\"): as the cut falls, the "
    "share of in-context pairs whose best match is answered against the precision of those "
    "answers, at the reported cuts and at the lowest cuts that keep a precision of 0.95 and 0.98; "
    "then by range and by landmark size at the evaluation's cut.";

// The report's tables, each computed once for the JSON, the Markdown and the HTML.
struct ReportTables {
  std::vector<EvaluationRow> rows, by_range;
  std::vector<EvaluationRow> by_hidden;     ///< empty when the dataset records no hidden fraction
  std::optional<FailurePictures> failures;  ///< when the dataset's directory was given
  const std::vector<ExplainedCase>* explained = nullptr;  ///< with lmk eval --explain
};

constexpr const char* kExplainNote =
    "Each missed instance and each false match in one cause, from the candidates the search "
    "kept, turned down or suppressed within the protocol's tolerance of the truth (lmk eval "
    "--explain; docs/evaluation.md). 'at truth' is the median metric value at the true poses of "
    "the misses, aligned and polished from the truth as a candidate there would be; 'wrong "
    "winner' the median of the wrong matches their pairs reported, 'its confidence' the median "
    "confidence of every wrong match (misses' winners and false matches).";

// One line per case.
TextTable case_table(const std::vector<ExplainedCase>& cases, const std::string& metric) {
  TextTable t;
  t.header = {"scene",   "landmark", "kind",         "cause",
              "range m", "at truth", "wrong winner", "its confidence"};
  t.numeric = {false, false, false, false, true, true, true, true};
  const auto error = [&](const std::optional<double>& v) {
    return v ? format_error(*v, metric) : std::string("-");
  };
  for (const ExplainedCase& c : cases) {
    t.rows.push_back({c.scene, c.landmark, c.missed ? "missed" : "false match", to_string(c.cause),
                      format_optional(c.range, 2), error(c.truth_error), error(c.winner_error),
                      format_optional(c.winner_confidence, 2)});
  }
  return t;
}

// What the failure pictures hold beyond the limit, in words.
std::string failures_summary(const FailurePictures& f) {
  return std::to_string(f.pairs_with_failures) +
         " pairs with a missed instance or a false match (matches below the threshold); " +
         std::to_string(f.pictures.size()) + " pictured" +
         (f.unpictured > 0 ? ", " + std::to_string(f.unpictured) + " not (beyond the limit)" : "") +
         ".";
}

// One section of the report, shown alike in Markdown and HTML: its paragraphs, its tables (each
// under a subtitle, or none), then what one format alone shows (the plots, the pictures). A new
// report adds a section here and reaches both files.
struct ReportSection {
  using Tables = std::vector<std::pair<std::string, TextTable>>;  ///< subtitle ("": none), table
  ReportSection(std::string title, std::vector<std::string> paragraphs, Tables tables = {},
                std::string html_extra = "")
      : title(std::move(title)),
        paragraphs(std::move(paragraphs)),
        tables(std::move(tables)),
        html_extra(std::move(html_extra)) {}

  std::string title;
  std::vector<std::string> paragraphs;
  Tables tables;
  std::string html_extra, markdown_extra;
};

ReportSection failures_section(const FailurePictures& f) {
  ReportSection s("Failures", {failures_summary(f)});
  for (const FailurePicture& p : f.pictures) s.markdown_extra += "- " + p.caption + "\n";
  s.html_extra =
      "<p>Depth images (near bright, far dark, no return black) with the true boxes in green "
      "(dashed: ignored, hardly seen), correct matches in blue and false matches in red.</p>\n";
  for (const FailurePicture& p : f.pictures)
    s.html_extra += "<figure>\n" + p.svg + "\n<figcaption>" + escape_html(p.caption) +
                    "</figcaption>\n</figure>\n";
  return s;
}

std::vector<ReportSection> report_sections(const Evaluation& e, const ReportTables& t) {
  std::vector<ReportSection> sections;
  sections.push_back(
      {"Precision and recall", {kAssumptionsNote}, {{"", evaluation_table(t.rows)}}});
  sections.push_back({"By range", {kRangeNote}, {{"", evaluation_table(t.by_range)}}});
  if (!t.by_hidden.empty())
    sections.push_back(
        {"By hidden fraction", {kHiddenNote}, {{"", evaluation_table(t.by_hidden)}}});
  sections.push_back({"Confidence",
                      {kConfidenceNote, confidence_summary(e)},
                      {{"", risk_coverage_table(e, true)}}});
  sections.push_back(
      {"Plots",
       {},
       {},
       "<figure>\n" + threshold_plot(e) + "</figure>\n<figure>\n" + times_plot(e) + "</figure>\n"});
  if (t.explained) {
    const std::string& metric = e.settings.find.selection.metric;
    sections.push_back({"Why",
                        {kExplainNote},
                        {{"", cause_table(cause_rows(*t.explained), metric)},
                         {"By range", cause_table(cause_rows(*t.explained, 0.5), metric)},
                         {"Every case", case_table(*t.explained, metric)}}});
  }
  if (t.failures) sections.push_back(failures_section(*t.failures));
  sections.push_back({"Pairs", {}, {{"", pair_table(e)}}});
  return sections;
}

std::string markdown(const Evaluation& e, const std::vector<ReportSection>& sections) {
  std::string s = "# lmk evaluation: " + e.dataset + "\n\n" + evaluation_header(e) + ".\n\nlmk " +
                  kVersion + ", dataset fingerprint " + e.fingerprint + ", run " +
                  format_optional(e.seconds, 1) + " s.\n";
  for (const ReportSection& section : sections) {
    if (section.paragraphs.empty() && section.tables.empty() && section.markdown_extra.empty())
      continue;  // the plots: HTML only
    s += "\n## " + section.title + "\n";
    for (const std::string& p : section.paragraphs)
      s += "\n" + p + (!p.empty() && p.back() == '\n' ? "" : "\n");
    for (const auto& [subtitle, table] : section.tables)
      s += (subtitle.empty() ? "\n" : "\n### " + subtitle + "\n\n") + table.markdown();
    if (!section.markdown_extra.empty()) s += "\n" + section.markdown_extra;
  }
  return s;
}

std::string html(const Evaluation& e, const std::vector<ReportSection>& sections) {
  std::string s =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>lmk "
      "evaluation: " +
      escape_html(e.dataset) +
      "</title>\n<style>\nbody{font-family:sans-serif;margin:2em;max-width:70em}\n"
      "table{border-collapse:collapse;margin:1em 0}\n"
      "th,td{border:1px solid #ccc;padding:2px 8px}\n.num{text-align:right}\n"
      "th{background:#f0f0f0}\n</style>\n</head>\n<body>\n<h1>lmk evaluation: " +
      escape_html(e.dataset) + "</h1>\n<p>" + escape_html(evaluation_header(e)) + ".</p>\n<p>lmk " +
      kVersion + ", dataset fingerprint <code>" + e.fingerprint + "</code>, run " +
      format_optional(e.seconds, 1) + " s.</p>\n";
  for (const ReportSection& section : sections) {
    s += "<h2>" + escape_html(section.title) + "</h2>\n";
    for (const std::string& p : section.paragraphs) s += "<p>" + escape_html(p) + "</p>\n";
    for (const auto& [subtitle, table] : section.tables)
      s += (subtitle.empty() ? "" : "<h3>" + escape_html(subtitle) + "</h3>\n") + html_table(table);
    s += section.html_extra;
  }
  return s + "</body>\n</html>\n";
}

}  // namespace

std::vector<ThresholdPoint> threshold_curve(const Evaluation& e, const std::string& setting,
                                            int assumption, int steps) {
  std::vector<ThresholdPoint> curve;
  const double t = *e.settings.find.selection.threshold;
  for (int i = 0; i < steps; ++i) {
    ThresholdPoint point;
    point.threshold = t * (0.1 + 1.9 * i / std::max(1, steps - 1));
    const Counts counts = evaluation_row(e, setting, assumption, point.threshold).counts;
    point.precision = counts.precision();
    point.recall = counts.recall();
    curve.push_back(point);
  }
  return curve;
}

void write_evaluation_report(const std::string& dir, const Evaluation& e,
                             const std::string& dataset_dir,
                             const std::vector<ExplainedCase>* explained) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw Error(dir + ": cannot create the report directory (" + ec.message() + ")");
  ReportTables tables;
  tables.rows = evaluation_rows(e);
  tables.by_range = evaluation_rows_by_range(e);
  if (records_hidden_fractions(e)) tables.by_hidden = evaluation_rows_by_hidden(e);
  if (!dataset_dir.empty()) tables.failures = failure_pictures(e, dataset_dir);
  tables.explained = explained;
  json j = detail::evaluation_document_to_json(e, tables.rows);
  if (explained) j["explain"] = detail::explanation_to_json(*explained);
  json curves = json::array();
  for (const std::string& setting : evaluation_settings(e)) {
    json points = json::array();
    for (const ThresholdPoint& p : threshold_curve(e, setting, curve_assumption(e))) {
      points.push_back({{"threshold", p.threshold},
                        {"precision", p.precision ? json(*p.precision) : json(nullptr)},
                        {"recall", p.recall ? json(*p.recall) : json(nullptr)}});
    }
    curves.push_back(
        {{"setting", setting}, {"assumption", curve_assumption(e)}, {"points", points}});
  }
  j["threshold_curves"] = curves;
  j["rows_by_range"] = detail::rows_to_json(tables.by_range);
  if (!tables.by_hidden.empty()) j["rows_by_hidden"] = detail::rows_to_json(tables.by_hidden);
  if (tables.failures) {
    json failures = json::array();
    for (const FailurePicture& f : tables.failures->pictures) {
      failures.push_back({{"scene", f.scene},
                          {"landmark", f.landmark},
                          {"missed", f.missed},
                          {"false_matches", f.false_found},
                          {"caption", f.caption}});
    }
    j["failures"] = {{"pairs_with_failures", tables.failures->pairs_with_failures},
                     {"pictured", failures},
                     {"unpictured", tables.failures->unpictured}};
  }
  write_text_atomically(fs::path(dir) / "report.json", j.dump(2) + "\n");
  const std::vector<ReportSection> sections = report_sections(e, tables);
  write_text_atomically(fs::path(dir) / "report.md", markdown(e, sections));
  write_text_atomically(fs::path(dir) / "report.html", html(e, sections));
}

}  // namespace lmk
