// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The third-party libraries each lmk module is built on, with the versions compiled in. `lmk
// --version` prints them, so a bug report states exactly what it ran against.

#include <string>
#include <vector>

namespace lmk {

struct DependencyVersion {
  std::string name;
  std::string version;
};

/// "major.minor.patch".
std::string dotted_version(int major, int minor, int patch);

/// Eigen, PCL (file I/O), CGAL (oriented boxes), nanoflann and TBB.
std::vector<DependencyVersion> geometry_dependencies();

}  // namespace lmk
