#include "wbi/estimation/low_pass_filter.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace wbi::estimation {

double low_pass_gain(double cutoff_hz, double dt_s) {
  if (cutoff_hz <= 0.0) {
    return 1.0;
  }
  // -expm1 keeps precision when 2π f_c Δt is small.
  return -std::expm1(-2.0 * std::numbers::pi * cutoff_hz * dt_s);
}

LowPassFilter::LowPassFilter(Eigen::Index size, double cutoff_hz, const StreamParameters& stream)
    : cutoff_hz_(cutoff_hz), stamps_(stream.sample_rate_hz, stream.max_gap_s) {
  if (size <= 0) {
    throw std::invalid_argument("low-pass filter: size must be > 0, got " + std::to_string(size));
  }
  if (!(cutoff_hz >= 0.0) || !std::isfinite(cutoff_hz)) {
    throw std::invalid_argument("low-pass filter: cutoff must be >= 0 Hz (0: no filtering), got " +
                                std::to_string(cutoff_hz));
  }
  y_ = Eigen::VectorXd::Zero(size);
}

SampleStatus LowPassFilter::update(std::int64_t stamp_ns,
                                   const Eigen::Ref<const Eigen::VectorXd>& x) {
  if (x.size() != y_.size()) {
    throw std::invalid_argument("low-pass filter update: x has " + std::to_string(x.size()) +
                                " values, expected " + std::to_string(y_.size()));
  }
  if (!x.allFinite()) {
    stamps_.count_non_finite();
    return SampleStatus::non_finite;
  }
  double dt_s = 0.0;
  const SampleStatus status = stamps_.check(stamp_ns, dt_s);
  if (status == SampleStatus::first || status == SampleStatus::after_gap) {
    y_ = x;
  } else if (status == SampleStatus::accepted) {
    y_ += low_pass_gain(cutoff_hz_, dt_s) * (x - y_);
  }
  return status;
}

}  // namespace wbi::estimation
