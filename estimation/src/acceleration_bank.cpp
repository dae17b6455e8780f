#include "wbi/estimation/acceleration_bank.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace wbi::estimation {
namespace {

std::vector<JointKalmanFilters> make_filters(const char* method, Eigen::Index joints,
                                             const AccelerationBankParameters& p, double period_s) {
  if (p.models < 1 || p.models > 8) {
    throw std::invalid_argument(std::string(method) +
                                ": acceleration-models must be in [1, 8], got " +
                                std::to_string(p.models));
  }
  if (!(p.noise_max >= p.noise_min)) {
    throw std::invalid_argument(std::string(method) +
                                ": acceleration-noise-max must be >= acceleration-noise-min, got " +
                                std::to_string(p.noise_max) + " < " + std::to_string(p.noise_min));
  }
  std::vector<JointKalmanFilters> filters;
  filters.reserve(static_cast<std::size_t>(p.models));
  const double ratio = p.noise_max / p.noise_min;
  for (int i = 0; i < p.models; ++i) {
    // Geometric spacing from the minimum to the maximum.
    const double u = p.models > 1 ? static_cast<double>(i) / (p.models - 1) : 0.0;
    filters.emplace_back(method, joints, p.order, p.counts, p.noise_min * std::pow(ratio, u),
                         period_s);
  }
  return filters;
}

}  // namespace

AccelerationBank::AccelerationBank(const char* method, Eigen::Index joints,
                                   const AccelerationBankParameters& p, double period_s)
    : filters_(make_filters(method, joints, p, period_s)),
      log_likelihood_(Eigen::MatrixXd::Zero(p.models, joints)),
      weights_(Eigen::MatrixXd::Constant(p.models, joints, 1.0 / p.models)),
      best_(Eigen::RowVectorXd::Zero(joints)),
      total_(Eigen::RowVectorXd::Zero(joints)),
      acceleration_at_stick_(Eigen::MatrixXd::Zero(p.models, joints)),
      velocity_(Eigen::VectorXd::Zero(joints)),
      acceleration_(Eigen::VectorXd::Zero(joints)),
      innovation_score_(Eigen::VectorXd::Zero(joints)) {}

void AccelerationBank::start(const Eigen::Ref<const Eigen::VectorXd>& q) {
  for (auto& filters : filters_) {
    filters.start(q);
  }
  log_likelihood_.setZero();
  weights_.setConstant(1.0 / static_cast<double>(weights_.rows()));
  velocity_.setZero();
  acceleration_.setZero();
  innovation_score_.setZero();
}

void AccelerationBank::step(double dt_s, const Eigen::Ref<const Eigen::VectorXd>& q,
                            double forget) {
  for (auto& filters : filters_) {
    filters.step(dt_s, q);
  }
  update_weights(forget);
}

void AccelerationBank::step_like(const AccelerationBank& stepped,
                                 const Eigen::Ref<const Eigen::VectorXd>& q, double forget) {
  for (std::size_t i = 0; i < filters_.size(); ++i) {
    filters_[i].step_like(stepped.filters_[i], q);
  }
  update_weights(forget);
}

void AccelerationBank::update_weights(double forget) {
  const auto models = static_cast<Eigen::Index>(filters_.size());
  const Eigen::Index joints = acceleration_.size();
  innovation_score_.setZero();
  for (Eigen::Index i = 0; i < models; ++i) {
    const auto& filters = filters_[static_cast<std::size_t>(i)];
    const double S = filters.innovation_variance();
    const double log_S = std::log(S);
    for (Eigen::Index j = 0; j < joints; ++j) {
      const double nu = filters.innovation()(j);
      const double score = nu * nu / S + log_S;  // −2 ln N(ν; 0, S) up to a constant
      log_likelihood_(i, j) = forget * log_likelihood_(i, j) + score;
      // weights_ are still those before this sample: the bank's prediction.
      innovation_score_(j) += weights_(i, j) * score;
    }
  }
  // Weights relative to the likeliest model, so that exp never underflows to
  // 0/0; whole-bank array expressions so that Eigen vectorises the exp.
  best_ = log_likelihood_.colwise().minCoeff();
  weights_.array() = (-0.5 * (log_likelihood_.rowwise() - best_).array()).exp();
  total_ = weights_.colwise().sum();
  weights_.array().rowwise() /= total_.array();
  for (Eigen::Index j = 0; j < joints; ++j) {
    blend(j);
  }
}

void AccelerationBank::blend(Eigen::Index j) {
  double dq = 0.0;
  double ddq = 0.0;
  for (std::size_t i = 0; i < filters_.size(); ++i) {
    const double w = weights_(static_cast<Eigen::Index>(i), j);
    dq += w * filters_[i].velocity(j);
    ddq += w * filters_[i].acceleration(j);
  }
  velocity_(j) = dq;
  acceleration_(j) = ddq;
}

void AccelerationBank::stick(Eigen::Index j, double fraction) {
  for (std::size_t i = 0; i < filters_.size(); ++i) {
    const double ddq = filters_[i].acceleration(j);
    acceleration_at_stick_(static_cast<Eigen::Index>(i), j) = ddq;
    filters_[i].set_acceleration(j, fraction * ddq);
  }
  blend(j);
}

void AccelerationBank::slip(Eigen::Index j, double fraction) {
  for (std::size_t i = 0; i < filters_.size(); ++i) {
    filters_[i].set_acceleration(
        j, fraction * acceleration_at_stick_(static_cast<Eigen::Index>(i), j));
  }
  blend(j);
}

void AccelerationBank::recover(Eigen::Index j, double increment) {
  for (std::size_t i = 0; i < filters_.size(); ++i) {
    filters_[i].add_acceleration(
        j, increment * acceleration_at_stick_(static_cast<Eigen::Index>(i), j));
  }
  blend(j);
}

}  // namespace wbi::estimation
