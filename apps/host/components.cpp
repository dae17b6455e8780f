#include "components.hpp"

#include <wbi/controllers/controller_host_component.hpp>
#include <wbi/controllers/reference_generators.hpp>
#include <wbi/estimator/estimator_component.hpp>
#include <wbi/model_service/component.hpp>
#include <wbi/sim_robot/sim_robot.hpp>

namespace wbi::host {

void register_components(wbi::runtime::Registry& registry) {
  wbi::model_service::register_components(registry);
  wbi::estimator::register_components(registry);
  wbi::sim_robot::register_components(registry);
  wbi::controllers::register_components(registry);
  wbi::controllers::register_reference_generators(registry);
}

}  // namespace wbi::host
