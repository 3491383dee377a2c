// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/eval/confidence_fit.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "lmk/eval/risk_coverage.h"
#include "lmk/geometry/error.h"

namespace lmk {

namespace {

// The columns of `names` among confidence_feature_names(); lmk::Error for an unknown one.
std::vector<std::size_t> feature_columns(const std::vector<std::string>& names) {
  const std::vector<std::string>& all = confidence_feature_names();
  std::vector<std::size_t> columns;
  for (const std::string& name : names.empty() ? all : names) {
    const auto it = std::find(all.begin(), all.end(), name);
    if (it == all.end()) {
      std::string known;
      for (const std::string& n : all) known += (known.empty() ? "" : ", ") + n;
      throw Error("calibrate-confidence: unknown feature '" + name + "' (known: " + known + ")");
    }
    columns.push_back(static_cast<std::size_t>(it - all.begin()));
  }
  return columns;
}

// Logistic regression by Newton's method: w minimises the negative log-likelihood of `y` under
// p = 1 / (1 + exp(-x w)) plus ridge / 2 |w|^2 over every weight but the bias (column 0).
Eigen::VectorXd fit_logistic(const Eigen::MatrixXd& x, const Eigen::VectorXd& y, double ridge) {
  const Eigen::Index k = x.cols();
  Eigen::VectorXd w = Eigen::VectorXd::Zero(k);
  Eigen::VectorXd penalty = Eigen::VectorXd::Constant(k, ridge);
  penalty[0] = 0.0;
  for (int iteration = 0; iteration < 100; ++iteration) {
    const Eigen::VectorXd p = (1.0 + (-(x * w)).array().exp()).inverse().matrix();
    const Eigen::VectorXd gradient = x.transpose() * (p - y) + penalty.cwiseProduct(w);
    const Eigen::VectorXd weight = p.array() * (1.0 - p.array());
    Eigen::MatrixXd hessian = x.transpose() * weight.asDiagonal() * x;
    hessian.diagonal() += penalty + Eigen::VectorXd::Constant(k, 1e-9);
    const Eigen::VectorXd step = hessian.ldlt().solve(gradient);
    w -= step;
    if (step.cwiseAbs().maxCoeff() < 1e-10) break;
  }
  return w;
}

}  // namespace

std::vector<ConfidenceSample> confidence_samples(const Evaluation& e) {
  std::vector<ConfidenceSample> out;
  for_each_counted_match(e, [&out](const FoundBox& f, bool right, bool best) {
    out.push_back(
        {confidence_features(f.confidence), right, best, f.confidence.free_space_unconfirmed});
  });
  return out;
}

ConfidenceCalibration fit_confidence_calibration(const std::vector<ConfidenceSample>& samples,
                                                 const ConfidenceFitSettings& settings,
                                                 const std::string& metric,
                                                 const std::string& fitted_on) {
  if (!(settings.ridge >= 0.0)) throw Error("calibrate-confidence: the ridge must be >= 0");
  const std::vector<std::size_t> columns = feature_columns(settings.features);
  std::vector<const ConfidenceSample*> used;
  std::size_t right = 0;
  for (const ConfidenceSample& s : samples) {
    if (s.unconfirmed) continue;  // probability 0 whatever the fit: no evidence for it
    used.push_back(&s);
    right += s.right ? 1 : 0;
  }
  if (used.empty()) throw Error("calibrate-confidence: no match to fit on");
  if (right == 0 || right == used.size()) {
    throw Error("calibrate-confidence: all " + std::to_string(used.size()) + " matches are " +
                (right == 0 ? "wrong" : "right") +
                ": a calibration needs both (add datasets with false matches)");
  }
  const auto n = static_cast<Eigen::Index>(used.size());
  Eigen::MatrixXd x(n, static_cast<Eigen::Index>(columns.size()) + 1);
  Eigen::VectorXd y(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const ConfidenceSample& s = *used[static_cast<std::size_t>(i)];
    x(i, 0) = 1.0;
    for (std::size_t c = 0; c < columns.size(); ++c)
      x(i, static_cast<Eigen::Index>(c) + 1) = s.features[columns[c]];
    y[i] = s.right ? 1.0 : 0.0;
  }
  const Eigen::VectorXd w = fit_logistic(x, y, settings.ridge);
  ConfidenceCalibration out;
  out.metric = metric;
  out.fitted_on = fitted_on;
  out.bias = w[0];
  for (std::size_t c = 0; c < columns.size(); ++c)
    out.weights[confidence_feature_names()[columns[c]]] = w[static_cast<Eigen::Index>(c) + 1];
  return out;
}

void recalibrate(Evaluation& e, const ConfidenceCalibration& calibration) {
  for (PairResult& p : e.pairs) {
    for (FoundBox& f : p.found) calibrate(f.confidence, f.box, &calibration);
  }
}

std::string confidence_calibration_json(const ConfidenceCalibration& c) {
  nlohmann::ordered_json weights = nlohmann::ordered_json::object();
  for (const auto& [name, w] : c.weights) weights[name] = w;
  const nlohmann::ordered_json j = {{"format", "lmk-confidence-calibration"},
                                    {"version", kConfidenceCalibrationVersion},
                                    {"metric", c.metric},
                                    {"fitted_on", c.fitted_on},
                                    {"bias", c.bias},
                                    {"weights", weights}};
  return j.dump(2) + "\n";
}

}  // namespace lmk
