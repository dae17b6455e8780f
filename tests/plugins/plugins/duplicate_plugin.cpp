// A plugin that registers a type name the built-in plugin has.
#include <wbi/plugin.hpp>
#include <wbi/runtime/registry.hpp>

namespace {
class Quiet final : public wbi::runtime::Component {
 public:
  void on_configure(const wbi::runtime::Parameters& /*parameters*/,
                    const wbi::runtime::ComponentContext& /*context*/) override {}
};
}  // namespace

WBI_PLUGIN(catalog) {
  catalog.registry<wbi::runtime::Registry>().add<Quiet>("estimator", "not the estimator");
}
