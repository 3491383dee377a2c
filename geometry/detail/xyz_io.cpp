// SPDX-License-Identifier: BSD-3-Clause
// Plain XYZ text: one point a line, "x y z" separated by spaces, tabs or commas. Further columns
// are ignored; blank lines and lines starting with '#' are skipped. Unorganised, no sensor pose.

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "lmk/geometry/detail/formats.h"
#include "lmk/geometry/error.h"

namespace lmk::detail {

CloudFile read_xyz(const std::string& path, const std::string& bytes, std::size_t max_points) {
  if (bytes.find('\0') != std::string::npos) {
    throw Error(path + ": not a text file (XYZ files hold 'x y z' lines of text)");
  }
  CloudFile file;
  file.encoding = Encoding::kAscii;
  file.fields = {"x", "y", "z"};
  std::istringstream in(bytes);
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    for (char& c : line) {
      if (c == ',') c = ' ';
    }
    const char* cursor = line.c_str();
    Eigen::Vector3f p;
    for (int a = 0; a < 3; ++a) {
      char* end = nullptr;
      p[a] = std::strtof(cursor, &end);
      if (end == cursor) {
        throw Error(path + ": line " + std::to_string(number) +
                    " does not start with three numbers x y z: '" + printable(line) + "'");
      }
      cursor = end;
    }
    if (file.cloud.points.size() == max_points) too_many_points(path, "more", max_points);
    file.cloud.points.push_back(p);
  }
  file.cloud.set_unorganized();
  return file;
}

void write_xyz(const std::filesystem::path& file, const PointCloud& cloud) {
  std::FILE* out = std::fopen(file.c_str(), "w");
  if (!out) throw Error(file.string() + ": cannot open for writing");
  // %.9g round-trips any float exactly.
  for (const Eigen::Vector3f& p : cloud.points) {
    std::fprintf(out, "%.9g %.9g %.9g\n", p.x(), p.y(), p.z());
  }
  const bool failed = std::ferror(out) != 0;
  if (std::fclose(out) != 0 || failed) throw Error(file.string() + ": write failed (disk full?)");
}

}  // namespace lmk::detail
