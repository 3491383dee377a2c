// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A list of poses in a text file, one per line, for frames that a command fuses (`lmk find
// A.pcd B.pcd ... --poses F`): each line is the pose of one frame's cloud in a common frame,
// T_common_cloud, as
//
//   x y z qx qy qz qw            metres, and the rotation as a unit quaternion (the order of the
//   t x y z qx qy qz qw          TUM RGB-D benchmark's groundtruth.txt, whose timestamp t may lead)
//
// '#' starts a comment; blank lines are skipped.

#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace lmk {

/// The poses in `text`, in order. Throws lmk::Error "<where>:<line>: ..." for a line that is not
/// 7 or 8 numbers, a number that is not finite, a translation beyond kMaxTranslation (pose.h) or a
/// quaternion that is not of unit length (within 1e-3).
std::vector<Eigen::Isometry3d> parse_pose_list(const std::string& text, const std::string& where);

/// The file at `path` (read_input_file(), a text file).
std::vector<Eigen::Isometry3d> read_pose_list(const std::string& path);

}  // namespace lmk
