// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/landmark/slide_check.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <limits>

#include "lmk/geometry/depth_noise.h"
#include "lmk/registration/point_to_plane.h"

namespace lmk {
namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

// "the box's x" when `axis` lies within 15 degrees of one of the box's axes, else its components.
std::string describe_axis(const Eigen::Vector3d& axis, const Box& box) {
  static const char* const kNames[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    if (std::abs(axis.dot(box.pose.linear().col(k))) >= std::cos(15.0 * kPi / 180.0))
      return std::string("the box's ") + kNames[k];
  }
  char text[64];
  std::snprintf(text, sizeof(text), "(%.2f, %.2f, %.2f)", axis.x(), axis.y(), axis.z());
  return text;
}

std::vector<Slide> motion_extents(const PointCloud& points, double noise) {
  std::vector<Slide> motions;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  std::size_t n = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (i < points.normals.size() && is_finite(points.points[i]) && is_finite(points.normals[i])) {
      centroid += points.points[i].cast<double>();
      ++n;
    }
  }
  if (n < 6 || !(noise > 0.0)) return motions;  // too few normals to say anything
  centroid /= static_cast<double>(n);
  double spread = 0.0;
  for (std::size_t i = 0; i < points.normals.size(); ++i) {
    if (is_finite(points.points[i]) && is_finite(points.normals[i]))
      spread += (points.points[i].cast<double>() - centroid).squaredNorm();
  }
  const double L = std::sqrt(spread / static_cast<double>(n));
  if (!(L > 0.0)) return motions;
  // The point-to-plane system of the landmark against itself (ICP's, point_to_plane.h), for a
  // translation t and a rotation about the centroid scaled by L, so that both are in metres.
  PointToPlaneSystem system;
  for (std::size_t i = 0; i < points.normals.size(); ++i) {
    if (!is_finite(points.points[i]) || !is_finite(points.normals[i])) continue;
    const Eigen::Vector3d p = points.points[i].cast<double>() - centroid;
    const Eigen::Vector3d normal = points.normals[i].cast<double>().normalized();
    Eigen::Matrix<double, 6, 1> J;
    J << normal, p.cross(normal) / L;
    system.add(J, 0.0, 1.0);
  }
  const Eigen::Matrix<double, 6, 6> H = system.JtJ / static_cast<double>(n);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eigen(H);
  // Ascending eigenvalues: the freest direction first.
  for (int k = 0; k < 6; ++k) {
    const double lambda = std::max(0.0, eigen.eigenvalues()(k));
    const Eigen::Matrix<double, 6, 1> v = eigen.eigenvectors().col(k);
    const double s =
        lambda > 1e-12 ? noise / std::sqrt(lambda) : std::numeric_limits<double>::infinity();
    const Eigen::Vector3d t = v.head<3>();
    const Eigen::Vector3d w = v.tail<3>() / L;  // rad per unit of s
    Slide slide;
    slide.turn = v.tail<3>().squaredNorm() > v.head<3>().squaredNorm();
    if (slide.turn) {
      slide.axis = w.normalized();
      // The screw axis of the motion (t, w) about the centroid passes through c + w x t / |w|^2.
      slide.through = centroid + w.cross(t) / w.squaredNorm();
      slide.extent = s * w.norm();
    } else {
      slide.axis = t.normalized();
      slide.through = centroid;
      slide.extent = s * t.norm();
    }
    slide.displacement = s;
    motions.push_back(slide);
  }
  return motions;
}

SlideReport slide_check(const PointCloud& points, double noise) {
  SlideReport report;
  report.noise = noise;
  // A motion of s raises the RMS residual by s sqrt(lambda): free when that stays within the noise
  // up to kSlideReportSigmas noise sigmas.
  for (const Slide& m : motion_extents(points, noise)) {
    if (!(m.displacement > kSlideReportSigmas * noise)) break;
    report.slides.push_back(m);
  }
  return report;
}

SlideReport slide_check(const Landmark& landmark, const DepthNoise& noise) {
  const double range = (landmark.box.center() - landmark.sensor_origin).norm();
  return slide_check(landmark.points, noise.residual_sigma(range, range));
}

std::vector<std::string> describe_slides(const SlideReport& report, const Box& box) {
  std::vector<std::string> lines;
  const double diagonal = box.size.norm();
  for (const Slide& s : report.slides) {
    char amount[48];
    if (s.turn) {
      if (!(s.extent < kPi)) {
        std::snprintf(amount, sizeof(amount), "freely");
      } else {
        std::snprintf(amount, sizeof(amount), "%.0f degrees", s.extent * 180.0 / kPi);
      }
      lines.push_back(std::string("turns ") + amount + " about " + describe_axis(s.axis, box) +
                      " within the noise");
    } else {
      if (!(s.extent < diagonal)) {
        std::snprintf(amount, sizeof(amount), "freely");
      } else {
        std::snprintf(amount, sizeof(amount), "%.0f cm", s.extent * 100.0);
      }
      lines.push_back(std::string("slides ") + amount + " along " + describe_axis(s.axis, box) +
                      " within the noise");
    }
  }
  if (!lines.empty()) {
    lines.push_back(
        "a search cannot tell the true pose from its neighbours along these: widen the box to take "
        "in an end or a corner (a shape symmetric about an axis turns about it by nature)");
  }
  return lines;
}

}  // namespace lmk
