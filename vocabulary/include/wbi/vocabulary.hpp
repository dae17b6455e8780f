// The whole vocabulary (vocabulary/README.md).
#pragma once

#include "wbi/vocabulary/contact_shape.hpp"
#include "wbi/vocabulary/control_mode.hpp"
#include "wbi/vocabulary/event.hpp"
#include "wbi/vocabulary/integrator.hpp"
#include "wbi/vocabulary/lifecycle_state.hpp"
#include "wbi/vocabulary/sensor_kind.hpp"
