// SPDX-License-Identifier: BSD-3-Clause
// lmk track FRAMES... LANDMARK.lmk [LANDMARK.lmk...]: landmarks followed through a stream of frames
// (search/tracker.h), frame by frame as they are read, with a line per frame and landmark, JSON
// lines with --json, and a summary at the end.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "lmk/geometry/atomic_file.h"
#include "lmk/geometry/cloud_io.h"
#include "lmk/geometry/error.h"
#include "lmk/geometry/settings_schema.h"
#include "lmk/geometry/statistics.h"
#include "lmk/landmark/depth_correction_file.h"
#include "lmk/landmark/landmark_file.h"
#include "lmk/search/internal/track_json.h"
#include "lmk/search/tracker.h"
#include "tools/bag_input.h"
#include "tools/cli_common.h"

namespace lmk::cli {
namespace {

namespace fs = std::filesystem;

struct TrackOptions {
  std::vector<std::string> inputs;  ///< frames and directories of frames, and the landmarks
  std::string json, depth_correction;
  bool timings = false;
  TrackSettings settings;
  BagOptions bag;  ///< a bag's topic, frame, and the time to start from
};

bool is_landmark_file(const fs::path& p) { return p.extension() == ".lmk"; }

// The frames named: files in the order given, each directory's cloud files by name.
std::vector<std::string> frame_files(const std::vector<std::string>& inputs) {
  std::vector<std::string> frames;
  for (const std::string& input : inputs) {
    if (is_landmark_file(input)) continue;
    if (!fs::is_directory(input)) {
      format_from_path(input);  // a file of another kind is refused before anything is read
      frames.push_back(input);
      continue;
    }
    std::vector<std::string> in_dir;
    for (const fs::directory_entry& e : fs::directory_iterator(input)) {
      if (!e.is_regular_file()) continue;
      try {
        format_from_path(e.path().string());
        in_dir.push_back(e.path().string());
      } catch (const Error&) {
        // not a cloud: another file of the directory (poses, images)
      }
    }
    if (in_dir.empty()) throw Error(input + ": holds no cloud file (.pcd, .ply, .xyz)");
    std::sort(in_dir.begin(), in_dir.end());
    frames.insert(frames.end(), in_dir.begin(), in_dir.end());
  }
  if (frames.empty()) throw Error("track: give the frames (cloud files or directories of them)");
  return frames;
}

nlohmann::json to_json(std::size_t frame, const std::string& file, const TrackedLandmark& t) {
  nlohmann::json j = detail::tracked_landmark_to_json(t);
  j["frame"] = frame;
  j["file"] = file;
  return j;
}

void print_line(std::size_t frame, const std::string& file, const TrackedLandmark& t,
                const ErrorMetric& metric) {
  std::printf("frame %zu %s: '%s' %s", frame, printable(file, kMaxPrintedPath).c_str(),
              printable(t.name).c_str(), to_string(t.state));
  if (t.match) {
    const Eigen::Vector3d c = t.match->box.center();
    std::printf(" at %.4f %.4f %.4f, error %s", c.x(), c.y(), c.z(),
                format_error(t.match->error, metric).c_str());
  } else {
    std::printf(" (%s)", to_string(t.lost_because).c_str());
  }
  std::printf(", %.1f ms\n", 1e3 * t.seconds);
}

// The one bag among the inputs, or "" when the frames are cloud files; a bag with other frames,
// or a second bag, is refused.
std::string bag_of(const std::vector<std::string>& inputs) {
  std::string bag;
  std::size_t frames = 0;
  for (const std::string& input : inputs) {
    if (is_landmark_file(input)) continue;
    ++frames;
    if (is_bag(input)) bag = input;
  }
  if (!bag.empty() && frames > 1)
    throw Error("track: give one bag, or cloud files and directories, not both");
  return bag;
}

// The frames to follow, one at a time and in order, each with the name it is reported by: the
// files and directories given, or the frames of a bag from --time on.
void for_each_frame(const TrackOptions& o,
                    const std::function<void(PointCloud&, const std::string&, bool)>& visit) {
  const std::string bag = bag_of(o.inputs);
  if (bag.empty()) {
    for (const std::string& file : frame_files(o.inputs)) {
      PointCloud frame = read_cloud(file);
      correct_depth(frame, o.depth_correction);
      visit(frame, fs::path(file).filename().string(), false);
    }
    return;
  }
  if (!o.depth_correction.empty())
    throw Error("track: --depth-correction applies to cloud files, not to a bag's frames");
  std::size_t k = 0;
  const std::string name = fs::path(bag).filename().string();
  for_each_bag_scene(bag, o.bag, [&](PointCloud& scene, bool in_base_frame) {
    visit(scene, name + "#" + std::to_string(k++), in_base_frame);
    return true;
  });
  if (k == 0) throw Error(bag + ": no frame from " + std::to_string(o.bag.time) + " s on");
}

int run_track(TrackOptions& o) {
  std::vector<std::shared_ptr<const Landmark>> landmarks;
  for (const std::string& input : o.inputs) {
    if (is_landmark_file(input))
      landmarks.push_back(std::make_shared<Landmark>(load_landmark(input)));
  }
  if (landmarks.empty()) throw Error("track: give at least one landmark file (.lmk)");
  std::optional<Tracker> tracker;  // built at the first frame, which says the scene's frame
  const ErrorMetric& metric = find_error_metric(o.settings.find.resolved().selection.metric);

  std::string json_lines;
  std::vector<double> frame_seconds;
  struct Counts {
    std::size_t tracking = 0, lost = 0, losses = 0, found_again = 0;
    bool was_lost = false;
  };
  std::vector<Counts> counts(landmarks.size());
  std::size_t f = 0;
  for_each_frame(o, [&](PointCloud& frame, const std::string& name, bool in_base_frame) {
    if (!tracker) {
      // A bag's frames in base_link: +z is up there.
      if (in_base_frame) o.settings.find.scene.base_frame = true;
      tracker.emplace(landmarks, o.settings);
    }
    const std::vector<TrackedLandmark> now = tracker->update(frame);
    double seconds = 0.0;
    for (std::size_t i = 0; i < now.size(); ++i) {
      const TrackedLandmark& t = now[i];
      seconds += t.seconds;
      Counts& c = counts[i];
      if (t.state == TrackState::tracking) ++c.tracking;
      if (t.state == TrackState::found_again) ++c.found_again;
      if (t.state == TrackState::lost) {
        ++c.lost;
        if (!c.was_lost) ++c.losses;
      }
      c.was_lost = t.state == TrackState::lost;
      if (o.json != "-") print_line(f, name, t, metric);
      if (o.json.empty()) continue;
      const std::string line = json_output(to_json(f, name, t), o.timings).dump() + "\n";
      if (o.json == "-") {
        std::cout << line << std::flush;  // as it happens: a bag may be long
      } else {
        json_lines += line;
      }
    }
    frame_seconds.push_back(seconds);
    ++f;
  });
  if (!o.json.empty() && o.json != "-") write_text_atomically(o.json, json_lines);
  FILE* summary = o.json == "-" ? stderr : stdout;
  std::fprintf(summary, "tracked %zu frames; per frame median %.1f ms, 95th percentile %.1f ms\n",
               f, 1e3 * percentile(frame_seconds, 0.5), 1e3 * percentile(frame_seconds, 0.95));
  for (std::size_t i = 0; i < landmarks.size(); ++i) {
    const Counts& c = counts[i];
    std::fprintf(
        summary,
        "  '%s': followed in %zu frames, lost in %zu (%zu losses), found again %zu times\n",
        landmarks[i]->name.c_str(), c.tracking, c.lost, c.losses, c.found_again);
  }
  return kOk;
}

}  // namespace

Subcommand add_track(CLI::App& app) {
  auto o = std::make_shared<TrackOptions>();
  CLI::App* sub = app.add_subcommand(
      "track", "Follow landmarks through a sequence of frames: where each is in every frame");
  sub->add_option("inputs", o->inputs,
                  "FRAME... LANDMARK.lmk...: cloud files (.pcd, .ply, .xyz) in order, or "
                  "directories of them (taken by name), and the landmarks to follow")
      ->required()
      ->expected(2, -1);
  add_track_options(sub, o->settings);
  add_depth_correction_option(sub, o->depth_correction);
  add_bag_options(sub, o->bag, false);
  sub->add_option("--time", o->bag.time,
                  "With a bag: seconds from its start; its frames are followed from there")
      ->check(within(0.0, 1e6))
      ->capture_default_str();
  sub->add_option("--json", o->json,
                  "Write a JSON line per frame and landmark (frame, file, landmark, state, "
                  "position, quaternion, error, confidence or lost_because) to FILE, or - for "
                  "stdout");
  add_timings_flag(sub, o->timings);
  return {sub, [o] { return run_track(*o); }};
}

}  // namespace lmk::cli
