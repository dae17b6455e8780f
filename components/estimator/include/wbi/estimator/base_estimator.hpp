// Base pose and mixed velocity/acceleration of a floating-base robot from its
// joint state, assuming one link is fixed in the world (e.g. the stance foot's
// sole), as the original whole-body interface did:
//   world_H_base = world_H_link · (base_H_link(q))⁻¹
//   J_link ν = 0          ⇒  ν_B  = −J_B⁻¹ J_j q̇            (J = [J_B J_j], 6×6 and 6×n)
//   J_link ν̇ + J̇ν = 0    ⇒  ν̇_B = −J_B⁻¹ (J_j q̈ + J̇ν)
// The link's world pose is fixed when estimation starts (from an initial base
// pose) and when the link is switched (from the current estimate), so the base
// pose stays continuous. Allocates nothing per update after construction.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <wbi/model/data.hpp>
#include <wbi/model/model.hpp>

namespace wbi::estimator {

struct BaseState {
  Eigen::Matrix4d world_H_base = Eigen::Matrix4d::Identity();
  Eigen::Matrix<double, 6, 1> velocity = Eigen::Matrix<double, 6, 1>::Zero();      // mixed
  Eigen::Matrix<double, 6, 1> acceleration = Eigen::Matrix<double, 6, 1>::Zero();  // its derivative
};

class FixedLinkBaseEstimator {
 public:
  // urdf: the robot's model; joints: the robot's joint order (as in its
  // description); link: the link (frame) assumed fixed; initial_world_H_base:
  // the base pose at the first update. Throws std::invalid_argument naming an
  // unknown link or joint, or a fixed-base model.
  FixedLinkBaseEstimator(const std::string& urdf, const std::vector<std::string>& joints,
                         const std::string& link, const Eigen::Matrix4d& initial_world_H_base);

  // q, dq, ddq: joint positions, velocities, accelerations in the robot's order.
  const BaseState& update(const Eigen::Ref<const Eigen::VectorXd>& q,
                          const Eigen::Ref<const Eigen::VectorXd>& dq,
                          const Eigen::Ref<const Eigen::VectorXd>& ddq);

  // Switches the fixed link; its world pose is taken from the current estimate.
  void set_fixed_link(const std::string& link);
  const std::string& fixed_link() const;

 private:
  Eigen::Matrix4d link_in_base(const Eigen::Ref<const Eigen::VectorXd>& q);

  wbi::model::Model model_;
  wbi::model::Data data_;
  int link_ = 0;
  bool started_ = false;
  Eigen::Matrix4d world_H_link_ = Eigen::Matrix4d::Identity();
  Eigen::VectorXd q_model_;  // [nq]
  Eigen::VectorXd nu_;       // [nv]
  BaseState state_;
};

}  // namespace wbi::estimator
