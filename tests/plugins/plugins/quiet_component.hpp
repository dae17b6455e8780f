// A component that does nothing: the type the test plugins register.
#pragma once

#include <wbi/runtime/component.hpp>

namespace wbi::test {

class QuietComponent final : public wbi::runtime::Component {
 public:
  void on_configure(const wbi::runtime::Parameters& /*parameters*/,
                    const wbi::runtime::ComponentContext& /*context*/) override {}
};

}  // namespace wbi::test
