// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/geometry/depth_image.h"

#include <png.h>

#include <cctype>
#include <cmath>
#include <csetjmp>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <sstream>

#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/input_file.h"
#include "lmk/geometry/settings_schema.h"

namespace lmk {

static_assert(kMaxImagePixels <= kMaxCloudPoints,
              "every depth image lmk reads must become a cloud lmk reads");

namespace {

// The path's extension in lower case: ".png".
std::string extension_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

void check_size(const std::string& path, std::uint64_t width, std::uint64_t height) {
  if (width == 0 || height == 0) throw Error(path + ": the image has no pixels");
  if (width * height > kMaxImagePixels) {
    throw Error(path + ": " + std::to_string(width) + " x " + std::to_string(height) +
                " pixels, more than lmk reads (" + std::to_string(kMaxImagePixels) + ")");
  }
}

// libpng reports errors through a callback that must not return: it stores the message and jumps
// back to the guard below, whose frame is still live. No C++ object is constructed between the
// setjmp and the jump, so none is skipped.
struct PngRead {
  explicit PngRead(const std::string& path_in, const std::string& bytes_in)
      : path(path_in), bytes(bytes_in) {
    png = png_create_read_struct(PNG_LIBPNG_VER_STRING, this, &PngRead::on_error,
                                 &PngRead::on_warning);
    if (png) info = png_create_info_struct(png);
    if (!png || !info) throw Error(path + ": out of memory to read the PNG");
    png_set_read_fn(png, this, &PngRead::on_read);
    png_set_user_limits(png, 1u << 20, 1u << 20);  // width and height; the pixel cap is ours
  }
  ~PngRead() { png_destroy_read_struct(&png, &info, nullptr); }
  PngRead(const PngRead&) = delete;
  PngRead& operator=(const PngRead&) = delete;

  static void on_error(png_structp png, png_const_charp message) {
    auto* self = static_cast<PngRead*>(png_get_error_ptr(png));
    std::strncpy(self->message, message, sizeof(self->message) - 1);
    png_longjmp(png, 1);
  }
  static void on_warning(png_structp, png_const_charp) {}
  static void on_read(png_structp png, png_bytep out, png_size_t n) {
    auto* self = static_cast<PngRead*>(png_get_io_ptr(png));
    if (n > self->bytes.size() - self->offset) png_error(png, "the file ends early");
    std::memcpy(out, self->bytes.data() + self->offset, n);
    self->offset += n;
  }

  // Runs `step` (libpng calls only); false when libpng reported an error.
  template <class Step>
  bool guarded(Step&& step) {
    if (setjmp(png_jmpbuf(png))) return false;
    step();
    return true;
  }
  [[noreturn]] void fail() const {
    throw Error(path + ": not a readable PNG (" + std::string(message) + ")");
  }

  // Reads the header and applies `transforms` (png_set_* calls) before the row size is known.
  template <class Transforms>
  void begin(Transforms&& transforms) {
    if (bytes.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(bytes.data()), 0, 8)) {
      throw Error(path + ": not a PNG file");
    }
    if (!guarded([&] {
          png_read_info(png, info);
          transforms();
          png_read_update_info(png, info);
        })) {
      fail();
    }
    width = png_get_image_width(png, info);
    height = png_get_image_height(png, info);
    check_size(path, width, height);
    row_bytes = png_get_rowbytes(png, info);
  }

  // Reads every row into `out`, which must hold height x row_bytes bytes.
  void rows(unsigned char* out) {
    std::vector<png_bytep> pointers(height);
    for (std::uint32_t r = 0; r < height; ++r) pointers[r] = out + std::size_t{r} * row_bytes;
    if (!guarded([&] { png_read_image(png, pointers.data()); })) fail();
  }

  const std::string& path;
  const std::string& bytes;
  std::size_t offset = 0;
  png_structp png = nullptr;
  png_infop info = nullptr;
  char message[256] = {};
  std::uint32_t width = 0, height = 0;
  std::size_t row_bytes = 0;
};

// The PNG file of `height` rows of `row_bytes` bytes each (16-bit samples in host order).
std::string encode_png(const unsigned char* pixels, std::size_t row_bytes, int width, int height,
                       int bit_depth, int colour_type) {
  struct Writer {
    Writer() {
      png = png_create_write_struct(PNG_LIBPNG_VER_STRING, this, &Writer::on_error, nullptr);
      if (png) info = png_create_info_struct(png);
      if (!png || !info) throw Error("PNG: out of memory");
      png_set_write_fn(png, this, &Writer::on_write, nullptr);
    }
    ~Writer() { png_destroy_write_struct(&png, &info); }
    static void on_error(png_structp png, png_const_charp message) {
      auto* self = static_cast<Writer*>(png_get_error_ptr(png));
      std::strncpy(self->message, message, sizeof(self->message) - 1);
      png_longjmp(png, 1);
    }
    static void on_write(png_structp png, png_bytep data, png_size_t n) {
      static_cast<Writer*>(png_get_io_ptr(png))->out.append(reinterpret_cast<char*>(data), n);
    }
    png_structp png = nullptr;
    png_infop info = nullptr;
    char message[256] = {};
    std::string out;
  } w;
  std::vector<png_bytep> rows(static_cast<std::size_t>(height));
  for (int r = 0; r < height; ++r)
    rows[static_cast<std::size_t>(r)] = const_cast<unsigned char*>(pixels) + r * row_bytes;
  if (setjmp(png_jmpbuf(w.png))) throw Error("PNG: cannot encode (" + std::string(w.message) + ")");
  png_set_IHDR(w.png, w.info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height),
               bit_depth, colour_type, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(w.png, w.info);
  if (bit_depth == 16) png_set_swap(w.png);  // host order to PNG's big-endian
  png_write_image(w.png, rows.data());
  png_write_end(w.png, nullptr);
  return std::move(w.out);
}

void check_pixels(std::size_t pixels, int width, int height, const char* what) {
  if (width <= 0 || height <= 0 || pixels != std::size_t(width) * std::size_t(height))
    throw Error(std::string(what) + ": the image's size does not match its pixels");
}

DepthImage read_depth_png(const std::string& path, const std::string& bytes) {
  PngRead read(path, bytes);
  int bit_depth = 0, colour_type = 0;
  read.begin([&] {
    bit_depth = png_get_bit_depth(read.png, read.info);
    colour_type = png_get_color_type(read.png, read.info);
    png_set_swap(read.png);  // PNG stores 16-bit samples big-endian
  });
  if (bit_depth != 16 || colour_type != PNG_COLOR_TYPE_GRAY) {
    throw Error(path + ": a depth image must be 16-bit greyscale PNG (this one has " +
                std::to_string(bit_depth) + "-bit samples, colour type " +
                std::to_string(colour_type) + ")");
  }
  DepthImage image;
  image.width = static_cast<int>(read.width);
  image.height = static_cast<int>(read.height);
  image.depth.resize(std::size_t{read.width} * read.height);
  read.rows(reinterpret_cast<unsigned char*>(image.depth.data()));
  return image;
}

// Binary PGM (P5): "P5", width, height and maxval as text separated by whitespace and comments,
// one whitespace byte, then the samples, 2 bytes big-endian each when maxval exceeds 255.
DepthImage read_depth_pgm(const std::string& path, const std::string& bytes) {
  std::size_t at = 0;
  const auto skip_space = [&] {
    while (at < bytes.size()) {
      if (bytes[at] == '#') {
        while (at < bytes.size() && bytes[at] != '\n') ++at;
      } else if (std::isspace(static_cast<unsigned char>(bytes[at]))) {
        ++at;
      } else {
        break;
      }
    }
  };
  const auto number = [&](const char* what) {
    skip_space();
    std::uint64_t v = 0;
    const std::size_t first = at;
    while (at < bytes.size() && std::isdigit(static_cast<unsigned char>(bytes[at])) &&
           at - first < 9) {
      v = v * 10 + static_cast<std::uint64_t>(bytes[at++] - '0');
    }
    if (at == first) throw Error(path + ": the PGM header lacks its " + std::string(what));
    return v;
  };
  if (bytes.compare(0, 2, "P5") != 0) throw Error(path + ": not a binary PGM (P5) file");
  at = 2;
  const std::uint64_t width = number("width");
  const std::uint64_t height = number("height");
  const std::uint64_t maxval = number("maxval");
  check_size(path, width, height);
  if (maxval <= 255 || maxval > 65535) {
    throw Error(path + ": a depth PGM must have 16-bit samples (maxval 256-65535, this one " +
                std::to_string(maxval) + ")");
  }
  ++at;  // the single whitespace byte before the samples
  const std::uint64_t needed = width * height * 2;
  if (at > bytes.size() || bytes.size() - at < needed) {
    throw Error(path + ": the file ends early (" + std::to_string(width) + " x " +
                std::to_string(height) + " samples need " + std::to_string(needed) + " bytes)");
  }
  DepthImage image;
  image.width = static_cast<int>(width);
  image.height = static_cast<int>(height);
  image.depth.resize(width * height);
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data() + at);
  for (std::size_t i = 0; i < image.depth.size(); ++i) {
    image.depth[i] = static_cast<std::uint16_t>((p[2 * i] << 8) | p[2 * i + 1]);
  }
  return image;
}

// The whitespace-separated finite numbers of a small text file, for messages naming `path`.
std::vector<double> numbers_in(const std::string& path) {
  std::istringstream in(read_input_file(path, kTextInput));
  std::vector<double> out;
  for (std::string word; in >> word;) {
    const std::optional<double> v = read_finite_number(word);
    if (!v) throw Error(path + ": '" + word + "' is not a finite number");
    out.push_back(*v);
  }
  return out;
}

}  // namespace

std::string depth_png(const DepthImage& image) {
  check_pixels(image.depth.size(), image.width, image.height, "depth PNG");
  return encode_png(reinterpret_cast<const unsigned char*>(image.depth.data()),
                    std::size_t(image.width) * 2, image.width, image.height, 16,
                    PNG_COLOR_TYPE_GRAY);
}

std::string greyscale_png(const std::vector<std::uint8_t>& pixels, int width, int height) {
  check_pixels(pixels.size(), width, height, "greyscale PNG");
  return encode_png(pixels.data(), std::size_t(width), width, height, 8, PNG_COLOR_TYPE_GRAY);
}

std::string colour_png(const ColourImage& image) {
  check_pixels(image.pixels.size(), image.width, image.height, "colour PNG");
  return encode_png(reinterpret_cast<const unsigned char*>(image.pixels.data()),
                    std::size_t(image.width) * 4, image.width, image.height, 8,
                    PNG_COLOR_TYPE_RGBA);
}

void PinholeIntrinsics::validate(const std::string& what) const {
  if (!(std::isfinite(fx) && std::isfinite(fy) && std::isfinite(cx) && std::isfinite(cy)) ||
      !(fx > 0.0 && fy > 0.0)) {
    throw Error(what + ": the intrinsics need positive focal lengths and finite centres");
  }
}

std::optional<std::size_t> PinholeIntrinsics::pixel_of(const Eigen::Vector3d& p, int width,
                                                       int height) const {
  if (!p.allFinite() || !(p.z() > 0.0)) return std::nullopt;
  const long u = std::lround(fx * p.x() / p.z() + cx);
  const long v = std::lround(fy * p.y() / p.z() + cy);
  if (u < 0 || v < 0 || u >= width || v >= height) return std::nullopt;
  return static_cast<std::size_t>(v) * static_cast<std::size_t>(width) +
         static_cast<std::size_t>(u);
}

PinholeIntrinsics intrinsics_from_camera_matrix(const double* K, const std::string& where) {
  if (K[1] != 0.0 || K[3] != 0.0 || K[6] != 0.0 || K[7] != 0.0 || K[8] != 1.0) {
    throw Error(where + ": not a camera matrix without skew (fx 0 cx / 0 fy cy / 0 0 1)");
  }
  return {K[0], K[4], K[2], K[5]};
}

PinholeIntrinsics read_intrinsics(const std::string& path) {
  const std::vector<double> v = numbers_in(path);
  PinholeIntrinsics k;
  if (v.size() == 9) {
    k = intrinsics_from_camera_matrix(v.data(), path);
  } else if (v.size() == 4) {
    k = {v[0], v[1], v[2], v[3]};
  } else {
    throw Error(path + ": " + std::to_string(v.size()) +
                " numbers; intrinsics are a 3 x 3 camera matrix or fx fy cx cy");
  }
  k.validate(path);
  return k;
}

bool is_depth_image_file(const std::string& path) {
  const std::string ext = extension_of(path);
  return ext == ".png" || ext == ".pgm";
}

DepthImage read_depth_image(const std::string& path) {
  const std::string bytes = read_input_file(path, kImageInput);
  if (extension_of(path) == ".pgm") return read_depth_pgm(path, bytes);
  if (extension_of(path) == ".png") return read_depth_png(path, bytes);
  throw Error(path + ": a depth image must be .png or .pgm");
}

ColourImage read_colour_image(const std::string& path) {
  const std::string bytes = read_input_file(path, kImageInput);
  if (extension_of(path) != ".png") throw Error(path + ": a colour image must be .png");
  PngRead read(path, bytes);
  read.begin([&] {
    // Every colour type to 8-bit RGBA: palettes and low bit depths expanded, 16 bits reduced,
    // grey copied to three channels, an opaque alpha added where there is none.
    png_set_expand(read.png);
    png_set_strip_16(read.png);
    png_set_gray_to_rgb(read.png);
    png_set_add_alpha(read.png, 0xff, PNG_FILLER_AFTER);
  });
  if (read.row_bytes != std::size_t{read.width} * 4) {
    throw Error(path + ": unexpected PNG layout after conversion to RGBA");
  }
  ColourImage image;
  image.width = static_cast<int>(read.width);
  image.height = static_cast<int>(read.height);
  image.pixels.resize(std::size_t{read.width} * read.height);
  static_assert(sizeof(Color) == 4, "Color is four bytes: r, g, b, a");
  read.rows(reinterpret_cast<unsigned char*>(image.pixels.data()));
  return image;
}

PointCloud depth_to_cloud(const DepthImage& depth, const PinholeIntrinsics& k,
                          const DepthToCloud& conversion, const ColourImage* colour) {
  k.validate("depth to cloud");
  if (depth.width <= 0 || depth.height <= 0 ||
      depth.depth.size() != std::size_t(depth.width) * std::size_t(depth.height)) {
    throw Error("depth to cloud: the depth image's size does not match its pixels");
  }
  if (!(conversion.metres_per_unit > 0.0) || !std::isfinite(conversion.metres_per_unit)) {
    throw Error("depth to cloud: the depth unit must be a positive number of metres");
  }
  if (colour && (colour->width != depth.width || colour->height != depth.height)) {
    throw Error("depth to cloud: the colour image is " + std::to_string(colour->width) + " x " +
                std::to_string(colour->height) + ", the depth image " +
                std::to_string(depth.width) + " x " + std::to_string(depth.height) +
                ": colour must be registered to depth, pixel for pixel");
  }
  PointCloud cloud;
  cloud.width = static_cast<std::uint32_t>(depth.width);
  cloud.height = static_cast<std::uint32_t>(depth.height);
  cloud.points.resize(depth.depth.size());
  if (colour) cloud.colors = colour->pixels;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::size_t i = 0;
  for (int v = 0; v < depth.height; ++v) {
    for (int u = 0; u < depth.width; ++u, ++i) {
      const double z = depth.depth[i] * conversion.metres_per_unit;
      if (depth.depth[i] == 0 || z < conversion.min_depth || z > conversion.max_depth) {
        cloud.points[i] = Eigen::Vector3f(nan, nan, nan);
        continue;
      }
      cloud.points[i] =
          Eigen::Vector3d((u - k.cx) * z / k.fx, (v - k.cy) * z / k.fy, z).cast<float>();
    }
  }
  return cloud;
}

}  // namespace lmk
