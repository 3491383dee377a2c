// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// One self-contained file per landmark, NAME.lmk.
//
// Format 5 (landmark/detail/landmark_record.h, docs/file-formats.md) is lmk's own container: a
// JSON header with the landmark's fields (the same as an export's landmark.json), then the points,
// their views and colours, and the voxels of the box observed free at capture, then a trailer
// with an FNV-1a hash. It stores what the grids are built from: loading rebuilds the distance
// field and the normals from the points, so that a file that loads means what it says.
//
// Formats 1 to 4 were OpenVDB files (landmark/detail/vdb_landmark_file.h). They still load: a
// child process decodes their grids, since behind a valid checksum a forged grid can abort inside
// libopenvdb (issue #61). `lmk landmark upgrade` rewrites them in format 5.
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

/// The format version a .lmk file was written in (1 to 4: OpenVDB files; 5: lmk's container),
/// after the same checks as load_landmark().
int landmark_file_version(const std::string& path);

/// Rewrites a landmark file of format 1 to 4 in format 5, atomically, and returns the version it
/// had; a file of format 5 is left as it is. Loading does not need it: it saves the child process
/// an old file is read in.
int upgrade_landmark_file(const std::string& path);

/// A box from a JSON file {"position":[x,y,z], "quaternion":[w,x,y,z], "size":[sx,sy,sz]}, the
/// same form as the "box" object of landmark.json. Throws lmk::Error naming the file and field.
Box read_box_json(const std::string& path);

/// The poses of a landmark's views (capture_views.h) from a JSON file: an array with one
/// {"position":[x,y,z], "quaternion":[w,x,y,z]} per view, each the pose of that view's cloud frame
/// in one common frame (a sequence's world, a robot's odometry). Throws lmk::Error naming the file
/// and the entry.
std::vector<Eigen::Isometry3d> read_view_poses(const std::string& path);

}  // namespace lmk
