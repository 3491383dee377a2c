// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// One self-contained file per landmark, NAME.lmk: an OpenVDB file.
//
// Layout (format version 2):
// - grid "points": a PointDataGrid of the landmark points in the capture frame, with the voxel
//   size of the capture leaf. OpenVDB stores positions relative to voxel centres, which cannot
//   reproduce float coordinates bit for bit, so each point also carries its exact coordinates in
//   the float attribute "capture_position", from which lmk reads them back losslessly.
// - metadata on that grid: lmk_format_version, lmk_name, lmk_box_pose (4x4), lmk_box_size,
//   lmk_sensor_origin, lmk_leaf_size, lmk_min_points, lmk_max_box_side.
// - after the OpenVDB data, a 24-byte lmk trailer: "LMKTRAIL", the data length and its FNV-1a hash.
//   OpenVDB ignores it; lmk checks it before OpenVDB reads anything, since OpenVDB reads some
//   damaged files without error and aborts on others.
//   Version 2 adds lmk_up, lmk_distance_band and lmk_empty_space_margin, and the int attribute
//   "capture_index": each point's index in the landmark, which OpenVDB's voxel order loses and
//   the closest-point grid below refers to.
// - grids "distance" (FloatGrid) and "closest" (Int32Grid): the landmark's distance field, whose
//   closest-point indices refer to the points in file order; "empty" (BoolGrid): the voxels of the
//   box observed free at capture. Version 1 files have none of these: loading upgrades them by
//   recomputing the grids from the points (rays to the landmark's own points only).
//
// Writes are atomic. Loading validates the version and every field; a corrupt, truncated or
// foreign file is an lmk::Error naming the file and the problem.

#include <string>
#include <vector>

#include "lmk/landmark/landmark.h"

namespace lmk {

void save_landmark(const std::string& path, const Landmark& landmark);
Landmark load_landmark(const std::string& path);

/// Interop: writes OUTDIR/points.pcd and OUTDIR/landmark.json (name, box, sensor origin, capture
/// settings, format version), creating OUTDIR if needed.
void export_landmark(const Landmark& landmark, const std::string& out_dir);
/// The inverse of export_landmark: reads DIR/points.pcd and DIR/landmark.json and validates them.
Landmark import_landmark(const std::string& dir);

/// Names of the grids stored in a .lmk file ("points", "distance", "closest", "empty"), without
/// loading them.
std::vector<std::string> landmark_file_grids(const std::string& path);

/// The format version a .lmk file was written in (2: one view, as lmk wrote before landmarks of
/// several views existed; 3: several views), after the same checks as load_landmark().
int landmark_file_version(const std::string& path);

/// A box from a JSON file {"position":[x,y,z], "quaternion":[w,x,y,z], "size":[sx,sy,sz]}, the
/// same form as the "box" object of landmark.json. Throws lmk::Error naming the file and field.
Box read_box_json(const std::string& path);

/// The poses of a landmark's views (capture_views.h) from a JSON file: an array with one
/// {"position":[x,y,z], "quaternion":[w,x,y,z]} per view, each the pose of that view's cloud frame
/// in one common frame (a sequence's world, a robot's odometry). Throws lmk::Error naming the file
/// and the entry.
std::vector<Eigen::Isometry3d> read_view_poses(const std::string& path);

}  // namespace lmk
