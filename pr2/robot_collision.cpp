// SPDX-License-Identifier: BSD-3-Clause
// RobotModel's collision side (issue #60): the links' poses over the whole tree, their <collision>
// shapes as solids, and which links are joined.

#include <algorithm>
#include <filesystem>
#include <functional>

#include "lmk/geometry/error.h"
#include "lmk/geometry/stl_mesh.h"
#include "lmk/pr2/internal/robot_model_impl.h"

namespace lmk {

namespace {

// The file a <mesh filename> names: package://NAME/PATH in NAME's folder (settings.package_path),
// else in settings.package_dir, file://PATH, or a path relative to the URDF's directory.
std::string mesh_path(const std::string& uri, const CollisionShapeSettings& settings,
                      const std::string& urdf_dir) {
  const std::string package = "package://", file = "file://";
  if (uri.rfind(package, 0) == 0) {
    const std::size_t slash = uri.find('/', package.size());
    const std::string rest = slash == std::string::npos ? "" : uri.substr(slash + 1);
    const std::string name = uri.substr(package.size(), slash - package.size());
    std::string dir = settings.package_path ? settings.package_path(name) : "";
    if (dir.empty()) dir = settings.package_dir.empty() ? urdf_dir : settings.package_dir;
    return (std::filesystem::path(dir) / rest).string();
  }
  if (uri.rfind(file, 0) == 0) return uri.substr(file.size());
  return (std::filesystem::path(urdf_dir) / uri).string();
}

// Spheres covering the mesh, as solids in the link frame.
void add_mesh(const urdf::Mesh& m, const std::string& link, const Eigen::Isometry3d& T_link_shape,
              const std::string& path, const CollisionShapeSettings& settings,
              std::vector<LinkSolid>& out) {
  std::string lower = path;
  std::transform(lower.begin(), lower.end(), lower.begin(), ::tolower);
  if (lower.size() < 4 || lower.substr(lower.size() - 4) != ".stl") {
    throw Error("link '" + link + "': collision mesh '" + path +
                "' is not an STL file (lmk reads STL collision meshes)");
  }
  const Eigen::Vector3d scale(m.scale.x, m.scale.y, m.scale.z);
  const std::vector<Eigen::Vector3d> surface =
      mesh_surface_points(read_stl_mesh(path), 0.5 * settings.mesh_cell, scale);
  for (const CoveringSphere& s : cover_with_spheres(surface, settings.mesh_cell)) {
    out.push_back({link, T_link_shape * Eigen::Translation3d(s.centre), Solid::sphere(s.radius)});
  }
}

}  // namespace

std::string RobotModel::root_link() const { return impl_->model->getRoot()->name; }

std::vector<FlatLink> RobotModel::flat_tree() const {
  std::vector<FlatLink> tree;
  // Depth first: a link is pushed before its children, which find it as the last one pushed.
  const std::function<void(const urdf::Link&)> walk = [&](const urdf::Link& link) {
    const int self = static_cast<int>(tree.size() - 1);
    for (const urdf::JointSharedPtr& j : link.child_joints) {
      const urdf::LinkConstSharedPtr child = impl_->model->getLink(j->child_link_name);
      if (!child) continue;
      FlatLink f;
      f.link = child->name;
      f.joint = j->name;
      f.parent = self;
      f.T_parent_joint = detail::to_eigen(j->parent_to_joint_origin_transform);
      const Eigen::Vector3d axis(j->axis.x, j->axis.y, j->axis.z);
      const bool turns = j->type == urdf::Joint::REVOLUTE || j->type == urdf::Joint::CONTINUOUS;
      if (axis.norm() > 0.0 && (turns || j->type == urdf::Joint::PRISMATIC)) {
        f.motion = turns ? FlatLink::Motion::kRevolute : FlatLink::Motion::kPrismatic;
        f.axis = axis.normalized();
      }  // else fixed (and floating or planar, which a robot's tree holds still here)
      tree.push_back(std::move(f));
      walk(*child);
    }
  };
  FlatLink root;
  root.link = impl_->model->getRoot()->name;
  tree.push_back(root);
  walk(*impl_->model->getRoot());
  return tree;
}

std::vector<Eigen::Isometry3d> flat_poses(const std::vector<FlatLink>& tree,
                                          const std::vector<double>& values) {
  std::vector<Eigen::Isometry3d> poses(tree.size());
  for (std::size_t i = 0; i < tree.size(); ++i) {
    const FlatLink& f = tree[i];
    if (f.parent < 0) {
      poses[i] = Eigen::Isometry3d::Identity();
      continue;
    }
    poses[i] = poses[static_cast<std::size_t>(f.parent)] * f.T_parent_joint;
    if (f.motion == FlatLink::Motion::kRevolute)
      poses[i].rotate(Eigen::AngleAxisd(values[i], f.axis));
    else if (f.motion == FlatLink::Motion::kPrismatic)
      poses[i].translate(f.axis * values[i]);
  }
  return poses;
}

std::vector<double> flat_values(const std::vector<FlatLink>& tree,
                                const std::map<std::string, double>& joints) {
  std::vector<double> values(tree.size(), 0.0);
  for (std::size_t i = 0; i < tree.size(); ++i) {
    if (tree[i].motion == FlatLink::Motion::kFixed) continue;
    const auto value = joints.find(tree[i].joint);
    if (value != joints.end()) values[i] = value->second;
  }
  return values;
}

std::map<std::string, Eigen::Isometry3d> RobotModel::link_poses(
    const std::map<std::string, double>& joints) const {
  for (const auto& [name, value] : joints) {
    if (!impl_->model->getJoint(name)) throw Error(impl_->what + ": no joint named '" + name + "'");
  }
  const std::vector<FlatLink> tree = flat_tree();
  const std::vector<Eigen::Isometry3d> placed = flat_poses(tree, flat_values(tree, joints));
  std::map<std::string, Eigen::Isometry3d> poses;
  for (std::size_t i = 0; i < tree.size(); ++i) poses[tree[i].link] = placed[i];
  return poses;
}

std::vector<LinkSolid> RobotModel::collision_solids(const CollisionShapeSettings& settings) const {
  std::vector<urdf::LinkSharedPtr> links;
  impl_->model->getLinks(links);
  std::sort(links.begin(), links.end(),
            [](const auto& a, const auto& b) { return a->name < b->name; });
  std::vector<LinkSolid> out;
  const std::vector<std::string>& only = settings.only_links;
  for (const urdf::LinkSharedPtr& link : links) {
    if (!only.empty() && std::find(only.begin(), only.end(), link->name) == only.end()) continue;
    for (const urdf::CollisionSharedPtr& c : link->collision_array) {
      if (!c || !c->geometry) continue;
      const Eigen::Isometry3d T = detail::to_eigen(c->origin);
      const urdf::Geometry& g = *c->geometry;
      switch (g.type) {
        case urdf::Geometry::BOX: {
          const auto& b = static_cast<const urdf::Box&>(g);
          out.push_back({link->name, T, Solid::box({b.dim.x, b.dim.y, b.dim.z})});
          break;
        }
        case urdf::Geometry::CYLINDER: {
          const auto& cyl = static_cast<const urdf::Cylinder&>(g);
          out.push_back({link->name, T, Solid::cylinder(cyl.radius, cyl.length)});
          break;
        }
        case urdf::Geometry::SPHERE:
          out.push_back({link->name, T, Solid::sphere(static_cast<const urdf::Sphere&>(g).radius)});
          break;
        case urdf::Geometry::MESH: {
          const auto& m = static_cast<const urdf::Mesh&>(g);
          add_mesh(m, link->name, T, mesh_path(m.filename, settings, impl_->dir), settings, out);
          break;
        }
      }
    }
  }
  return out;
}

std::vector<RobotModel::TreeJoint> RobotModel::tree_joints() const {
  std::vector<TreeJoint> out;
  for (const auto& [name, joint] : impl_->model->joints_)
    out.push_back({name, joint->parent_link_name, joint->child_link_name});
  return out;
}

}  // namespace lmk
