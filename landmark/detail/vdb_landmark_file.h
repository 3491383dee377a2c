// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Landmark files of formats 1 to 4: OpenVDB files. lmk writes format 5 (landmark_record.h), and
// reads these in a child process (landmark_file.cpp), since behind a valid checksum a forged grid
// can abort inside libopenvdb (issue #61, finding 2). Internal.
//
// Layout (format 2):
// - grid "points": a PointDataGrid of the landmark points in the capture frame, with the voxel
//   size of the capture leaf, each point carrying its exact coordinates in the float attribute
//   "capture_position" and its index in the landmark in the int attribute "capture_index";
// - metadata on that grid: lmk_format_version, lmk_name, lmk_box_pose (4x4), lmk_box_size,
//   lmk_sensor_origin, lmk_leaf_size, lmk_min_points, lmk_max_box_side, lmk_up,
//   lmk_distance_band, lmk_empty_space_margin, [lmk_allow_flat];
// - grids "distance" (FloatGrid) and "closest" (Int32Grid), the distance field, and "empty"
//   (BoolGrid), the voxels of the box observed free at capture;
// - after the OpenVDB data, the lmk trailer (landmark_container.h).
// Format 1 had only the points grid. Format 3 adds "capture_views" (one bit per view),
// lmk_view_count and lmk_view_origin_V, or "capture_colour" (0xRRGGBB); format 4 the capture
// check's findings as JSON text in lmk_capture_findings.

#include <string>

#include "lmk/landmark/landmark.h"

namespace lmk::detail {

/// Whether `bytes` begin with OpenVDB's magic number.
bool has_vdb_magic(const std::string& bytes);

/// The landmark as a file of format 1 to 4 stores it: its fields, points, views and colours in
/// capture order, its empty space (none in format 1), its findings when stored (else absent), and
/// the version it was written in. Nothing derived: no normals, no distance field. Checks the
/// trailer and the container's layout before OpenVDB reads anything. Throws lmk::Error.
Landmark read_vdb_landmark(const std::string& path);

/// The format version a file of format 1 to 4 was written in, after the same checks.
int read_vdb_landmark_version(const std::string& path);

/// Writes `landmark` as lmk wrote it before format 5: version 2 for one view without colour or
/// findings, 3 with views or colour, 4 with findings. For the tests that check old files load.
void write_vdb_landmark(const std::string& path, const Landmark& landmark);

}  // namespace lmk::detail
