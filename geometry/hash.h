// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A stable 64-bit FNV-1a hash. Unlike std::hash it is the same on every platform and run, so it
// can seed random streams, check file integrity and key caches that outlive the process.

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <type_traits>

namespace lmk {

class Fnv1a {
 public:
  static constexpr std::uint64_t kOffsetBasis = 14695981039346656037ull;
  explicit Fnv1a(std::uint64_t basis = kOffsetBasis) : hash_(basis) {}

  Fnv1a& add(const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) hash_ = (hash_ ^ bytes[i]) * kPrime;
    return *this;
  }
  Fnv1a& add(std::string_view text) {
    add(text.data(), text.size());
    // A separator, so that add("ab").add("c") and add("a").add("bc") differ.
    const unsigned char end = 0xff;
    return add(&end, 1);
  }
  /// The bytes of a trivially copyable value (numbers, plain structs).
  template <typename T>
  Fnv1a& add_value(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>, "hash the bytes of plain values only");
    return add(&value, sizeof(T));
  }

  std::uint64_t value() const { return hash_; }
  /// 16 lowercase hex digits.
  std::string hex() const {
    char text[17];
    std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(hash_));
    return text;
  }

 private:
  static constexpr std::uint64_t kPrime = 1099511628211ull;
  std::uint64_t hash_;
};

/// FNV-1a of a byte range, without separators (the plain algorithm).
inline std::uint64_t fnv1a(const void* data, std::size_t size) {
  return Fnv1a().add(data, size).value();
}

}  // namespace lmk
