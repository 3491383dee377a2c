// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/search/confidence/match_confidence.h"

#include <cmath>
#include <cstdio>

#include "lmk/geometry/pose.h"

namespace lmk {
namespace {

// A rival within this many error sigmas of the match is as good as it within the noise; within
// kCloseSigmas it is close enough to be the doubt a person should hear first.
constexpr double kWithinNoiseSigmas = 3.0;
constexpr double kCloseSigmas = 6.0;
// A match using more than this share of the empty-space allowance has something in its free space
// (flying pixels stay well under it).
constexpr double kIntrusionDoubt = 0.25;

std::string format(const char* pattern, double a) {
  char text[160];
  std::snprintf(text, sizeof(text), pattern, a);
  return text;
}

// "fits within the noise" or "fits 4.2 error sigmas worse".
std::string how_close(double margin) {
  if (margin < kWithinNoiseSigmas) return "fits within the noise";
  return format("fits only %.1f error sigmas worse", margin);
}

std::string describe_competitor(const MatchConfidence& c, const Box& box) {
  const Competitor& rival = c.competitor;
  const double margin = c.margin;
  switch (rival.kind) {
    case Competitor::Kind::slide: {
      const Eigen::Vector3d along = (rival.box.center() - box.center()).normalized();
      return format("a pose %.0f cm along ", rival.distance * 100.0) + describe_axis(along, box) +
             " " + how_close(margin);
    }
    case Competitor::Kind::turn: {
      const Eigen::AngleAxisd turn(box.pose.linear().transpose() * rival.box.pose.linear());
      const Eigen::Vector3d axis = box.pose.linear() * turn.axis();
      return format("a pose turned %.0f degrees about ", rival.angle * 180.0 / M_PI) +
             describe_axis(axis, box) + " " + how_close(margin);
    }
    case Competitor::Kind::look_alike:
      return format("a look-alike %.0f cm away ", rival.distance * 100.0) +
             (margin < kWithinNoiseSigmas ? std::string("scores the same")
                                          : format("scores only %.1f error sigmas worse", margin));
    case Competitor::Kind::none:
      break;
  }
  return "";
}

}  // namespace

const std::vector<std::string>& setting_names(Competitor::Kind) {
  static const std::vector<std::string> names = {"none", "slide", "turn", "look-alike"};
  return names;
}

std::string describe_doubt(const MatchConfidence& c, const Box& box) {
  // The first doubt that holds, in the order a person can act on: free space the sensor cannot
  // confirm (look from elsewhere), a rival pose (widen the box, look again), then a pose free to
  // move, then too little seen, then a poor fit.
  if (c.free_space_unconfirmed) {
    return format("only %.0f%% of the space its box says is free is seen free",
                  std::floor(c.free_space_seen * 100.0)) +
           " (the rest is hidden or returned nothing)";
  }
  if (c.competitor.kind != Competitor::Kind::none && c.margin < kCloseSigmas) {
    return describe_competitor(c, box);
  }
  if (c.freedom > kSamePoseDistance) {
    const std::string amount =
        std::isinf(c.freedom) ? std::string("freely") : format("%.0f cm", c.freedom * 100.0);
    return std::string(c.freest.turn ? "it turns " : "it slides ") + amount +
           (c.freest.turn ? " about " : " along ") + describe_axis(c.freest.axis, box) +
           " within the noise";
  }
  if (c.coverage < 0.7) {
    return format("only %.0f%% of the landmark is seen", c.coverage * 100.0);
  }
  if (c.intrusion > kIntrusionDoubt) return "something stands in the space its box says is free";
  if (c.competitor.kind != Competitor::Kind::none) return describe_competitor(c, box);
  return format("its error is %.1f times the depth noise at ", c.fit) + format("%.1f m", c.range);
}

}  // namespace lmk
