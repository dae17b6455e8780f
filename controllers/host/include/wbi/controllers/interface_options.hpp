// The whole-body interface's options as a deploy file gives them: one reader
// and one set of defaults (DdsInterfaceOptions's, as C++ and Python use them)
// for every component that controls a robot.
//
//   robot            required; the robot's name
//   model            local (default): the model in this process, from urdf;
//                    remote: the robot's model service (wbi/<robot>/model)
//   urdf             the robot's URDF, relative to the deploy file; required
//                    for a local model, optional for a remote one (frame names)
//   model_backend    a local model's dynamics library: wbi (default) or dart
//   model_timeout_s  deadline of one remote model call (default 0.2 s)
//   controller       the name on the commands (default: the instance's name)
//   claim            claim (default), force or none (components/robot/README.md)
//   max_age_s        oldest sample a read accepts (default 0.1 s)
#pragma once

#include <wbi/dds_interface_options.hpp>
#include <wbi/runtime/component.hpp>

namespace wbi::controllers {

DdsInterfaceOptions read_interface_options(const runtime::Parameters& parameters,
                                           const runtime::ComponentContext& context);

}  // namespace wbi::controllers
