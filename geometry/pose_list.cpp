// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/pose_list.h"

#include <cmath>
#include <sstream>

#include "lmk/geometry/error.h"
#include "lmk/geometry/input_file.h"
#include "lmk/geometry/pose.h"

namespace lmk {

std::vector<Eigen::Isometry3d> parse_pose_list(const std::string& text, const std::string& where) {
  std::vector<Eigen::Isometry3d> poses;
  std::istringstream lines(text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    const std::string at = where + ":" + std::to_string(number);
    const std::size_t comment = line.find('#');
    if (comment != std::string::npos) line.erase(comment);
    std::istringstream fields(line);
    std::vector<double> values;
    std::string field;
    while (fields >> field) {
      std::size_t used = 0;
      double v = 0.0;
      try {
        v = std::stod(field, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != field.size()) {
        // Escaped: a NUL would cut the message short, a control byte reach the terminal.
        throw Error(at + ": '" + printable(field, kEchoedBytes) + "' is not a number");
      }
      values.push_back(v);
    }
    if (values.empty()) continue;
    if (values.size() != 7 && values.size() != 8) {
      throw Error(at + ": expected 7 numbers (x y z qx qy qz qw) or 8 (a timestamp first), found " +
                  std::to_string(values.size()));
    }
    const std::size_t o = values.size() - 7;  // past the timestamp
    const Eigen::Vector3d position(values[o], values[o + 1], values[o + 2]);
    const Eigen::Vector4d wxyz(values[o + 6], values[o + 3], values[o + 4], values[o + 5]);
    poses.push_back(pose_from_unit_quaternion(position, wxyz, at, "quaternion"));
  }
  return poses;
}

std::vector<Eigen::Isometry3d> read_pose_list(const std::string& path) {
  // A pose a line, one per frame of a fusion: 1 MiB holds thousands. Parsed text grows about
  // 18-fold, so a 266 MB list took 4.7 GB before its count was checked (issue #61, finding 5).
  constexpr InputKind kPoseListInput{"pose list", std::uintmax_t{1} << 20};
  return parse_pose_list(read_input_file(path, kPoseListInput), path);
}

}  // namespace lmk
