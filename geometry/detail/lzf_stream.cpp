// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/detail/lzf_stream.h"

#include <cstring>
#include <vector>

namespace lmk::detail {
namespace {

// The output is written into a buffer of the window plus kStep bytes; when an instruction might
// not fit, what is not yet handed on goes to the sink and the last kLzfWindow bytes move to its
// start. An instruction writes at most 264 bytes.
constexpr std::size_t kStep = 64 * 1024;
constexpr std::size_t kLongestInstruction = 264;

class Output {
 public:
  Output(std::size_t expected, const LzfSink& sink)
      : expected_(expected), sink_(sink), buffer_(kLzfWindow + kStep) {}

  std::size_t written() const { return base_ + fill_; }

  // Room for one more instruction, handing on and sliding the buffer when needed.
  void make_room() {
    if (fill_ + kLongestInstruction <= buffer_.size()) return;
    hand_on();
    std::memmove(buffer_.data(), buffer_.data() + fill_ - kLzfWindow, kLzfWindow);
    base_ += fill_ - kLzfWindow;
    fill_ = kLzfWindow;
  }

  // Copies `n` input bytes; false past the expected length.
  bool literal(const unsigned char* in, std::size_t n) {
    if (written() + n > expected_) return false;
    std::memcpy(buffer_.data() + fill_, in, n);
    fill_ += n;
    return true;
  }

  // Repeats `n` bytes starting `distance` (at most kLzfWindow, and within what was written) back;
  // when they overlap what is being written, the copy repeats them. False past the expected
  // length.
  bool back_reference(std::size_t distance, std::size_t n) {
    if (written() + n > expected_) return false;
    unsigned char* out = buffer_.data() + fill_;
    const unsigned char* from = out - distance;
    if (distance >= n) {
      std::memcpy(out, from, n);
    } else if (distance == 1) {
      std::memset(out, *from, n);  // a run: how a block of zeros is written
    } else {
      for (std::size_t i = 0; i < n; ++i) out[i] = from[i];
    }
    fill_ += n;
    return true;
  }

  // Hands on what the sink has not yet had.
  void hand_on() {
    const std::size_t start = handed_ - base_;
    if (fill_ > start) sink_(handed_, buffer_.data() + start, fill_ - start);
    handed_ = base_ + fill_;
  }

 private:
  std::size_t expected_;
  const LzfSink& sink_;
  std::vector<unsigned char> buffer_;
  std::size_t base_ = 0;    // output position of buffer_[0]
  std::size_t fill_ = 0;    // bytes of buffer_ in use
  std::size_t handed_ = 0;  // output position up to which the sink has had the bytes
};

}  // namespace

std::string decode_lzf_stream(const unsigned char* in, std::size_t in_bytes, std::size_t expected,
                              const LzfSink& sink) {
  Output out(expected, sink);
  std::size_t i = 0;
  while (i < in_bytes) {
    out.make_room();
    const unsigned control = in[i++];
    if (control < 32) {  // a literal run of control + 1 bytes
      const std::size_t n = control + 1;
      if (in_bytes - i < n) return "a literal run is cut off by the end of the block";
      if (!out.literal(in + i, n)) return "the block expands past its declared size";
      i += n;
      continue;
    }
    // A back reference: 3 bits of length (7: one more length byte), 13 bits of distance.
    std::size_t n = control >> 5;
    if (n == 7) {
      if (i >= in_bytes) return "a back reference is cut off by the end of the block";
      n += in[i++];
    }
    if (i >= in_bytes) return "a back reference is cut off by the end of the block";
    const std::size_t distance = ((control & 0x1fu) << 8) + in[i++] + 1;
    if (distance > out.written()) return "a back reference points before the start of the data";
    if (!out.back_reference(distance, n + 2)) return "the block expands past its declared size";
  }
  out.hand_on();
  if (out.written() != expected) {
    return "the block expands to " + std::to_string(out.written()) + " bytes, not the " +
           std::to_string(expected) + " it declares";
  }
  return {};
}

}  // namespace lmk::detail
