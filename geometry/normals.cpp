#include "geometry/normals.h"

#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>

#include "geometry/error.h"

namespace lmk {

std::vector<Eigen::Vector3f> estimate_normals(const PointCloud& cloud, const KdTree& tree,
                                              const NormalSettings& settings) {
  if (settings.k < 3)
    throw Error("normals: k must be at least 3, got " + std::to_string(settings.k));
  const Eigen::Vector3f nan = Eigen::Vector3f::Constant(std::nanf(""));
  const Eigen::Vector3d origin = cloud.sensor_origin();
  std::vector<Eigen::Vector3f> normals(cloud.size(), nan);

  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cloud.size()), [&](const auto& range) {
    std::vector<Neighbor> neighbors;  // one scratch buffer per task, never shared
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const Eigen::Vector3f& p = cloud.points[i];
      if (!is_finite(p)) continue;
      tree.knn(p, static_cast<std::size_t>(settings.k), neighbors);
      if (neighbors.size() < 3) continue;
      // Covariance about the neighbourhood mean, in double for conditioning.
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (const Neighbor& n : neighbors) mean += cloud.points[n.index].cast<double>();
      mean /= static_cast<double>(neighbors.size());
      Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
      for (const Neighbor& n : neighbors) {
        const Eigen::Vector3d d = cloud.points[n.index].cast<double>() - mean;
        cov += d * d.transpose();
      }
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(cov);
      // Eigenvalues come in increasing order; two near-zero ones mean the points lie on a line.
      if (solver.eigenvalues()[1] <= 1e-12 * std::max(1.0, solver.eigenvalues()[2])) continue;
      Eigen::Vector3d n = solver.eigenvectors().col(0);
      if (n.dot(origin - p.cast<double>()) < 0.0) n = -n;
      normals[i] = n.cast<float>();
    }
  });
  return normals;
}

void compute_normals(PointCloud& cloud, const NormalSettings& settings) {
  const KdTree tree(cloud);
  cloud.normals = estimate_normals(cloud, tree, settings);
}

}  // namespace lmk
