#include "wbi/controllers/controller_types.hpp"

#include <wbi/controllers/momentum_balance_controller.hpp>
#include <wbi/controllers/pd_gravity_controller.hpp>

namespace wbi::controllers {

const ControllerRegistry& controller_types() {
  static const ControllerRegistry registry = [] {
    ControllerRegistry types;
    register_pd_gravity(types);  // pd_gravity, hold
    register_momentum_balance(types);
    return types;
  }();
  return registry;
}

}  // namespace wbi::controllers
