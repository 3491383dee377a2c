// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/landmark/detail/landmark_record.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "lmk/geometry/error.h"

namespace lmk::detail {
namespace {

constexpr char kMagic[8] = {'\x89', 'L', 'M', 'K', '\r', '\n', '\x1a', '\n'};

template <typename T>
void put(std::string& out, T value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

// A cursor over the record: little-endian reads that throw, naming what was read, past the end.
class RecordReader {
 public:
  RecordReader(const std::string& path, const std::string& data) : path_(path), data_(data) {}

  template <typename T>
  T read(const char* what) {
    require(sizeof(T), 1, what);
    T value;
    std::memcpy(&value, data_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }

  // Checks that `count` items of `size` bytes remain before reading them.
  void require(std::size_t size, std::size_t count, const char* what) const {
    if (count > (data_.size() - at_) / size) {
      throw Error(path_ + ": corrupt landmark file: " + what + " run past the end of the file");
    }
  }

  std::string read_text(std::size_t n, const char* what) {
    require(1, n, what);
    std::string text = data_.substr(at_, n);
    at_ += n;
    return text;
  }

  std::size_t remaining() const { return data_.size() - at_; }

 private:
  const std::string& path_;
  const std::string& data_;
  std::size_t at_ = 0;
};

// "arrays" of the header: the counts and which optional arrays there are.
struct Arrays {
  std::size_t points = 0, empty_voxels = 0;
  bool views = false, colours = false;
};

Arrays read_arrays(const std::string& path, const nlohmann::json& header) {
  const auto corrupt = [&path](const std::string& why) {
    return Error(path + ": corrupt landmark file: the header's \"arrays\" " + why);
  };
  const auto it = header.find("arrays");
  if (it == header.end() || !it->is_object()) throw corrupt("are missing");
  Arrays a;
  for (const char* count : {"points", "empty_voxels"}) {
    const auto n = it->find(count);
    if (n == it->end() || !n->is_number_unsigned()) {
      throw corrupt(std::string("lack a count of ") + count);
    }
    (std::string(count) == "points" ? a.points : a.empty_voxels) = n->get<std::size_t>();
  }
  for (const char* flag : {"views", "colours"}) {
    const auto b = it->find(flag);
    if (b == it->end() || !b->is_boolean()) throw corrupt(std::string("lack \"") + flag + "\"");
    (std::string(flag) == "views" ? a.views : a.colours) = b->get<bool>();
  }
  return a;
}

bool voxel_less(const Eigen::Vector3i& a, const Eigen::Vector3i& b) {
  return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}

}  // namespace

bool has_record_magic(const std::string& bytes) {
  return bytes.size() >= sizeof(kMagic) && std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) == 0;
}

std::string record_bytes(const LandmarkRecord& record) {
  nlohmann::json header = record.header;
  header["arrays"] = {{"points", record.points.size()},
                      {"views", !record.views.empty()},
                      {"colours", !record.colours.empty()},
                      {"empty_voxels", record.empty_voxels.size()}};
  const std::string text = header.dump();
  std::string out(kMagic, sizeof(kMagic));
  put(out, static_cast<std::uint32_t>(kRecordFormatVersion));
  put(out, static_cast<std::uint32_t>(text.size()));
  out += text;
  for (const Eigen::Vector3f& p : record.points) {
    for (int a = 0; a < 3; ++a) put(out, p[a]);
  }
  for (const std::uint32_t v : record.views) put(out, v);
  for (const Color& c : record.colours) {
    for (const std::uint8_t channel : {c.r, c.g, c.b}) put(out, channel);
  }
  for (const Eigen::Vector3i& v : record.empty_voxels) {
    for (int a = 0; a < 3; ++a) put(out, static_cast<std::int32_t>(v[a]));
  }
  return out;
}

LandmarkRecord parse_record(const std::string& path, const std::string& data) {
  if (!has_record_magic(data)) throw Error(path + ": not an lmk landmark file of format 5");
  RecordReader in(path, data);
  in.read_text(sizeof(kMagic), "the magic");
  const auto version = in.read<std::uint32_t>("the format version");
  if (version != kRecordFormatVersion) {
    throw Error(path + ": landmark format version " + std::to_string(version) +
                " is not supported (this lmk reads versions 1 to " +
                std::to_string(kRecordFormatVersion) + ")");
  }
  const auto header_bytes = in.read<std::uint32_t>("the header's length");
  if (header_bytes == 0 || header_bytes > kMaxRecordHeaderBytes) {
    throw Error(path + ": corrupt landmark file: a header of " + std::to_string(header_bytes) +
                " bytes (1 to " + std::to_string(kMaxRecordHeaderBytes) + ")");
  }
  LandmarkRecord r;
  try {
    r.header = nlohmann::json::parse(in.read_text(header_bytes, "the header"));
  } catch (const nlohmann::json::exception& e) {
    throw Error(path + ": corrupt landmark file: its header is not JSON (" + printable(e.what()) +
                ")");
  }
  if (!r.header.is_object())
    throw Error(path + ": corrupt landmark file: its header is not an object");
  const Arrays a = read_arrays(path, r.header);
  r.header.erase("arrays");

  // The counts must account for every byte: checked before anything is allocated.
  const std::size_t point_bytes = 12 + (a.views ? 4 : 0) + (a.colours ? 3 : 0);
  const std::size_t left = in.remaining();
  if (a.points > left / point_bytes || a.empty_voxels > left / 12 ||
      a.points * point_bytes + a.empty_voxels * 12 != left) {
    throw Error(path + ": corrupt landmark file: " + std::to_string(a.points) + " points and " +
                std::to_string(a.empty_voxels) + " empty voxels do not fill its " +
                std::to_string(left) + " bytes of arrays");
  }
  r.points.resize(a.points);
  for (Eigen::Vector3f& p : r.points) {
    for (int k = 0; k < 3; ++k) p[k] = in.read<float>("the points");
    if (!p.allFinite()) throw Error(path + ": corrupt landmark file: a point is not finite");
  }
  if (a.views) {
    r.views.resize(a.points);
    for (std::uint32_t& v : r.views) v = in.read<std::uint32_t>("the views");
  }
  if (a.colours) {
    r.colours.resize(a.points);
    for (Color& c : r.colours) {
      c.r = in.read<std::uint8_t>("the colours");
      c.g = in.read<std::uint8_t>("the colours");
      c.b = in.read<std::uint8_t>("the colours");
    }
  }
  r.empty_voxels.resize(a.empty_voxels);
  for (std::size_t i = 0; i < r.empty_voxels.size(); ++i) {
    Eigen::Vector3i& v = r.empty_voxels[i];
    for (int k = 0; k < 3; ++k) v[k] = in.read<std::int32_t>("the empty voxels");
    if (i > 0 && !voxel_less(r.empty_voxels[i - 1], v)) {
      throw Error(path + ": corrupt landmark file: the empty voxels are not in ascending order");
    }
  }
  return r;
}

}  // namespace lmk::detail
