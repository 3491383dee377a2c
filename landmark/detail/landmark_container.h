// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What lmk checks in a landmark file before OpenVDB parses it (landmark_file.cpp). Internal; the
// fuzz target and the tests use it to build files with a valid trailer over chosen contents.
//
// 1. The lmk trailer, appended after the OpenVDB data: a magic word, the length of the data
//    before it and an FNV-1a hash of that data. OpenVDB ignores trailing bytes, so the file stays
//    a plain VDB file for other tools. It catches damage: truncation, flipped bits.
// 2. The OpenVDB container's layout: the header, the grid descriptors and each grid's metadata,
//    walked with every declared length checked against the bytes present. OpenVDB trusts those
//    lengths: a metadata string declared 4 GB long in a 160 kB file made it allocate 18 GB.

#include <cstddef>
#include <string>

namespace lmk::detail {

/// The trailer's size in bytes: magic (8), data length (8), hash (8).
inline constexpr std::size_t kLandmarkTrailerSize = 24;

/// The trailer for `data` (24 bytes), to append to it.
std::string landmark_trailer(const std::string& data);

/// Throws lmk::Error naming `path` unless `bytes` ends in a trailer that matches the rest.
void check_landmark_trailer(const std::string& path, const std::string& bytes);

/// Throws lmk::Error naming `path` unless the OpenVDB data (the file without its trailer) is laid
/// out as OpenVDB 10 writes it, with every declared length and offset within the data. Files of
/// another OpenVDB file version are left to OpenVDB.
void check_vdb_layout(const std::string& path, const std::string& data);

}  // namespace lmk::detail
