// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/detail/pcd_compressed.h"

#include <algorithm>
#include <cstring>

#include "lmk/geometry/detail/lzf_stream.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/point_records.h"

namespace lmk::detail {
namespace {

// PCL's datatype code for a TYPE and SIZE; 0 (no type) for one lmk cannot read, which
// decode_point_records refuses only if it reads that field.
std::uint8_t datatype_of(const PcdField& f) {
  using T = PointDatatype;
  T t = T{0};
  if (f.type == 'F') t = f.size == 4 ? T::kFloat32 : f.size == 8 ? T::kFloat64 : T{0};
  if (f.type == 'U')
    t = f.size == 1 ? T::kUint8 : f.size == 2 ? T::kUint16 : f.size == 4 ? T::kUint32 : T{0};
  if (f.type == 'I')
    t = f.size == 1 ? T::kInt8 : f.size == 2 ? T::kInt16 : f.size == 4 ? T::kInt32 : T{0};
  return static_cast<std::uint8_t>(t);
}

// A field kept: where its values lie in the uncompressed stream and where they go in the blob.
struct Kept {
  std::size_t stream_start = 0;  // the field's first byte in the stream
  std::size_t stride = 0;        // its bytes per point in the stream (size x count)
  std::size_t size = 0;          // the bytes kept per point: its first value
  std::size_t offset = 0;        // the value's offset within a blob point
};

// Copies the kept values that fall within stream bytes [position, position + n) into the blob.
void keep(const Kept& k, std::size_t points, std::size_t position, const unsigned char* bytes,
          std::size_t n, pcl::PCLPointCloud2& blob) {
  const std::size_t field_end = k.stream_start + points * k.stride;
  const std::size_t low = std::max(position, k.stream_start);
  const std::size_t high = std::min(position + n, field_end);
  for (std::size_t i = low < high ? (low - k.stream_start) / k.stride : points; i < points; ++i) {
    const std::size_t value = k.stream_start + i * k.stride;
    if (value >= high) break;
    const std::size_t from = std::max(value, low), to = std::min(value + k.size, high);
    if (from < to) {
      std::memcpy(blob.data.data() + i * blob.point_step + k.offset + (from - value),
                  bytes + (from - position), to - from);
    }
  }
}

}  // namespace

pcl::PCLPointCloud2 read_compressed_body(const std::string& path, const unsigned char* body,
                                         std::size_t available, const std::vector<PcdField>& fields,
                                         std::uint32_t width, std::uint32_t height) {
  const std::size_t points = std::size_t{width} * height;
  pcl::PCLPointCloud2 blob;
  blob.width = width;
  blob.height = height;
  std::vector<Kept> kept;
  std::size_t stream_bytes = 0, padding_bytes = 0;
  for (const PcdField& f : fields) {
    const std::size_t stride = f.size * f.count;
    if (f.name == "_") {
      padding_bytes += stride;
      continue;
    }
    const bool first_of_its_name =
        std::none_of(blob.fields.begin(), blob.fields.end(),
                     [&f](const pcl::PCLPointField& b) { return b.name == f.name; });
    if (is_read_field(f.name) && first_of_its_name) {
      pcl::PCLPointField b;
      b.name = f.name;
      b.offset = blob.point_step;
      b.datatype = datatype_of(f);
      b.count = 1;
      blob.fields.push_back(b);
      kept.push_back({stream_bytes * points, stride, f.size, blob.point_step});
      blob.point_step += static_cast<std::uint32_t>(f.size);
    }
    stream_bytes += stride;
  }
  blob.row_step = blob.point_step * width;

  // The block starts with its compressed and uncompressed sizes (uint32 each).
  std::uint32_t sizes[2] = {0, 0};
  if (available < sizeof(sizes)) {
    throw Error(path + ": truncated: the compressed block has no sizes");
  }
  std::memcpy(sizes, body, sizeof(sizes));
  if (available - sizeof(sizes) < sizes[0]) {
    throw Error(path + ": truncated: the compressed block declares " + std::to_string(sizes[0]) +
                " bytes but the file holds " + std::to_string(available - sizeof(sizes)));
  }
  if (sizes[1] != points * stream_bytes && sizes[1] != points * (stream_bytes + padding_bytes)) {
    const std::size_t held = stream_bytes == 0 ? 0 : sizes[1] / stream_bytes;
    throw Error(path + (held < points ? ": truncated: header" : ": header") + " declares " +
                std::to_string(points) + " points but the data holds " + std::to_string(held));
  }
  if (points == 0) return blob;
  // What the block expands to in the fields kept, against its own size. LZF can repeat 264 bytes
  // from 3, and a cloud of zeros is a valid cloud: 6 MB declaring 50 million x, y, z points held
  // 1.2 GB. Real clouds expand 1.5- to 3.4-fold into these fields (the 54 compressed PCDs of
  // ../shared/data), a frame of mostly no returns more. A file whose kept points pass 256 MiB
  // (16 million points of x, y, z and colour) may expand at most 16-fold: any file under 25 MB
  // is read within 1 GB (issue #61, finding 1).
  constexpr std::size_t kMostKeptExpansion = 16;
  constexpr std::size_t kKeptBytesAlwaysRead = std::size_t{256} << 20;
  const std::size_t kept_bytes = points * blob.point_step;
  if (kept_bytes > std::max(kKeptBytesAlwaysRead, kMostKeptExpansion * sizes[0])) {
    throw Error(path + ": its compressed block of " + std::to_string(sizes[0]) +
                " bytes would expand to " + std::to_string(kept_bytes) + " bytes of points, over " +
                std::to_string(kMostKeptExpansion) +
                " times its size (real clouds expand 1.5 to 3.4 times); save it as binary PCD to "
                "read it");
  }
  blob.data.resize(points * blob.point_step);
  const std::string problem =
      decode_lzf_stream(body + sizeof(sizes), sizes[0], sizes[1],
                        [&](std::size_t position, const unsigned char* bytes, std::size_t n) {
                          for (const Kept& k : kept) keep(k, points, position, bytes, n, blob);
                        });
  if (!problem.empty()) throw Error(path + ": corrupt compressed PCD data: " + problem);
  return blob;
}

}  // namespace lmk::detail
