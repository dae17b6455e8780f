#include "wbi/sim_rig/in_process_robot.hpp"

#include <wbi/estimator/estimator_component.hpp>
#include <wbi/sim_robot/sim_robot.hpp>

namespace wbi::sim_rig {

InProcessRobot::InProcessRobot(const std::string& participant_name,
                               const std::string& sim_parameters,
                               const std::string& estimator_parameters)
    : participant_(participant_name) {
  sim_robot::register_components(registry_);
  estimator::register_components(registry_);
  sim_.emplace(registry_.create("sim_robot"),
               runtime::ComponentContext{"sim", "sim_robot", &participant_, &clock_});
  estimator_.emplace(registry_.create("estimator"),
                     runtime::ComponentContext{"estimator", "estimator", &participant_, &clock_});
  sim_->configure(runtime::Parameters::from_string(sim_parameters));
  estimator_->configure(runtime::Parameters::from_string(estimator_parameters));
  estimator_->activate();
}

InProcessRobot::~InProcessRobot() = default;

void InProcessRobot::start_simulation() { sim_->activate(); }

}  // namespace wbi::sim_rig
