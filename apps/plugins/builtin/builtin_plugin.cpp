// The plugin `wbi_builtin`: the project's own component types, controller
// types and simulation engines, registered through the same entry point a
// lab's plugin has (wbi/plugin.hpp). Every program that makes types by name
// loads it first (wbi::runtime::load_plugins).
#include <memory>

#include <wbi/controllers/controller_host_component.hpp>
#include <wbi/controllers/momentum_balance_controller.hpp>
#include <wbi/controllers/pd_gravity_controller.hpp>
#include <wbi/controllers/reference_generators.hpp>
#include <wbi/controllers/walking_planner.hpp>
#include <wbi/estimator/estimator_component.hpp>
#include <wbi/model_service/component.hpp>
#include <wbi/plugin.hpp>
#include <wbi/runtime/builtin.hpp>
#include <wbi/sim_robot/sim_robot.hpp>

namespace {

// The catalog's registry, shared without ownership: the catalog outlives
// every component made from it (wbi/catalog.hpp).
template <class R>
std::shared_ptr<const R> lent(R& registry) {
  return std::shared_ptr<const R>(std::shared_ptr<void>(), &registry);
}

}  // namespace

WBI_PLUGIN(catalog) {
  using namespace wbi;
  auto& components = catalog.registry<runtime::Registry>();
  auto& controller_types = catalog.registry<controllers::ControllerRegistry>();
  auto& engines = catalog.registry<sim_robot::EngineRegistry>();

  runtime::register_builtin_components(components);
  model_service::register_components(components);
  estimator::register_components(components);
  sim_robot::register_builtin_engines(engines);
  sim_robot::register_components(components, lent(engines));
  controllers::register_pd_gravity(controller_types);
  controllers::register_momentum_balance(controller_types);
  controllers::register_reference_generators(components);
  controllers::register_reference_planners(controller_types);
  controllers::register_walking_planner(controller_types);
  controllers::register_components(components, lent(controller_types));
  // `type: pd_gravity` as a component: for every controller type, a lab's too.
  catalog.after_loading([](Catalog& all) {
    controllers::register_single_controller_hosts(
        all.registry<runtime::Registry>(), lent(all.registry<controllers::ControllerRegistry>()));
  });
}
