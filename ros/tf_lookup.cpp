// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/ros/tf_lookup.h"

#include <tf2/exceptions.h>
#include <tf2_eigen/tf2_eigen.h>

#include "lmk/geometry/error.h"

namespace lmk::ros1 {

Eigen::Isometry3d lookup_pose(const tf2_ros::Buffer& tf, const std::string& target,
                              const std::string& source, const ::ros::Time& time,
                              const ::ros::Duration& timeout) {
  try {
    // Without a timeout, ask the core directly: tf2_ros's waiting lookup wants a TF thread (a bag's
    // buffer has none) and complains even when it would not wait.
    if (timeout.isZero()) {
      const tf2::BufferCore& core = tf;
      return tf2::transformToEigen(core.lookupTransform(target, source, time));
    }
    return tf2::transformToEigen(tf.lookupTransform(target, source, time, timeout));
  } catch (const tf2::TransformException& e) {
    throw Error("no transform from '" + source + "' to '" + target + "': " + e.what());
  }
}

}  // namespace lmk::ros1
