#include "contact_points.hpp"

#include <algorithm>
#include <limits>

#include "wbi/model/kinematics.hpp"

namespace wbi::sim {

using Eigen::Vector3d;
using sim_models::SimPlan;

std::vector<ContactPoint> contact_points(const RobotConfig& c, const SimPlan& plan) {
  std::vector<ContactPoint> points;
  for (std::size_t k = 0; k < plan.contact_link_of.size(); ++k) {
    const robot_config::ContactGeometry& g = c.contacts[k];
    const int link = plan.contact_link_of[k];
    auto add = [&](const Vector3d& p_F, double radius) {
      ContactPoint cp;
      cp.link = link;
      cp.frame = plan.contact_link_frames[static_cast<std::size_t>(link)];
      cp.p_F = p_F;
      cp.radius = radius;
      cp.friction = g.friction;
      points.push_back(cp);
    };
    switch (g.shape) {
      case wbi::ContactShape::box:
        for (int sx : {1, -1}) {
          for (int sy : {1, -1}) {
            add(g.position + g.rotation * Vector3d(0.5 * sx * g.size.x(), 0.5 * sy * g.size.y(),
                                                   -0.5 * g.size.z()),
                0.0);
          }
        }
        break;
      case wbi::ContactShape::sphere:
        add(g.position, g.radius);
        break;
      case wbi::ContactShape::capsule:
        for (int sz : {1, -1}) {
          add(g.position + g.rotation * Vector3d(0.0, 0.0, 0.5 * sz * g.length), g.radius);
        }
        break;
    }
  }
  return points;
}

double height_above_ground(const model::Model& m, model::Data& kinematics, const Eigen::VectorXd& q,
                           const std::vector<ContactPoint>& points, double ground) {
  model::forward_kinematics(m, kinematics, q);
  double z_min = std::numeric_limits<double>::infinity();
  for (const auto& cp : points) {
    const auto fi = static_cast<std::size_t>(cp.frame);
    const auto b = static_cast<std::size_t>(m.frame_body[fi]);
    const Vector3d p =
        kinematics.p_WB[b] + kinematics.R_WB[b] * (m.frame_R_BF[fi] * cp.p_F + m.frame_p_BF[fi]);
    z_min = std::min(z_min, p.z() - cp.radius);
  }
  return z_min - ground;
}

}  // namespace wbi::sim
