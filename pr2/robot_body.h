// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A robot's body for collision checking (issue #60): every link's collision solids
// (RobotModel::collision_solids) with points over their surfaces, placed at given joint values,
// and the pairs of links that may touch by design: links up to three joints apart, and links that
// already touch with every joint at zero (a shoulder inside the torso's shell).

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lmk/pbd/motion_check.h"
#include "lmk/pr2/robot_model.h"

namespace lmk {

struct BodySolid {
  std::size_t link = 0;  ///< index into RobotBody::links()
  Eigen::Isometry3d T_link_solid = Eigen::Isometry3d::Identity();
  Solid solid = Solid::sphere(0.01);
  std::vector<Eigen::Vector3d> surface;  ///< solid frame
};

class RobotBody {
 public:
  /// The body of `model`; surface points about `surface_spacing` m apart. `may_touch`: further
  /// pairs of links that touch by design (an SRDF's <disable_collisions>, srdf.h), beside the links
  /// near each other along the tree; a link without collision shapes needs none. Throws lmk::Error
  /// when a collision mesh cannot be read, or for a pair naming a link the model lacks.
  explicit RobotBody(std::shared_ptr<const RobotModel> model,
                     const CollisionShapeSettings& shapes = {}, double surface_spacing = 0.015,
                     const std::vector<std::pair<std::string, std::string>>& may_touch = {});

  /// Links that have solids, by index.
  const std::vector<std::string>& links() const { return links_; }
  const std::vector<BodySolid>& solids() const { return solids_; }
  /// Each solid's pose in the root link's frame at `joints` (others at 0), in solids() order.
  std::vector<Eigen::Isometry3d> place(const JointValues& joints) const;
  /// Whether links a and b (indices) may touch.
  bool may_touch(std::size_t a, std::size_t b) const { return allowed_[a * links_.size() + b]; }
  /// The deepest contact within `padding` between a solid of a link in `moving` (by link index,
  /// nonzero: moving) and any solid of a link it may not touch, at the placement `placed`.
  /// `required` (by link index, none above `padding`): each link's own padding instead, a pair
  /// keeping the less of its two links'. `nearest` (by link index, filled with +infinity by the
  /// caller): each link's nearest approach to another within `padding`.
  std::optional<MotionContact> self_contact(const std::vector<Eigen::Isometry3d>& placed,
                                            const std::vector<char>& moving, double padding,
                                            const std::vector<double>* required = nullptr,
                                            std::vector<double>* nearest = nullptr) const;
  /// The link's solids (indices into solids()), and a sphere holding them all at the placement
  /// `placed`: its centre (root frame) and radius.
  const std::vector<std::size_t>& link_solids(std::size_t link) const {
    return bounds_[link].solids;
  }
  Eigen::Vector3d link_centre(std::size_t link,
                              const std::vector<Eigen::Isometry3d>& placed) const {
    return placed[bounds_[link].solids[0]] * bounds_[link].centre;
  }
  double link_radius(std::size_t link) const { return bounds_[link].radius; }
  /// The links (by index) that move when `joint` does.
  std::vector<char> links_moved_by(const std::string& joint) const;
  const RobotModel& model() const { return *model_; }

 private:
  /// Lets the named pairs of links touch (`index`: each link's index by name); a link without
  /// solids needs nothing. Throws lmk::Error for a name that is no link of the model.
  void allow_pairs(const std::map<std::string, std::size_t>& index,
                   const std::vector<std::pair<std::string, std::string>>& pairs);

  std::shared_ptr<const RobotModel> model_;
  std::vector<FlatLink> tree_;        // the model's tree, for place()
  std::vector<std::size_t> at_node_;  // per link: its index in tree_
  std::vector<char> turned_;  // per solid: turned in its link (most only sit off its origin)
  std::vector<std::string> links_;
  std::vector<BodySolid> solids_;
  std::vector<char> allowed_;  // links x links
  // Per link: its solids, and a sphere holding them all, centred in its first solid's frame: a
  // pair of links whose spheres are apart needs none of their solids' pairs.
  struct Cluster {
    std::vector<std::size_t> solids;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // in the link's first solid's frame
    double radius = 0.0;
  };
  struct LinkBound {
    std::vector<std::size_t> solids;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // in solids[0]'s frame
    double radius = 0.0;
    std::vector<Cluster> clusters;  // the solids grouped by cells, for self contact
  };
  Eigen::Vector3d bounding_sphere(const std::vector<std::size_t>& members,
                                  const Eigen::Isometry3d& frame, double& radius) const;
  void closest_pair(const std::vector<std::size_t>& as, const std::vector<std::size_t>& bs,
                    const std::vector<Eigen::Isometry3d>& placed, double padding,
                    std::pair<std::size_t, std::size_t> links, const std::vector<double>* required,
                    std::vector<double>* nearest, std::optional<MotionContact>& best) const;
  std::vector<LinkBound> bounds_;
};

}  // namespace lmk
