// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The .lmk container of format 5: lmk's own bytes, which lmk parses whole, instead of OpenVDB's.
// Internal; landmark_file.cpp maps a Landmark to and from it, and the tests and fuzz target build
// files with it.
//
// Formats 1 to 4 were OpenVDB files whose grids OpenVDB decoded: behind a valid checksum a forged
// grid aborted the process, and 147 of 300 loaded with silently changed contents (issue #61,
// finding 2). Format 5 stores what the grids are built from, and loading rebuilds them:
//
//   offset  size  what
//   0       8     magic "\x89LMK\r\n\x1a\n"
//   8       4     uint32 5, the format version
//   12      4     uint32 H, the header's length (1 to kMaxRecordHeaderBytes)
//   16      H     the header: a JSON object (landmark.json's fields, plus "arrays")
//   16+H    12 N  the points: float32 x, y, z each, in capture order
//                 [with "views": uint32 each, one bit per view]
//                 [with "colours": uint8 r, g, b each]
//           12 M  the empty-space voxels: int32 i, j, k each, in strictly ascending order
//   end     24    the trailer (landmark_container.h): "LMKTRAIL", the length, the FNV-1a hash
//
// N and M are the header's "arrays": {"points": N, "views": bool, "colours": bool,
// "empty_voxels": M}; the arrays must fill the bytes between the header and the trailer exactly.
// Every number is little-endian.

#include <Eigen/Core>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lmk/geometry/point_cloud.h"

namespace lmk::detail {

inline constexpr int kRecordFormatVersion = 5;
inline constexpr std::size_t kMaxRecordHeaderBytes = 1 << 20;

/// What a format-5 file holds.
struct LandmarkRecord {
  nlohmann::json header;  ///< an object: everything but the arrays ("arrays" is written for them)
  std::vector<Eigen::Vector3f> points;
  std::vector<std::uint32_t> views;  ///< empty, or one mask per point
  std::vector<Color> colours;        ///< empty, or one per point (alpha is not stored)
  std::vector<Eigen::Vector3i> empty_voxels;
};

/// Whether `bytes` begins with format 5's magic.
bool has_record_magic(const std::string& bytes);

/// The record's bytes, without the trailer.
std::string record_bytes(const LandmarkRecord& record);

/// The record in `data` (a file's bytes without its trailer). Throws lmk::Error naming `path` for
/// anything that is not as written above: the magic, the version, the header's length and JSON,
/// the arrays' counts against the bytes, a non-finite point, voxels out of order.
LandmarkRecord parse_record(const std::string& path, const std::string& data);

}  // namespace lmk::detail
