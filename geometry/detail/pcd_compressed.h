// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// PCD's binary_compressed body, read by lmk rather than by PCL: PCL decompresses the whole body and
// then copies it into a cloud of every declared field, so a 22.8 MB file declaring 500,000 points
// of 4,012 bytes took 3.9 GB (issue #61, finding 1). lmk keeps only the fields it reads, one value
// each, as the LZF stream goes by. Internal: not installed.

#include <pcl/PCLPointCloud2.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace lmk::detail {

/// One field as a PCD header declares it.
struct PcdField {
  std::string name;
  std::size_t size = 0;   ///< bytes of one value: 1, 2, 4 or 8
  std::size_t count = 1;  ///< values per point
  char type = 'F';        ///< F, U or I
};

/// Decodes the compressed body at `body` (`available` bytes: its compressed and uncompressed sizes
/// as two uint32, then the LZF block) into a blob of `width` x `height` points that holds only the
/// fields lmk reads (is_read_field), the first value of each, under their declared names and types.
///
/// PCL's layout: the uncompressed data is each field's values for every point, one field after
/// another, padding fields "_" left out; its size must be the points times the fields' bytes
/// (with or without the padding, as PCL's writers have done). Throws lmk::Error naming `path`
/// when the sizes disagree or the block is corrupt.
pcl::PCLPointCloud2 read_compressed_body(const std::string& path, const unsigned char* body,
                                         std::size_t available, const std::vector<PcdField>& fields,
                                         std::uint32_t width, std::uint32_t height);

}  // namespace lmk::detail
