// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/datasets/real_data.h"

#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"

namespace lmk {

Box milk_carton_box(const PointCloud& carton_crop) {
  const Eigen::AlignedBox3f bounds = carton_crop.bounds();
  if (bounds.isEmpty()) throw Error("milk_carton_box: the carton crop has no finite point");
  Eigen::Vector3d lo = bounds.min().cast<double>(), hi = bounds.max().cast<double>();
  constexpr double kMargin = 0.02;
  lo -= Eigen::Vector3d::Constant(kMargin);  // left, top (-y) and front (-z)
  hi.x() += kMargin;                         // right
  Box box;
  box.pose.translation() = 0.5 * (lo + hi);
  box.size = hi - lo;
  return box;
}

MilkWorkload load_milk_workload(const std::filesystem::path& data_dir) {
  MilkWorkload w;
  w.scene = read_cloud((data_dir / "pcl/milk_cartoon_all_small_clorox.pcd").string());
  w.box = milk_carton_box(read_cloud((data_dir / "pcl/milk.pcd").string()));
  w.landmark = capture(w.scene, w.box, "milk");
  return w;
}

}  // namespace lmk
