#include "wbi/runtime/builtin.hpp"

namespace wbi::runtime {

namespace {

class Idle final : public Component {
 public:
  void on_configure(const Parameters& /*parameters*/,
                    const ComponentContext& /*context*/) override {}
};

}  // namespace

void register_builtin_components(Registry& registry) {
  registry.add<Idle>("idle", "does nothing; its status shows the loop timing");
}

}  // namespace wbi::runtime
