// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Depth and colour images of an RGB-D camera, and the organised cloud they make.
//
// Depth images are 16-bit: PNG (greyscale, 16 bits) or binary PGM (P5, maxval above 255), in
// whatever unit the camera wrote (millimetres for Kinect-style frames, 1/5000 m in TUM RGB-D); 0
// is "no return". Colour images are 8-bit PNG (greyscale, RGB, with or without alpha, or
// palette). Both are read through libpng, within the input-file ceilings of input_file.h.

#include <cstdint>
#include <string>
#include <vector>

#include "lmk/geometry/pinhole_intrinsics.h"
#include "lmk/geometry/point_cloud.h"

namespace lmk {

/// fx, fy, cx, cy of a 3 x 3 camera matrix given row by row; lmk::Error (`where` first) for one
/// with skew or another last row: the layouts agree on what they accept (issue #47).
PinholeIntrinsics intrinsics_from_camera_matrix(const double* K, const std::string& where);

/// Reads a 3 x 3 camera matrix (fx 0 cx / 0 fy cy / 0 0 1, whitespace-separated, as 7-Scenes,
/// 3DMatch and SUN3D write it) or four numbers "fx fy cx cy". lmk::Error names the file and what
/// is wrong.
PinholeIntrinsics read_intrinsics(const std::string& path);

/// A depth image in the camera's raw unit, row-major.
struct DepthImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint16_t> depth;  ///< 0: no return
};

/// An 8-bit colour image, row-major.
struct ColourImage {
  int width = 0;
  int height = 0;
  std::vector<Color> pixels;
};

/// The most pixels an image may have (a 4096 x 4096 frame, eight times a 1080p depth camera's),
/// checked from its header before anything is allocated. A frame becomes a cloud of as many
/// points, about 57 bytes each on their way (0.9 GB here); an 8000 x 8000 PNG of 140 KB took
/// 3.65 GB and became a cloud lmk's own reader refuses (issue #47). Below kMaxCloudPoints.
inline constexpr std::uint64_t kMaxImagePixels = std::uint64_t{1} << 24;

/// Whether `path` names a depth image by its extension (.png or .pgm, any case).
bool is_depth_image_file(const std::string& path);

/// Reads a 16-bit depth image (.png or .pgm). lmk::Error names the file and the problem: not a
/// PNG or PGM, not 16-bit greyscale, truncated, too large.
DepthImage read_depth_image(const std::string& path);

/// Reads an 8-bit colour PNG; 16-bit channels are reduced to 8.
ColourImage read_colour_image(const std::string& path);

/// PNG files of images, through libpng: a depth image as 16-bit greyscale (what
/// read_depth_image reads back), an 8-bit greyscale picture (row-major, one byte a pixel), and a
/// colour image as 8-bit RGBA. lmk::Error for an image whose size does not match its pixels.
std::string depth_png(const DepthImage& image);
std::string greyscale_png(const std::vector<std::uint8_t>& pixels, int width, int height);
std::string colour_png(const ColourImage& image);

/// How depth becomes points.
struct DepthToCloud {
  double metres_per_unit = 0.001;  ///< millimetres by default
  double min_depth = 0.0;          ///< m; nearer depths are no return
  double max_depth = 10.0;         ///< m; farther depths are no return (beyond any RGB-D camera)
};

/// The organised cloud (width x height, NaN where there was no return) of `depth` in the camera's
/// optical frame, with the sensor at the origin. With `colour` (registered to the depth image:
/// the same size, pixel for pixel), each point gets its pixel's colour.
PointCloud depth_to_cloud(const DepthImage& depth, const PinholeIntrinsics& intrinsics,
                          const DepthToCloud& conversion = {}, const ColourImage* colour = nullptr);

}  // namespace lmk
