// SPDX-License-Identifier: BSD-3-Clause
#include "lmk/pr2/robot_body.h"

#include <algorithm>
#include <limits>
#include <map>
#include <tuple>

#include "lmk/geometry/error.h"

namespace lmk {

namespace {

constexpr int kJointsApartTouching = 3;
constexpr double kClusterCell = 0.08;  // m: the side of the cells a link's solids are grouped by

// The deepest of `a`'s surface points inside `b` grown by `padding`, as a signed distance to b and
// the point (root frame); nothing when none is.
std::optional<std::pair<double, Eigen::Vector3d>> deepest_point(const BodySolid& a,
                                                                const Eigen::Isometry3d& Ta,
                                                                const BodySolid& b,
                                                                const Eigen::Isometry3d& Tb,
                                                                double padding) {
  if (a.solid.kind() == Solid::Kind::sphere) {
    // A sphere against any solid: the solid's signed distance at its centre, less its radius
    // (exact for two spheres, and the common case: a fitted arm).
    const double r = a.solid.size().x();
    const Eigen::Vector3d c = Ta.translation();
    const double d = b.solid.signed_distance(Tb.inverse() * c) - r;
    if (!(d < padding)) return std::nullopt;
    return std::make_pair(d, c);
  }
  const Eigen::Isometry3d T_b_a = Tb.inverse() * Ta;
  std::optional<std::pair<double, Eigen::Vector3d>> best;
  for (const Eigen::Vector3d& s : a.surface) {
    const double d = b.solid.signed_distance(T_b_a * s);
    if (d < padding && (!best || d < best->first)) best = std::make_pair(d, Ta * s);
  }
  return best;
}

bool near_enough(const BodySolid& a, const Eigen::Isometry3d& Ta, const BodySolid& b,
                 const Eigen::Isometry3d& Tb, double padding) {
  const double reach = a.solid.bounding_radius() + b.solid.bounding_radius() + padding;
  return (Ta.translation() - Tb.translation()).squaredNorm() <= reach * reach;
}

}  // namespace

Eigen::Vector3d RobotBody::bounding_sphere(const std::vector<std::size_t>& members,
                                           const Eigen::Isometry3d& frame, double& radius) const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i : members) sum += frame * solids_[i].T_link_solid.translation();
  const Eigen::Vector3d centre = sum / static_cast<double>(members.size());
  radius = 0.0;
  for (std::size_t i : members) {
    radius = std::max(radius, (frame * solids_[i].T_link_solid.translation() - centre).norm() +
                                  solids_[i].solid.bounding_radius());
  }
  return centre;
}

RobotBody::RobotBody(std::shared_ptr<const RobotModel> model, const CollisionShapeSettings& shapes,
                     double surface_spacing,
                     const std::vector<std::pair<std::string, std::string>>& may_touch)
    : model_(std::move(model)) {
  if (!model_) throw Error("robot body: no robot model");
  std::map<std::string, std::size_t> index;
  for (LinkSolid& s : model_->collision_solids(shapes)) {
    const auto [it, added] = index.emplace(s.link, links_.size());
    if (added) links_.push_back(s.link);
    BodySolid b{it->second, s.T_link_solid, s.solid, s.solid.surface_points(surface_spacing)};
    solids_.push_back(std::move(b));
  }
  tree_ = model_->flat_tree();
  for (const BodySolid& s : solids_)
    turned_.push_back(s.T_link_solid.linear() == Eigen::Matrix3d::Identity() ? 0 : 1);
  for (const std::string& link : links_) {
    std::size_t i = 0;
    while (i < tree_.size() && tree_[i].link != link) ++i;
    if (i == tree_.size()) throw Error("robot body: link '" + link + "' is not in the tree");
    at_node_.push_back(i);
  }
  const std::size_t n = links_.size();
  bounds_.resize(n);
  for (std::size_t i = 0; i < solids_.size(); ++i) bounds_[solids_[i].link].solids.push_back(i);
  for (LinkBound& b : bounds_) {
    const Eigen::Isometry3d first = solids_[b.solids[0]].T_link_solid.inverse();
    b.centre = bounding_sphere(b.solids, first, b.radius);
    // The link's solids gathered by cells, each cell's group with a sphere holding it.
    std::map<std::tuple<long, long, long>, std::vector<std::size_t>> cells;
    for (std::size_t i : b.solids) {
      const Eigen::Vector3d c =
          (first * solids_[i].T_link_solid.translation() / kClusterCell).array().floor();
      cells[{static_cast<long>(c.x()), static_cast<long>(c.y()), static_cast<long>(c.z())}]
          .push_back(i);
    }
    for (auto& [key, members] : cells) {
      Cluster cluster;
      cluster.centre = bounding_sphere(members, first, cluster.radius);
      cluster.solids = std::move(members);
      b.clusters.push_back(std::move(cluster));
    }
  }
  allowed_.assign(n * n, 0);
  for (std::size_t i = 0; i < n; ++i) allowed_[i * n + i] = 1;
  // Links up to three joints apart along the tree: their shapes meet at the joints by design (a
  // wrist's links around the short one between them), or the joints' limits keep them apart (the
  // forearm cannot fold into the upper arm past the elbow's limit).
  std::map<std::string, std::string> parent_of;
  for (const RobotModel::TreeJoint& j : model_->tree_joints()) parent_of[j.child] = j.parent;
  for (const auto& [child, first_parent] : parent_of) {
    std::string ancestor = first_parent;
    for (int apart = 1; apart <= kJointsApartTouching; ++apart) {
      const auto i = index.find(child), k = index.find(ancestor);
      if (i != index.end() && k != index.end())
        allowed_[i->second * n + k->second] = allowed_[k->second * n + i->second] = 1;
      const auto up = parent_of.find(ancestor);
      if (up == parent_of.end()) break;
      ancestor = up->second;
    }
  }
  allow_pairs(index, may_touch);
  // Links that touch with every joint at zero touch by design (a shell around a motor).
  const std::vector<Eigen::Isometry3d> zero = place({});
  for (std::size_t i = 0; i < solids_.size(); ++i) {
    for (std::size_t j = 0; j < solids_.size(); ++j) {
      const std::size_t a = solids_[i].link, b = solids_[j].link;
      if (allowed_[a * n + b] || !near_enough(solids_[i], zero[i], solids_[j], zero[j], 0.0))
        continue;
      if (deepest_point(solids_[i], zero[i], solids_[j], zero[j], 0.0))
        allowed_[a * n + b] = allowed_[b * n + a] = 1;
    }
  }
}

void RobotBody::allow_pairs(const std::map<std::string, std::size_t>& index,
                            const std::vector<std::pair<std::string, std::string>>& pairs) {
  const std::size_t n = links_.size();
  for (const auto& [a, b] : pairs) {
    for (const std::string& link : {a, b})
      if (!model_->has_link(link))
        throw Error("robot body: '" + link + "', said to touch '" + (link == a ? b : a) +
                    "' by design, is no link of " + model_->name());
    const auto i = index.find(a), k = index.find(b);
    if (i != index.end() && k != index.end())
      allowed_[i->second * n + k->second] = allowed_[k->second * n + i->second] = 1;
  }
}

std::vector<Eigen::Isometry3d> RobotBody::place(const JointValues& joints) const {
  const std::vector<Eigen::Isometry3d> poses = flat_poses(tree_, flat_values(tree_, joints));
  std::vector<Eigen::Isometry3d> out(solids_.size());
  for (std::size_t l = 0; l < links_.size(); ++l) {
    const Eigen::Isometry3d& T = poses[at_node_[l]];
    for (std::size_t i : bounds_[l].solids) {
      const Eigen::Isometry3d& L = solids_[i].T_link_solid;
      if (turned_[i]) {
        out[i] = T * L;
      } else {  // the same product, without multiplying by the identity
        out[i].linear() = T.linear();
        out[i].translation() = T.linear() * L.translation() + T.translation();
      }
    }
  }
  return out;
}

std::optional<MotionContact> RobotBody::self_contact(const std::vector<Eigen::Isometry3d>& placed,
                                                     const std::vector<char>& moving,
                                                     double padding,
                                                     const std::vector<double>* required,
                                                     std::vector<double>* nearest) const {
  std::optional<MotionContact> best;
  const std::size_t n = links_.size();
  std::vector<Eigen::Vector3d> centre(n);
  for (std::size_t l = 0; l < n; ++l) centre[l] = placed[bounds_[l].solids[0]] * bounds_[l].centre;
  for (std::size_t la = 0; la < n; ++la) {
    if (!moving[la]) continue;
    for (std::size_t lb = 0; lb < n; ++lb) {
      if (allowed_[la * n + lb] || (moving[lb] && lb < la)) continue;
      const double reach = bounds_[la].radius + bounds_[lb].radius + padding;
      if ((centre[la] - centre[lb]).squaredNorm() > reach * reach) continue;
      // Cluster against cluster, then the solids of the pairs of clusters that reach each other.
      for (const Cluster& ca : bounds_[la].clusters) {
        const Eigen::Vector3d a_at = placed[bounds_[la].solids[0]] * ca.centre;
        for (const Cluster& cb : bounds_[lb].clusters) {
          const double r = ca.radius + cb.radius + padding;
          if ((a_at - placed[bounds_[lb].solids[0]] * cb.centre).squaredNorm() > r * r) continue;
          closest_pair(ca.solids, cb.solids, placed, padding, {la, lb}, required, nearest, best);
        }
      }
    }
  }
  return best;
}

void RobotBody::closest_pair(const std::vector<std::size_t>& as, const std::vector<std::size_t>& bs,
                             const std::vector<Eigen::Isometry3d>& placed, double padding,
                             std::pair<std::size_t, std::size_t> links,
                             const std::vector<double>* required, std::vector<double>* nearest,
                             std::optional<MotionContact>& best) const {
  const auto [la, lb] = links;
  // What the pair must keep: the less of what each link must (a link that stays must keep the
  // padding).
  const double need = required ? std::min((*required)[la], (*required)[lb]) : padding;
  for (std::size_t i : as) {
    const BodySolid& a = solids_[i];
    for (std::size_t j : bs) {
      const BodySolid& b = solids_[j];
      if (!near_enough(a, placed[i], b, placed[j], padding)) continue;
      // Both ways: a small solid may lie inside a large one without a point of the large one's
      // surface inside it (a sphere's own measure is exact: once is enough).
      const bool sphere = a.solid.kind() == Solid::Kind::sphere;
      const auto first = deepest_point(a, placed[i], b, placed[j], padding);
      const auto second =
          sphere ? std::nullopt : deepest_point(b, placed[j], a, placed[i], padding);
      for (const auto& hit : {first, second}) {
        if (!hit) continue;
        if (nearest) {
          (*nearest)[la] = std::min((*nearest)[la], hit->first);
          (*nearest)[lb] = std::min((*nearest)[lb], hit->first);
        }
        if (hit->first >= need || (best && hit->first >= best->distance)) continue;
        best = MotionContact{links_[la], "the robot's " + links_[lb], hit->first, hit->second, 0.0};
      }
    }
  }
}

std::vector<char> RobotBody::links_moved_by(const std::string& joint) const {
  const std::map<std::string, Eigen::Isometry3d> still = model_->link_poses({}),
                                                 moved = model_->link_poses({{joint, 0.5}});
  std::vector<char> out(links_.size(), 0);
  for (std::size_t i = 0; i < links_.size(); ++i)
    out[i] = !still.at(links_[i]).isApprox(moved.at(links_[i]), 1e-9);
  return out;
}

}  // namespace lmk
