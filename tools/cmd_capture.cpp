// SPDX-License-Identifier: BSD-3-Clause
// lmk capture SCENE [SCENE...] (--box-center X Y Z --box-rpy R P Y --box-size SX SY SZ |
//             --box-json FILE) --name NAME -o OUT.lmk [--poses FILE] [--register] [--up X Y Z]
//             [--base-frame] [--no-check]: cut a landmark out of a scene with a box, or fuse it
//             from several views of it (landmark/capture_views.h), and check that it is
//             distinctive in the first scene.

#include <cmath>
#include <cstdio>
#include <memory>

#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/pose.h"
#include "lmk/landmark/capture_views.h"
#include "lmk/landmark/depth_correction_file.h"
#include "lmk/landmark/landmark_file.h"
#include "lmk/landmark/slide_check.h"
#include "lmk/search/capture_check.h"
#include "tools/cli_common.h"

namespace lmk::cli {
namespace {

struct CaptureOptions {
  std::vector<std::string> scenes;
  std::string name, output, box_json, poses;
  bool register_views = false;
  std::vector<double> center, rpy_deg, size;
  UpOptions up;
  bool no_check = false;
  std::string depth_correction;
  CaptureSettings settings;
};

Box box_from_options(const CaptureOptions& o) {
  if (!o.box_json.empty()) {
    if (!o.center.empty() || !o.size.empty() || !o.rpy_deg.empty()) {
      throw Error("capture: give the box either with --box-json or with --box-center/--box-size");
    }
    return read_box_json(o.box_json);
  }
  if (o.center.empty() || o.size.empty()) {
    throw Error(
        "capture: the box needs --box-center X Y Z and --box-size SX SY SZ (or --box-json)");
  }
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
  if (!o.rpy_deg.empty())
    rpy = Eigen::Vector3d(o.rpy_deg[0], o.rpy_deg[1], o.rpy_deg[2]) * M_PI / 180.0;
  return Box(pose_from_xyz_rpy({o.center[0], o.center[1], o.center[2]}, rpy),
             {o.size[0], o.size[1], o.size[2]});
}

// The look-alike check's verdict (search/distinctiveness.h): warns on stderr, naming the places,
// when the landmark also matches somewhere else in its own scene, or when the search misses the
// captured instance itself.
void report_look_alikes(const DistinctivenessReport& report, const Landmark& landmark) {
  if (!report.found_itself) {
    std::fprintf(stderr,
                 "warning: the search does not find '%s' in its own capture scene; the landmark "
                 "may have too few points or too little shape to be found reliably\n",
                 landmark.name.c_str());
  }
  if (report.other_instances.empty()) {
    if (report.found_itself) {
      std::printf("check: '%s' is distinctive in its capture scene (%.2f s)\n",
                  landmark.name.c_str(), report.search.stats.seconds_total);
    }
    return;
  }
  std::fprintf(stderr, "warning: '%s' also matches %zu other place%s in its own capture scene:\n",
               landmark.name.c_str(), report.other_instances.size(),
               report.other_instances.size() == 1 ? "" : "s");
  for (const Match& m : report.other_instances) {
    const Eigen::Vector3d c = m.box.center();
    std::fprintf(stderr, "  at %.3f %.3f %.3f m (error %s, coverage %.2f)\n", c.x(), c.y(), c.z(),
                 format_error(m.error, report.search.stats.metric).c_str(), m.terms.coverage());
  }
  std::fprintf(stderr,
               "  a robot could take those for the landmark: draw the box with more context or "
               "more empty margin (--no-check skips this check)\n");
}

// The slide check's verdict (landmark/slide_check.h): warns on stderr, direction by direction,
// when the landmark's own shape lets it slide or turn within the capture frame's noise.
void report_slides(const SlideReport& slides, const Landmark& landmark) {
  const std::vector<std::string> lines = describe_slides(slides, landmark.box);
  if (lines.empty()) {
    std::printf("check: '%s' fixes its pose in every direction\n", landmark.name.c_str());
    return;
  }
  std::fprintf(stderr, "warning: '%s' can move within the sensor's noise:\n",
               landmark.name.c_str());
  for (const std::string& line : lines) std::fprintf(stderr, "  %s\n", line.c_str());
}

// The capture check (search/capture_check.h) in the first view's scene: its findings go into the
// file. --no-check skips the look-alike search, not what needs none (the noise, the slides).
CaptureCheck check_in_capture_scene(const PointCloud& scene, const Landmark& landmark,
                                    bool look_alikes) {
  FindSettings find;
  find.scene.up = landmark.up;  // the capture frame is the scene frame
  return check_capture(landmark, &scene, find, look_alikes);
}

// Where each view's cloud frame lies in the first's (place_views), each registration reported.
std::vector<CaptureView> place(const CaptureOptions& o, const std::vector<PointCloud>& clouds,
                               const Box& box) {
  ViewPlacement placement;
  if (!o.poses.empty()) {
    placement.poses = read_view_poses(o.poses);
    if (placement.poses.size() != clouds.size()) {
      throw Error(o.poses + ": " + std::to_string(placement.poses.size()) + " poses for " +
                  std::to_string(clouds.size()) + " views; give one pose per scene, in order");
    }
  }
  placement.register_views = o.register_views;
  std::vector<const PointCloud*> views;
  for (const PointCloud& cloud : clouds) views.push_back(&cloud);
  return place_views(views, box, placement, [](std::size_t view, const ViewRegistration& r) {
    std::printf(
        "view %zu: registered onto view 1: overlap %.0f%%, residual %.1f mm, moved %.1f mm and "
        "%.2f deg at the box\n",
        view, 100.0 * r.overlap, 1000.0 * r.residual, 1000.0 * r.moved, r.turned * 180.0 / M_PI);
  });
}

int run_capture(CaptureOptions& o) {
  o.settings.up = o.up.vector();
  o.settings.base_frame = o.up.base_frame;
  for (const std::string& scene : o.scenes) format_from_path(scene);
  // Counted before any is read: 500 views were loaded and registered (40 s, 2.45 GB) before the
  // capture said that 16 is the most (issue #47).
  check_capture_settings(o.settings, "capture");
  if (o.scenes.size() > kMaxLandmarkViews) {
    throw Error("capture: " + std::to_string(o.scenes.size()) +
                " views: a landmark holds at most " + std::to_string(kMaxLandmarkViews));
  }
  if (o.scenes.size() == 1 && (!o.poses.empty() || o.register_views)) {
    throw Error("capture: --poses and --register join several views; give more than one scene");
  }
  const Box box = box_from_options(o);  // bad box arguments fail before the scene is read
  std::vector<PointCloud> clouds;
  for (const std::string& scene : o.scenes) {
    clouds.push_back(read_cloud(scene));
    correct_depth(clouds.back(), o.depth_correction);
  }
  Landmark landmark = capture_views(place(o, clouds, box), box, o.name, o.settings);
  const CaptureCheck check = check_in_capture_scene(clouds[0], landmark, !o.no_check);
  landmark.findings = check.findings;
  save_landmark(o.output, landmark);
  std::printf("wrote %s: landmark '%s', %zu points from %zu view%s, box %.3f x %.3f x %.3f m\n",
              o.output.c_str(), landmark.name.c_str(), landmark.points.size(),
              landmark.view_count(), landmark.view_count() == 1 ? "" : "s", box.size.x(),
              box.size.y(), box.size.z());
  if (landmark.settings.allow_flat) {
    std::printf("a flat patch matches wherever it fits: no distinctiveness check\n");
  } else if (!o.no_check) {
    report_look_alikes(*check.look_alikes, landmark);
    report_slides(check.slides, landmark);
  }
  return kOk;
}

}  // namespace

Subcommand add_capture(CLI::App& app) {
  auto o = std::make_shared<CaptureOptions>();
  CLI::App* sub = app.add_subcommand("capture", "Cut a landmark out of a scene with a box");
  sub->add_option("scenes", o->scenes,
                  "Scene cloud (.pcd, .ply, .xyz); several are views of one landmark, fused in the "
                  "first one's frame, where the box is given")
      ->required();
  sub->add_option("--poses", o->poses,
                  "Several views: JSON array of each scene's pose in one common frame "
                  "[{position:[x,y,z], quaternion:[w,x,y,z]}, ...]; without it the views are "
                  "registered onto the first, taken to share its frame");
  sub->add_flag("--register", o->register_views,
                "Several views with --poses: refine the poses by registration onto the first view");
  sub->add_option("--box-center", o->center, "Box centre in the scene frame, m")->expected(3);
  sub->add_option("--box-rpy", o->rpy_deg, "Box roll pitch yaw, degrees (default 0 0 0)")
      ->expected(3);
  sub->add_option("--box-size", o->size, "Box side lengths, m")->expected(3);
  sub->add_option("--box-json", o->box_json,
                  "Box as JSON {position:[x,y,z], quaternion:[w,x,y,z], size:[sx,sy,sz]}");
  sub->add_option("--name", o->name, "Landmark name")->required();
  sub->add_option("-o,--output", o->output, "Landmark file to write (.lmk)")
      ->required()
      ->check(output_extension(".lmk", "a landmark file"));
  add_capture_options(sub, o->settings);
  add_up_options(sub, o->up);
  add_depth_correction_option(sub, o->depth_correction);
  sub->add_flag("--no-check", o->no_check,
                "Skip the distinctiveness check (searching the landmark in its own scene)");
  return {sub, [o] { return run_capture(*o); }};
}

}  // namespace lmk::cli
