// A plugin as a lab writes one: a controller and a component type.
#include <wbi/controllers/controller.hpp>
#include <wbi/plugin.hpp>
#include <wbi/runtime/registry.hpp>

#include "quiet_component.hpp"

namespace {

// Sends zero torques: enough to be hosted, listed and made by name.
class Zero final : public wbi::controllers::Controller {
 public:
  std::vector<wbi::controllers::ParameterSpec> parameters() const override { return {}; }
  void configure(wbi::WholeBodyInterface& robot,
                 const wbi::controllers::ParameterTable& /*parameters*/) override {
    command_.setZero(robot.dofs());
  }
  void activate(const wbi::RobotState& /*measured*/) override {}
  bool update(double /*time_s*/, double /*period_s*/) override { return true; }
  const Eigen::VectorXd& command() const override { return command_; }

 private:
  Eigen::VectorXd command_;
};

}  // namespace

WBI_PLUGIN(catalog) {
  catalog.registry<wbi::controllers::ControllerRegistry>().add<Zero>("test_zero", "zero torques");
  catalog.registry<wbi::runtime::Registry>().add<wbi::test::QuietComponent>("test_quiet",
                                                                            "does nothing");
}
