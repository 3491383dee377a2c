// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/landmark/detail/landmark_container.h"

#include <cstdint>
#include <cstring>

#include "lmk/geometry/error.h"
#include "lmk/geometry/hash.h"

namespace lmk::detail {

namespace {

constexpr char kTrailerMagic[8] = {'L', 'M', 'K', 'T', 'R', 'A', 'I', 'L'};
// The trailer's hash starts from this basis (not FNV's standard one, which has one digit more);
// it is part of the file format, so it stays.
constexpr std::uint64_t kTrailerHashBasis = 1469598103934665603ULL;

std::uint64_t trailer_hash(const char* data, std::size_t size) {
  return Fnv1a(kTrailerHashBasis).add(data, size).value();
}

// The OpenVDB file version whose layout check_vdb_layout knows (io::Archive, OpenVDB 6 to 10).
constexpr std::uint32_t kVdbFileVersion = 224;

// A cursor over the OpenVDB data: little-endian reads that throw, naming what was being read,
// when the data ends first.
class VdbReader {
 public:
  VdbReader(const std::string& path, const std::string& data) : path_(path), data_(data) {}

  template <typename T>
  T read(const char* what) {
    require(sizeof(T), what);
    T value;
    std::memcpy(&value, data_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }

  void skip(std::uint64_t bytes, const char* what) {
    require(bytes, what);
    at_ += static_cast<std::size_t>(bytes);
  }

  // io::readString: a 32-bit length, then the characters.
  void skip_string(const char* what) { skip(read<std::uint32_t>(what), what); }

  // MetaMap::readMeta: a count, then per entry a name, a type name and a sized value.
  void skip_metadata(const char* what) {
    const auto count = read<std::int32_t>(what);
    // Each entry takes at least 12 bytes (three lengths): a larger count cannot be honest.
    if (count < 0 || static_cast<std::uint64_t>(count) * 12 > remaining()) corrupt(what);
    for (std::int32_t i = 0; i < count; ++i) {
      skip_string(what);
      skip_string(what);
      skip(read<std::uint32_t>(what), what);
    }
  }

  void seek(std::int64_t offset, const char* what) {
    if (offset < 0 || static_cast<std::uint64_t>(offset) > data_.size()) corrupt(what);
    at_ = static_cast<std::size_t>(offset);
  }

  std::size_t at() const { return at_; }
  std::uint64_t remaining() const { return data_.size() - at_; }

  [[noreturn]] void corrupt(const char* what) const {
    throw Error(path_ + ": corrupt landmark file: its " + what +
                " declares more bytes than the file holds");
  }

 private:
  void require(std::uint64_t bytes, const char* what) const {
    if (bytes > remaining()) corrupt(what);
  }

  const std::string& path_;
  const std::string& data_;
  std::size_t at_ = 0;
};

}  // namespace

std::string landmark_trailer(const std::string& data) {
  const std::uint64_t length = data.size(), hash = trailer_hash(data.data(), data.size());
  std::string trailer(kTrailerMagic, sizeof(kTrailerMagic));
  trailer.append(reinterpret_cast<const char*>(&length), sizeof(length));
  trailer.append(reinterpret_cast<const char*>(&hash), sizeof(hash));
  return trailer;
}

void check_landmark_trailer(const std::string& path, const std::string& bytes) {
  if (bytes.size() < kLandmarkTrailerSize ||
      bytes.compare(bytes.size() - kLandmarkTrailerSize, sizeof(kTrailerMagic), kTrailerMagic,
                    sizeof(kTrailerMagic)) != 0) {
    throw Error(path + ": truncated, or an OpenVDB file that lmk did not write (no lmk trailer)");
  }
  std::uint64_t length = 0, hash = 0;
  std::memcpy(&length, bytes.data() + bytes.size() - 16, sizeof(length));
  std::memcpy(&hash, bytes.data() + bytes.size() - 8, sizeof(hash));
  if (length != bytes.size() - kLandmarkTrailerSize || hash != trailer_hash(bytes.data(), length)) {
    throw Error(path +
                ": corrupt landmark file: its data does not match the checksum it was "
                "written with");
  }
}

void check_vdb_layout(const std::string& path, const std::string& data) {
  VdbReader in(path, data);
  // io::Archive::readHeader: magic, file version, library version, grid offsets flag, UUID.
  in.read<std::int64_t>("header");
  if (in.read<std::uint32_t>("header") != kVdbFileVersion) return;  // another layout: OpenVDB's
  in.skip(2 * sizeof(std::uint32_t), "header");
  const bool has_grid_offsets = in.read<char>("header") != 0;
  in.skip(36, "header");  // the UUID, as text
  in.skip_metadata("file metadata");
  if (!has_grid_offsets) return;  // lmk always writes offsets; without them, OpenVDB's layout
  const auto grids = in.read<std::int32_t>("grid count");
  if (grids < 0 || grids > 64) in.corrupt("grid count");
  for (std::int32_t g = 0; g < grids; ++g) {
    // io::GridDescriptor::read: name, type, instance parent, then the grid, block and end offsets.
    in.skip_string("grid descriptor");
    in.skip_string("grid descriptor");
    in.skip_string("grid descriptor");
    const auto grid_at = in.read<std::int64_t>("grid descriptor");
    const auto block_at = in.read<std::int64_t>("grid descriptor");
    const auto end_at = in.read<std::int64_t>("grid descriptor");
    if (grid_at != static_cast<std::int64_t>(in.at()) || block_at < grid_at || end_at < block_at ||
        static_cast<std::uint64_t>(end_at) > data.size()) {
      in.corrupt("grid descriptor");
    }
    // io::Archive::readGrid: the compression flags, then the grid's own metadata.
    in.read<std::uint32_t>("grid compression");
    in.skip_metadata("grid metadata");
    if (static_cast<std::int64_t>(in.at()) > block_at) in.corrupt("grid metadata");
    in.seek(end_at, "grid descriptor");  // the next descriptor follows the grid
  }
}

}  // namespace lmk::detail
