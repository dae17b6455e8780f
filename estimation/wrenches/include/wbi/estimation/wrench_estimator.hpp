// Joint torques and external wrenches from six-axis F/T sensors, through the
// model: what a robot without joint-torque sensors (iCub) knows of its torques.
//
// Formulation (the "external wrenches and joint torques" estimator of
// wholeBodyDynamics / iDynTree: Nori et al., "iCub whole-body control through
// force regulation on rigid non-coplanar contacts", Front. Robot. AI 2015;
// Traversaro, PhD thesis, 2017, ch. 5):
//
// 1. The link tree is cut at the F/T sensors' fixed joints into submodels.
//    A measured wrench is a boundary wrench of the two submodels it joins:
//    w_s acts on the parent side, −w_s on the child side (sensors.idl: the
//    wrench the child side exerts on the parent side).
// 2. Newton–Euler of submodel k, world axes about the world origin:
//      Σ_{links l ∈ k} (I_l a_l + v_l ×* I_l v_l) = Σ_{h ∈ k} X_h x_h + Σ_{s ∂ k} ±W_s
//    (a_l includes −g, RBDA §5.3), with x_h = (force, moment about the link
//    origin) the unknown wrench at hypothesis link h and X_h = [1 0; [p_h]× 1]
//    its transport to the world origin. Six equations per submodel.
// 3. One hypothesis: x_h = X_h⁻¹ b_k exactly. Several: the minimum-norm
//    solution x = Aᵀ(A Aᵀ)⁻¹ b_k (A = [X_h …], 6 × 6m, full row rank), so
//    that the submodel's balance holds exactly and nothing is invented where
//    the data cannot tell hypotheses apart. Each x_h is about its own link's
//    origin, so the norm weighs wrenches where they act, not about the world
//    origin. Chosen over a weighted or sign-constrained solution because it is
//    allocation-free, closed-form and exact when each submodel has one contact.
// 4. Joint torques: RNEA on the whole model with the estimated wrenches. As
//    every submodel is balanced, the wrench it transmits through each sensor
//    equals the measured one, so τ_j uses the sensors nearest to joint j;
//    the base rows of the result are the overall residual (zero up to
//    rounding: base_residual()).
//
// A hypothesis is "loaded" once its force exceeds contact_on_force and until
// it falls below contact_off_force (hysteresis); a link may have its own pair
// (a chest whose estimate has a background of several newtons). A NaN, infinite or saturated
// reading marks both submodels of its sensor invalid: their wrenches are
// zeroed and flagged, and so is every joint torque whose subtree holds one of
// them. Outputs never carry NaN.
#pragma once

#include <cstdint>
#include <limits>
#include <map>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "wbi/model/data.hpp"
#include "wbi/model/model.hpp"

namespace wbi::estimation {

using model::Matrix3d;
using model::Vector3d;
using model::Vector6d;

// A six-axis F/T sensor at a fixed joint of the URDF; its frame is the joint's
// child link, its reading the wrench the child side exerts on the parent side.
struct ForceTorqueSensor {
  std::string name;
  std::string joint;
};

struct WrenchEstimatorOptions {
  std::vector<ForceTorqueSensor> sensors;
  // Wrench hypotheses: links where the environment may push (contacts with the
  // ground), then any extra ones (a chest, a hand). Every submodel needs one.
  std::vector<std::string> contact_links;
  std::vector<std::string> extra_links;
  Vector3d gravity{0.0, 0.0, -9.81};
  double contact_on_force = 10.0;  // [N] a hypothesis becomes loaded above this force
  double contact_off_force = 5.0;  // [N] and unloaded below this one
  // Per hypothesis link, instead of the two above (either may be given alone).
  std::map<std::string, double> link_on_force;
  std::map<std::string, double> link_off_force;
  // A reading with a force (torque) component at or beyond these is saturated.
  double force_limit = std::numeric_limits<double>::infinity();   // [N]
  double torque_limit = std::numeric_limits<double>::infinity();  // [N·m]
};

// One part of the robot between F/T sensors.
struct Submodel {
  std::string name;                 // its link nearest the root
  std::vector<std::string> links;   // every URDF link in it
  std::vector<int> hypotheses;      // indices into WrenchEstimator::link_names()
  std::vector<int> parent_sensors;  // sensors it is the parent side of
  std::vector<int> child_sensors;   // sensors it is the child side of
};

class WrenchEstimator {
 public:
  // Throws std::invalid_argument with one message naming every problem: unknown
  // or movable sensor joints, unknown or repeated links, submodels with no
  // hypothesis, contact_off_force > contact_on_force (also per link), a
  // per-link threshold on a link that is no hypothesis.
  WrenchEstimator(const model::Model& model, WrenchEstimatorOptions options);

  // One tick. q [nq], nu [nv], dnu [nv] as in the model library; readings
  // [n_sensors] (force, torque about the sensor origin), sensor axes, in the
  // order of options.sensors. Never allocates.
  void update(const model::ConstVectorRef& q, const model::ConstVectorRef& nu,
              const model::ConstVectorRef& dnu, std::span<const Vector6d> readings);

  // ---- results of the last update() ----
  const Eigen::VectorXd& joint_torques() const { return joint_torques_; }  // [n_joints] model order
  bool joint_torque_valid(int joint) const { return joint_valid_[joint] != 0; }
  // Wrench the environment exerts on hypothesis link h: (force, moment about
  // the link origin), world axes.
  const Vector6d& link_wrench(int h) const { return wrenches_[h].wrench; }
  // Every hypothesis' wrench at its link frame, as model::forward_dynamics takes them.
  std::span<const model::ExternalWrench> link_wrenches() const { return wrenches_; }
  bool link_wrench_valid(int h) const { return hypothesis_valid_[h] != 0; }
  bool loaded(int h) const { return loaded_[h] != 0; }
  bool reading_valid(int s) const { return reading_valid_[s] != 0; }
  // Base rows of the torque RNEA (mixed base wrench): what the estimated
  // wrenches leave unexplained, zero up to rounding when every reading is valid.
  const Vector6d& base_residual() const { return base_residual_; }

  // ---- structure ----
  const std::vector<std::string>& link_names() const { return link_names_; }  // the hypotheses
  bool is_contact_link(int h) const { return h < n_contacts_; }
  const std::vector<Submodel>& submodels() const { return submodels_; }
  int n_sensors() const { return static_cast<int>(sensor_frames_.size()); }
  const model::Model& model() const { return model_; }
  const WrenchEstimatorOptions& options() const { return options_; }

 private:
  // A link's inertia, about its body's origin in body axes.
  struct Piece {
    int body = 0;
    model::SpatialInertia inertia;
  };
  struct SensorSides {
    int parent = 0;  // submodel on the parent side
    int child = 0;   // submodel on the child side
  };
  struct Solver {  // the least-squares system of one submodel
    Eigen::Matrix<double, 6, Eigen::Dynamic> A;
    Eigen::VectorXd x;
  };

  void solve_submodel(int k);
  Vector3d link_position(std::size_t h) const;  // origin of hypothesis h's link, world
  void update_contact_states();
  void set_thresholds(std::vector<std::string>& errors);
  void mark_invalid_torques();

  model::Model model_;
  WrenchEstimatorOptions options_;
  model::Data data_;
  std::vector<int> sensor_frames_;  // the sensor frame: the fixed joint's child link
  std::vector<SensorSides> sensor_sides_;
  std::vector<Submodel> submodels_;
  std::vector<std::vector<Piece>> pieces_;  // per submodel
  std::vector<Solver> solvers_;             // per submodel
  std::vector<std::string> link_names_;
  int n_contacts_ = 0;
  std::vector<int> hypothesis_body_;
  std::vector<int> hypothesis_submodel_;
  std::vector<double> on_force_, off_force_;  // per hypothesis

  // per tick
  std::vector<Vector6d> balance_;  // b_k per submodel, world origin
  std::vector<model::ExternalWrench> wrenches_;
  std::vector<std::uint8_t> reading_valid_, submodel_valid_, hypothesis_valid_, joint_valid_,
      loaded_;
  Eigen::VectorXd joint_torques_;
  Vector6d base_residual_ = Vector6d::Zero();
};

}  // namespace wbi::estimation
