// The parts of the native module wbi._wbi, one function per file.
#pragma once

#include <pybind11/pybind11.h>

namespace wbi::python {

// wbi.Model: the rigid-body model library (model_bindings.cpp).
void bind_model(pybind11::module_& module);

// wbi.DdsInterface and the interface's vocabulary (interface_bindings.cpp).
void bind_interface(pybind11::module_& module);

}  // namespace wbi::python
