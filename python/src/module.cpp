// wbi._wbi: the native half of the Python package wbi (python/wbi/__init__.py
// re-exports it).
#include <pybind11/pybind11.h>

#include "bindings.hpp"

PYBIND11_MODULE(_wbi, module) {
  module.doc() =
      "wbi native bindings: the model library (Model) and the whole-body interface over DDS "
      "(DdsInterface), a client of a robot's controller host (ControllerHost). Import the package "
      "wbi instead.";
  wbi::python::bind_model(module);
  wbi::python::bind_interface(module);
  wbi::python::bind_controller_host(module);
}
