#pragma once
// One self-contained file per landmark, NAME.lmk: an OpenVDB file.
//
// Layout (format version 1):
// - grid "points": a PointDataGrid of the landmark points in the capture frame, with the voxel
//   size of the capture leaf. OpenVDB stores positions relative to voxel centres, which cannot
//   reproduce float coordinates bit for bit, so each point also carries its exact coordinates in
//   the float attribute "capture_position", from which lmk reads them back losslessly.
// - metadata on that grid: lmk_format_version, lmk_name, lmk_box_pose (4x4), lmk_box_size,
//   lmk_sensor_origin, lmk_leaf_size, lmk_min_points, lmk_max_box_side.
// - after the OpenVDB data, a 24-byte lmk trailer: "LMKTRAIL", the data length and its FNV-1a hash.
//   OpenVDB ignores it; lmk checks it before OpenVDB reads anything, since OpenVDB reads some
//   damaged files without error and aborts on others.
// - later versions add the distance and empty-space grids as further grids in the same file.
//
// Writes are atomic. Loading validates the version and every field; a corrupt, truncated or
// foreign file is an lmk::Error naming the file and the problem.

#include <string>
#include <vector>

#include "landmark/landmark.h"

namespace lmk {

void save_landmark(const std::string& path, const Landmark& landmark);
Landmark load_landmark(const std::string& path);

/// Interop: writes OUTDIR/points.pcd and OUTDIR/landmark.json (name, box, sensor origin, capture
/// settings, format version), creating OUTDIR if needed.
void export_landmark(const Landmark& landmark, const std::string& out_dir);
/// The inverse of export_landmark: reads DIR/points.pcd and DIR/landmark.json and validates them.
Landmark import_landmark(const std::string& dir);

/// Names of the grids stored in a .lmk file ("points", and later the distance and empty-space
/// grids), without loading them.
std::vector<std::string> landmark_file_grids(const std::string& path);

/// A box from a JSON file {"position":[x,y,z], "quaternion":[w,x,y,z], "size":[sx,sy,sz]}, the
/// same form as the "box" object of landmark.json. Throws lmk::Error naming the file and field.
Box read_box_json(const std::string& path);

}  // namespace lmk
