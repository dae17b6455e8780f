#include "wbi/estimation/wrench_estimator.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

#include "partition.hpp"
#include "wbi/model/rnea.hpp"

namespace wbi::estimation {

namespace {

using model::SpatialInertia;

// A link inertia about its body's origin in body axes, moved to world axes
// about the world origin (body at rotation R, origin p):
//   h_O = m p + R h,  I_O = R I Rᵀ + m(|p|² 1 − p pᵀ) + 2(p·h′) 1 − p h′ᵀ − h′ pᵀ,  h′ = R h.
SpatialInertia to_world(const SpatialInertia& local, const Matrix3d& R, const Vector3d& p) {
  SpatialInertia w;
  const Vector3d h = R * local.h;
  w.m = local.m;
  w.h = local.m * p + h;
  w.I = R * local.I * R.transpose() +
        local.m * (p.squaredNorm() * Matrix3d::Identity() - p * p.transpose()) +
        2.0 * p.dot(h) * Matrix3d::Identity() - p * h.transpose() - h * p.transpose();
  return w;
}

// (force, moment about point p) → (force, moment about the world origin).
Vector6d at_world_origin(const Vector6d& w, const Vector3d& p) {
  Vector6d r = w;
  r.tail<3>() += p.cross(w.head<3>());
  return r;
}

std::string joined(const std::vector<std::string>& items, const char* separator) {
  std::string text;
  for (const std::string& item : items) {
    text += (text.empty() ? "" : separator) + item;
  }
  return text;
}

}  // namespace

WrenchEstimator::WrenchEstimator(const model::Model& model, WrenchEstimatorOptions options)
    : model_(model), options_(std::move(options)), data_(model_) {
  std::vector<std::string> errors;
  detail::Partition partition = detail::partition_at_sensors(model_, options_.sensors, errors);
  sensor_frames_ = partition.sensor_frames;
  for (int f : sensor_frames_) {
    if (f >= 0) {
      sensor_sides_.push_back({partition.submodel_of_frame[static_cast<std::size_t>(
                                   model_.frame_parent[static_cast<std::size_t>(f)])],
                               partition.submodel_of_frame[static_cast<std::size_t>(f)]});
    }
  }
  submodels_ = std::move(partition.submodels);
  if (!(options_.contact_off_force <= options_.contact_on_force)) {
    errors.push_back("contact_off_force (" + std::to_string(options_.contact_off_force) +
                     " N) is above contact_on_force (" + std::to_string(options_.contact_on_force) +
                     " N)");
  }
  // hypotheses: contact links first, then the extra ones
  link_names_ = options_.contact_links;
  link_names_.insert(link_names_.end(), options_.extra_links.begin(), options_.extra_links.end());
  n_contacts_ = static_cast<int>(options_.contact_links.size());
  std::set<std::string> seen;
  for (std::size_t h = 0; h < link_names_.size(); ++h) {
    const std::string& link = link_names_[h];
    if (!seen.insert(link).second) {
      errors.push_back("link '" + link + "' is listed twice as a wrench hypothesis");
    }
    if (!model_.has_frame(link)) {
      errors.push_back("wrench hypothesis: no link '" + link + "' in " + model_.source);
      continue;
    }
    const int frame = model_.frame_id(link);
    const int k = partition.submodel_of_frame[static_cast<std::size_t>(frame)];
    if (!model_.floating_base && k == partition.submodel_of_frame[0]) {
      errors.push_back("link '" + link +
                       "' is on the fixed base's submodel: its wrench cannot be told from "
                       "the base's reaction");
      continue;
    }
    submodels_[static_cast<std::size_t>(k)].hypotheses.push_back(static_cast<int>(h));
    wrenches_.push_back({frame, Vector6d::Zero()});
    hypothesis_body_.push_back(model_.frame_body[static_cast<std::size_t>(frame)]);
    hypothesis_submodel_.push_back(k);
  }
  set_thresholds(errors);
  for (std::size_t k = 0; k < submodels_.size(); ++k) {
    const Submodel& sub = submodels_[k];
    const bool fixed_root = !model_.floating_base && k == 0;
    if (sub.hypotheses.empty() && !fixed_root) {
      std::vector<std::string> sensors;
      for (int s : sub.child_sensors) {
        sensors.push_back(options_.sensors[static_cast<std::size_t>(s)].name);
      }
      for (int s : sub.parent_sensors) {
        sensors.push_back(options_.sensors[static_cast<std::size_t>(s)].name);
      }
      errors.push_back("submodel '" + sub.name + "' (links " + joined(sub.links, ", ") +
                       "; sensors " + joined(sensors, ", ") +
                       ") has no wrench hypothesis: list one of its links in contact_links or "
                       "extra_links");
    }
  }
  if (!errors.empty()) {
    throw std::invalid_argument("wrench estimator on " + model_.source + ": " +
                                joined(errors, "; "));
  }
  // each submodel's mass, lumped per body
  pieces_.resize(submodels_.size());
  for (int f = 0; f < model_.n_frames(); ++f) {
    const auto uf = static_cast<std::size_t>(f);
    if (model_.frame_inertia[uf].m <= 0.0) {
      continue;
    }
    auto& pieces = pieces_[static_cast<std::size_t>(partition.submodel_of_frame[uf])];
    const int body = model_.frame_body[uf];
    auto it = std::find_if(pieces.begin(), pieces.end(),
                           [&](const Piece& piece) { return piece.body == body; });
    if (it == pieces.end()) {
      pieces.push_back({body, SpatialInertia{}});
      it = std::prev(pieces.end());
    }
    it->inertia += model_.frame_inertia[uf];
  }
  solvers_.resize(submodels_.size());
  for (std::size_t k = 0; k < submodels_.size(); ++k) {
    const auto m = static_cast<Eigen::Index>(submodels_[k].hypotheses.size());
    solvers_[k].A.setZero(6, 6 * m);
    solvers_[k].x.setZero(6 * m);
  }
  balance_.assign(submodels_.size(), Vector6d::Zero());
  reading_valid_.assign(sensor_frames_.size(), 1);
  submodel_valid_.assign(submodels_.size(), 1);
  hypothesis_valid_.assign(link_names_.size(), 1);
  loaded_.assign(link_names_.size(), 0);
  joint_valid_.assign(static_cast<std::size_t>(model_.n_joints), 1);
  joint_torques_.setZero(model_.n_joints);
}

void WrenchEstimator::update(const model::ConstVectorRef& q, const model::ConstVectorRef& nu,
                             const model::ConstVectorRef& dnu, std::span<const Vector6d> readings) {
  if (readings.size() != sensor_frames_.size()) {
    throw std::invalid_argument("wrench estimator: " + std::to_string(readings.size()) +
                                " F/T readings, expected " + std::to_string(sensor_frames_.size()));
  }
  // body velocities and accelerations (gravity included): the forward pass of RNEA
  model::inverse_dynamics(model_, data_, q, nu, dnu, options_.gravity);
  std::fill(submodel_valid_.begin(), submodel_valid_.end(), std::uint8_t{1});
  for (std::size_t k = 0; k < submodels_.size(); ++k) {
    Vector6d& b = balance_[k];
    b.setZero();
    for (const Piece& piece : pieces_[k]) {
      const auto body = static_cast<std::size_t>(piece.body);
      const SpatialInertia I = to_world(piece.inertia, data_.R_WB[body], data_.p_WB[body]);
      b += I * data_.a[body] + model::cross_force(data_.v[body], I * data_.v[body]);
    }
  }
  // the sensors' boundary wrenches: child on parent W_s, parent on child −W_s,
  // so b_k = F_k + Σ_{k child} W_s − Σ_{k parent} W_s
  for (std::size_t s = 0; s < sensor_frames_.size(); ++s) {
    const Vector6d& w = readings[s];
    const auto parent = static_cast<std::size_t>(sensor_sides_[s].parent);
    const auto child = static_cast<std::size_t>(sensor_sides_[s].child);
    const bool finite = w.allFinite();
    const bool saturated = finite && (w.head<3>().cwiseAbs().maxCoeff() >= options_.force_limit ||
                                      w.tail<3>().cwiseAbs().maxCoeff() >= options_.torque_limit);
    reading_valid_[s] = finite && !saturated ? 1 : 0;
    if (reading_valid_[s] == 0) {
      submodel_valid_[parent] = submodel_valid_[child] = 0;
      continue;
    }
    const auto f = static_cast<std::size_t>(sensor_frames_[s]);
    const auto body = static_cast<std::size_t>(model_.frame_body[f]);
    const Matrix3d R_WS = data_.R_WB[body] * model_.frame_R_BF[f];
    const Vector3d p_S = data_.p_WB[body] + data_.R_WB[body] * model_.frame_p_BF[f];
    Vector6d W;
    W << R_WS * w.head<3>(), R_WS * w.tail<3>();
    W = at_world_origin(W, p_S);
    balance_[child] += W;
    balance_[parent] -= W;
  }
  for (std::size_t k = 0; k < submodels_.size(); ++k) {
    solve_submodel(static_cast<int>(k));
  }
  // joint torques: RNEA with the estimated wrenches (zero where invalid)
  const Eigen::VectorXd& tau =
      model::inverse_dynamics(model_, data_, q, nu, dnu, options_.gravity, wrenches_);
  joint_torques_ = tau.tail(model_.n_joints);
  if (model_.floating_base) {
    base_residual_ = tau.head<6>();
  }
  mark_invalid_torques();
  update_contact_states();
}

// Step 3 of the header: x = X_h⁻¹ b for one hypothesis, x = Aᵀ(A Aᵀ)⁻¹ b for several.
void WrenchEstimator::solve_submodel(int k) {
  const auto uk = static_cast<std::size_t>(k);
  const std::vector<int>& hypotheses = submodels_[uk].hypotheses;
  const bool valid = submodel_valid_[uk] != 0;
  for (int h : hypotheses) {
    hypothesis_valid_[static_cast<std::size_t>(h)] = valid ? 1 : 0;
  }
  if (hypotheses.empty()) {
    return;
  }
  const Vector6d& b = balance_[uk];
  if (!valid) {
    for (int h : hypotheses) {
      wrenches_[static_cast<std::size_t>(h)].wrench.setZero();
    }
    return;
  }
  if (hypotheses.size() == 1) {
    const auto h = static_cast<std::size_t>(hypotheses[0]);
    const Vector3d& p = link_position(h);
    Vector6d& x = wrenches_[h].wrench;
    x.head<3>() = b.head<3>();
    x.tail<3>() = b.tail<3>() - p.cross(b.head<3>());
    return;
  }
  Solver& solver = solvers_[uk];
  for (std::size_t i = 0; i < hypotheses.size(); ++i) {
    const auto h = static_cast<std::size_t>(hypotheses[i]);
    auto X = solver.A.middleCols<6>(6 * static_cast<Eigen::Index>(i));
    X.setIdentity();
    X.bottomLeftCorner<3, 3>() = model::skew(link_position(h));
  }
  const model::Matrix6d AAt = solver.A * solver.A.transpose();
  const Vector6d y = AAt.ldlt().solve(b);
  solver.x.noalias() = solver.A.transpose() * y;
  for (std::size_t i = 0; i < hypotheses.size(); ++i) {
    wrenches_[static_cast<std::size_t>(hypotheses[i])].wrench =
        solver.x.segment<6>(6 * static_cast<Eigen::Index>(i));
  }
}

Vector3d WrenchEstimator::link_position(std::size_t h) const {
  const auto f = static_cast<std::size_t>(wrenches_[h].frame);
  const auto body = static_cast<std::size_t>(model_.frame_body[f]);
  return data_.p_WB[body] + data_.R_WB[body] * model_.frame_p_BF[f];
}

// τ_j = S_jᵀ Σ_{subtree of j}(…): invalid when the subtree holds an invalid hypothesis.
void WrenchEstimator::mark_invalid_torques() {
  for (int j = 0; j < model_.n_joints; ++j) {
    const int first = model_.joint_body[static_cast<std::size_t>(j)];
    const int last = first + model_.body_subtree_size[static_cast<std::size_t>(first)];
    bool valid = true;
    for (std::size_t h = 0; h < hypothesis_body_.size() && valid; ++h) {
      valid =
          hypothesis_valid_[h] != 0 || hypothesis_body_[h] < first || hypothesis_body_[h] >= last;
    }
    joint_valid_[static_cast<std::size_t>(j)] = valid ? 1 : 0;
  }
}

// The contact thresholds per hypothesis: the link's own, else the common ones.
void WrenchEstimator::set_thresholds(std::vector<std::string>& errors) {
  for (const auto* given : {&options_.link_on_force, &options_.link_off_force}) {
    for (const auto& [link, force] : *given) {
      if (std::find(link_names_.begin(), link_names_.end(), link) == link_names_.end()) {
        errors.push_back("contact threshold for '" + link + "', which is no wrench hypothesis");
      }
    }
  }
  for (const auto& link : link_names_) {
    const auto on = options_.link_on_force.find(link);
    const auto off = options_.link_off_force.find(link);
    on_force_.push_back(on != options_.link_on_force.end() ? on->second
                                                           : options_.contact_on_force);
    off_force_.push_back(off != options_.link_off_force.end() ? off->second
                                                              : options_.contact_off_force);
    const bool own = on != options_.link_on_force.end() || off != options_.link_off_force.end();
    if (own && !(off_force_.back() <= on_force_.back())) {
      errors.push_back("'" + link + "': its contact off force (" +
                       std::to_string(off_force_.back()) + " N) is above its on force (" +
                       std::to_string(on_force_.back()) + " N)");
    }
  }
}

void WrenchEstimator::update_contact_states() {
  for (std::size_t h = 0; h < wrenches_.size(); ++h) {
    if (hypothesis_valid_[h] == 0) {
      continue;  // unknown: keep the last state
    }
    const double force = wrenches_[h].wrench.head<3>().norm();
    if (force > on_force_[h]) {
      loaded_[h] = 1;
    } else if (force < off_force_[h]) {
      loaded_[h] = 0;
    }
  }
}

}  // namespace wbi::estimation
