// The parts of the native module wbi._wbi, one function per file.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <pybind11/pybind11.h>
#include <wbi/dds/participant.hpp>

namespace wbi::python {

// wbi.Model: the rigid-body model library (model_bindings.cpp).
void bind_model(pybind11::module_& module);

// wbi.DdsInterface (interface_bindings.cpp), after the interface's vocabulary.
void bind_interface(pybind11::module_& module);

// The interface's vocabulary: its enums, Stamp, RobotState and errors
// (vocabulary_bindings.cpp; bind_interface calls it first).
void bind_vocabulary(pybind11::module_& module);

// wbi.ControllerHost: a client of a robot's controller host (controller_bindings.cpp).
void bind_controller_host(pybind11::module_& module);

// The participant options of a Python object that joins a deployment, from
// its keyword arguments, as every wbi tool joins (interface_bindings.cpp).
// Raises ValueError naming a bad value.
dds::ParticipantOptions join_from_keywords(
    const std::string& participant_name, const std::optional<std::string>& deploy,
    std::optional<int> domain_id, const std::optional<std::string>& discovery,
    const std::optional<std::vector<std::string>>& peers,
    const std::optional<std::vector<std::string>>& interfaces,
    const std::optional<std::string>& discovery_server, const std::optional<std::string>& qos_file,
    const std::optional<std::string>& security, const std::optional<std::string>& identity);

}  // namespace wbi::python
