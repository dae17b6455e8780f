// Every controller type the host can run: one registration line each in
// controller_types.cpp.
#pragma once

#include "wbi/controllers/controller.hpp"

namespace wbi::controllers {

const ControllerRegistry& controller_types();

}  // namespace wbi::controllers
