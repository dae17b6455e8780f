#include "ground_truth_summary.hpp"

#include <cmath>
#include <iomanip>

namespace wbi::robot {

namespace {

Eigen::VectorXd to_vector(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

}  // namespace

GroundTruthSummary::GroundTruthSummary(const actuation::BackendDescription& description,
                                       const actuation::GroundTruth& first)
    : joint_names_(description.joint_names),
      contact_links_(first.contact_links),
      lower_(to_vector(description.position_lower)),
      upper_(to_vector(description.position_upper)),
      effort_(to_vector(description.effort_limit)),
      start_(first.contact_positions),
      slip_(Eigen::VectorXd::Zero(static_cast<Eigen::Index>(first.contact_positions.size()))),
      at_limit_(description.joint_names.size(), 0),
      torque_(Eigen::VectorXd::Zero(static_cast<Eigen::Index>(description.joint_names.size()))) {}

void GroundTruthSummary::add(const actuation::GroundTruth& truth) {
  for (std::size_t l = 0; l < start_.size() && l < truth.contact_positions.size(); ++l) {
    const auto i = static_cast<Eigen::Index>(l);
    const double travel = (truth.contact_positions[l] - start_[l]).head<2>().norm();
    slip_[i] = std::max(slip_[i], travel);
  }
  const Eigen::Index n = torque_.size();
  const Eigen::Index offset = truth.q.size() - n;  // the base's coordinates first, if any
  for (Eigen::Index j = 0; j < n && offset >= 0; ++j) {
    const double q = truth.q[offset + j];
    if (q <= lower_[j] + kLimitTolerance || q >= upper_[j] - kLimitTolerance) {
      ++at_limit_[static_cast<std::size_t>(j)];
    }
    if (j < truth.tau_actuator.size()) {
      torque_[j] = std::max(torque_[j], std::abs(truth.tau_actuator[j]));
    }
  }
  ++ticks_;
}

double GroundTruthSummary::largest_slip() const {
  return slip_.size() == 0 ? -1.0 : slip_.maxCoeff();
}

int GroundTruthSummary::slipping_link() const {
  Eigen::Index i = -1;
  if (slip_.size() > 0) {
    slip_.maxCoeff(&i);
  }
  return static_cast<int>(i);
}

double GroundTruthSummary::largest_limit_fraction() const {
  const int j = joint_most_at_limit();
  return j < 0 || ticks_ == 0 ? 0.0
                              : static_cast<double>(at_limit_[static_cast<std::size_t>(j)]) /
                                    static_cast<double>(ticks_);
}

int GroundTruthSummary::joint_most_at_limit() const {
  int best = -1;
  for (std::size_t j = 0; j < at_limit_.size(); ++j) {
    if (best < 0 || at_limit_[j] > at_limit_[static_cast<std::size_t>(best)]) {
      best = static_cast<int>(j);
    }
  }
  return best;
}

double GroundTruthSummary::largest_effort_fraction() const {
  const int j = joint_nearest_effort();
  return j < 0 ? 0.0 : torque_[j] / effort_[j];
}

int GroundTruthSummary::joint_nearest_effort() const {
  int best = -1;
  double best_fraction = -1.0;
  for (Eigen::Index j = 0; j < torque_.size(); ++j) {
    const double fraction =
        std::isfinite(effort_[j]) && effort_[j] > 0.0 ? torque_[j] / effort_[j] : 0.0;
    if (fraction > best_fraction) {
      best_fraction = fraction;
      best = static_cast<int>(j);
    }
  }
  return best;
}

void GroundTruthSummary::print(std::ostream& out, const std::string& who) const {
  out << who << ": ground truth over " << ticks_ << " ticks\n";
  if (const int l = slipping_link(); l >= 0) {
    out << who << ": contact slip: " << std::setprecision(3) << std::fixed
        << 1000.0 * largest_slip() << " mm (" << contact_links_[static_cast<std::size_t>(l)]
        << ", largest horizontal travel of a contact link's frame)\n";
  }
  if (const int j = joint_most_at_limit(); j >= 0) {
    const auto u = static_cast<std::size_t>(j);
    out << who << ": joint at a limit: " << std::setprecision(2) << std::fixed
        << 100.0 * largest_limit_fraction() << " % of ticks (" << joint_names_[u]
        << ", the most)\n";
  }
  if (const int j = joint_nearest_effort(); j >= 0) {
    out << who << ": torque: " << std::setprecision(3) << std::fixed << largest_effort_fraction()
        << " of the effort limit (" << joint_names_[static_cast<std::size_t>(j)] << ": "
        << std::setprecision(1) << torque_[j] << " of " << effort_[j] << " N·m, the largest)\n";
  }
  out << std::defaultfloat << std::flush;
}

}  // namespace wbi::robot
