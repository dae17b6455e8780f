#include "wbi/estimation/model_kalman.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace wbi::estimation {

ModelKalmanEstimator::ModelKalmanEstimator(Eigen::Index joints, const ModelKalmanParameters& params,
                                           const StreamParameters& stream)
    : DerivativeEstimator(joints, stream),
      filters_("model-kalman", joints, params.model_order, params.resolution_counts,
               params.process_noise, 1.0 / stream.sample_rate_hz),
      applied_(Eigen::VectorXd::Zero(joints)) {}

// At rest, as `kalman`; the next input enters whole.
void ModelKalmanEstimator::start(const Eigen::Ref<const Eigen::VectorXd>& q) {
  filters_.start(q);
  applied_.setZero();
}

void ModelKalmanEstimator::step(double dt_s, const Eigen::Ref<const Eigen::VectorXd>& q,
                                Eigen::VectorXd& dq, Eigen::VectorXd& ddq) {
  filters_.step(dt_s, q);
  filters_.velocity(dq);
  filters_.acceleration(ddq);
}

void ModelKalmanEstimator::set_model_acceleration(
    const Eigen::Ref<const Eigen::VectorXd>& model_ddq) {
  if (model_ddq.size() != joints()) {
    throw std::invalid_argument("model-kalman: the model acceleration has " +
                                std::to_string(model_ddq.size()) + " values, expected " +
                                std::to_string(joints()));
  }
  for (Eigen::Index j = 0; j < model_ddq.size(); ++j) {
    if (!std::isfinite(model_ddq[j])) {
      ++non_finite_inputs_;
      continue;
    }
    filters_.add_acceleration(j, model_ddq[j] - applied_[j]);
    applied_[j] = model_ddq[j];
    set_acceleration(j, filters_.acceleration(j));
  }
}

}  // namespace wbi::estimation
