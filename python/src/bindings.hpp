// The parts of the native module wbi._wbi, one function per file.
#pragma once

#include <pybind11/pybind11.h>

namespace wbi::python {

// wbi.Model: the rigid-body model library (model_bindings.cpp).
void bind_model(pybind11::module_& module);

// wbi.DdsInterface (interface_bindings.cpp), after the interface's vocabulary.
void bind_interface(pybind11::module_& module);

// The interface's vocabulary: its enums, Stamp, RobotState and errors
// (vocabulary_bindings.cpp; bind_interface calls it first).
void bind_vocabulary(pybind11::module_& module);

}  // namespace wbi::python
