// The State element over wbi/<robot>/state; estimator parameters go out on
// wbi/<robot>/state/parameters.
#pragma once

#include <wbi/dds/publisher.hpp>

#include "robot_connection.hpp"
#include "wbi/model.hpp"
#include "wbi/state.hpp"

namespace wbi::proxy {

class DdsState final : public wbi::State {
 public:
  explicit DdsState(RobotConnection& robot);

  // The model whose frame_list() names "fixed_link" frames (set by init()).
  void use_frames_of(const wbi::Model& model) { model_ = &model; }

  Stamp read_robot_state(RobotState& state, ReadMode mode) override;
  Stamp read_estimates(EstimateKind kind, VectorRef values, ReadMode mode) override;
  Stamp read_estimate(EstimateKind kind, int index, VectorRef values, ReadMode mode) override;
  Stamp read_base_pose(Transform& world_H_base, ReadMode mode) override;
  const IdList& external_wrench_links() const override;
  void set_estimation_parameter(const std::string& name, double value) override;

 private:
  int estimate_count(EstimateKind kind) const;
  // Calls reader(const StateEstimate&) with the newest estimate, in place
  // (Stream::read), for a read of `kind`.
  template <class Read>
  void read_state(std::size_t kind, ReadMode mode, Read&& reader) {
    robot_.state.read(kind, mode, robot_.options.max_age_s, robot_.options.blocking_read_timeout,
                      std::forward<Read>(reader));
  }
  Stamp read_range(EstimateKind kind, int first, int count, VectorRef out, ReadMode mode);
  // Estimates [first, first + count) of `kind` from one estimate into out.
  void read_sample(const wbi::msg::StateEstimate& state, EstimateKind kind, int first, int count,
                   VectorRef out) const;

  RobotConnection& robot_;
  dds::Publisher<wbi::msg::EstimatorParameter> parameters_;
  const wbi::Model* model_ = nullptr;
};

}  // namespace wbi::proxy
