// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Reading an input file whole, safely: lmk refuses what is not a regular file (a named pipe would
// block the open forever, a device could stream without end) and any file over a documented
// ceiling, before anything is opened or allocated. Every reader of user files goes through here:
// point clouds, landmarks, programs, datasets, boxes, the robot description and cache entries.

#include <cstdint>
#include <filesystem>
#include <string>
#include <system_error>

namespace lmk {

/// Ceilings on the size of each kind of file lmk reads (docs/reliability.md). A point-cloud file
/// is read whole before decoding; 4 GiB holds a binary scene of kMaxCloudPoints with colour.
inline constexpr std::uintmax_t kMaxCloudFileBytes = std::uintmax_t{4} << 30;
/// A landmark file is a few MB (points, distance field, free space); 1 GiB is far beyond any box.
inline constexpr std::uintmax_t kMaxLandmarkFileBytes = std::uintmax_t{1} << 30;
/// An image (depth or colour) is decoded whole; 512 MiB is far beyond a 16K x 16K 16-bit PNG.
inline constexpr std::uintmax_t kMaxImageFileBytes = std::uintmax_t{512} << 20;
/// A ROS bag is read through its index, never whole; 1 TiB is beyond any recording of a robot.
inline constexpr std::uintmax_t kMaxBagFileBytes = std::uintmax_t{1} << 40;
/// Programs, datasets, boxes, settings, URDFs and cache entries: JSON or XML text.
inline constexpr std::uintmax_t kMaxTextFileBytes = std::uintmax_t{256} << 20;

/// What a file holds, for messages: "point-cloud file", "landmark file", "program file"...
struct InputKind {
  const char* name;
  std::uintmax_t max_bytes;
};

inline constexpr InputKind kCloudInput{"point-cloud file", kMaxCloudFileBytes};
inline constexpr InputKind kLandmarkInput{"landmark file", kMaxLandmarkFileBytes};
inline constexpr InputKind kJsonInput{"JSON file", kMaxTextFileBytes};
inline constexpr InputKind kProgramInput{"program file", kMaxTextFileBytes};
inline constexpr InputKind kDatasetInput{"dataset file", kMaxTextFileBytes};
inline constexpr InputKind kRobotInput{"robot description", kMaxTextFileBytes};
inline constexpr InputKind kImageInput{"image file", kMaxImageFileBytes};
inline constexpr InputKind kTextInput{"text file", kMaxTextFileBytes};
inline constexpr InputKind kBagInput{"ROS bag", kMaxBagFileBytes};

/// Throws lmk::Error, with one line starting with the path, unless `path` names an existing
/// regular file (after symbolic links) of at most `kind.max_bytes`. Never opens the file.
/// Returns its size.
std::uintmax_t check_input_file(const std::string& path, const InputKind& kind);

/// check_input_file, then the whole contents. An empty file is returned as an empty string.
std::string read_input_file(const std::string& path, const InputKind& kind);

/// Describes a byte count for messages: "512 bytes", "3.2 MiB", "4 GiB".
std::string describe_bytes(std::uintmax_t bytes);

/// Whether `path` lies inside the directory `root` once every symbolic link is followed: the files
/// a dataset or a sequence names may not reach elsewhere ("../../etc/passwd", a link out). `ec` is
/// set, and false returned, when either cannot be resolved (a symbolic link loop).
bool lies_within(const std::filesystem::path& path, const std::filesystem::path& root,
                 std::error_code& ec);

}  // namespace lmk
