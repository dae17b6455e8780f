// wbi.ControllerHost: list, switch and set the parameters of a robot's
// controllers while they run (controllers/README.md), as `wbi controller` and
// `wbi param` do. A refusal raises ValueError with the host's one line; no
// host answering within timeout_s raises TimeoutError. Calls release the GIL.
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/stl.h>
#include <wbi/controllers/host_client.hpp>
#include <wbi/controllers/reference_writer.hpp>
#include <wbi/dds/rpc.hpp>
#include <wbi/types.hpp>

#include "bindings.hpp"

namespace py = pybind11;

namespace wbi::python {

namespace {

class PythonHost {
 public:
  PythonHost(const dds::ParticipantOptions& join, const std::string& robot, double timeout_s)
      : participant_(std::make_unique<dds::Participant>(join)),
        client_(std::make_unique<controllers::HostClient>(
            *participant_, robot,
            std::chrono::duration_cast<std::chrono::nanoseconds>(
                std::chrono::duration<double>(timeout_s)))) {}

  // Runs a call without the GIL; a refusal becomes ValueError, no answer TimeoutError.
  template <typename Call>
  auto call(Call&& function) {
    try {
      py::gil_scoped_release release;
      return function(*client_);
    } catch (const dds::CallError& error) {  // no host answered (the GIL is held again here)
      PyErr_SetString(PyExc_TimeoutError, error.what());
      throw py::error_already_set();
    } catch (const Error& refusal) {
      throw py::value_error(refusal.what());
    }
  }

 private:
  std::unique_ptr<dds::Participant> participant_;
  std::unique_ptr<controllers::HostClient> client_;
};

std::unique_ptr<PythonHost> make_host(
    const std::string& robot, double timeout_s, const std::optional<std::string>& deploy,
    std::optional<int> domain_id, const std::optional<std::string>& discovery,
    const std::optional<std::vector<std::string>>& peers,
    const std::optional<std::vector<std::string>>& interfaces,
    const std::optional<std::string>& discovery_server, const std::optional<std::string>& qos_file,
    const std::optional<std::string>& security, const std::optional<std::string>& identity) {
  return std::make_unique<PythonHost>(
      join_from_keywords("wbi_python_host", deploy, domain_id, discovery, peers, interfaces,
                         discovery_server, qos_file, security, identity),
      robot, timeout_s);
}

// A planner's writer of one reference input (wbi.ReferenceWriter).
class PythonReferenceWriter {
 public:
  PythonReferenceWriter(const dds::ParticipantOptions& join, const std::string& robot,
                        const std::string& controller, const std::string& input,
                        const std::string& source)
      : participant_(std::make_unique<dds::Participant>(join)),
        writer_(std::make_unique<controllers::ReferenceWriter>(*participant_, robot, controller,
                                                               input, source)) {}

  controllers::ReferenceWriter& writer() { return *writer_; }

 private:
  std::unique_ptr<dds::Participant> participant_;
  std::unique_ptr<controllers::ReferenceWriter> writer_;
};

std::unique_ptr<PythonReferenceWriter> make_reference_writer(
    const std::string& robot, const std::string& controller, const std::string& input,
    const std::string& source, const std::optional<std::string>& deploy,
    std::optional<int> domain_id, const std::optional<std::string>& discovery,
    const std::optional<std::vector<std::string>>& peers,
    const std::optional<std::vector<std::string>>& interfaces,
    const std::optional<std::string>& discovery_server, const std::optional<std::string>& qos_file,
    const std::optional<std::string>& security, const std::optional<std::string>& identity) {
  return std::make_unique<PythonReferenceWriter>(
      join_from_keywords("wbi_python_reference", deploy, domain_id, discovery, peers, interfaces,
                         discovery_server, qos_file, security, identity),
      robot, controller, input, source);
}

py::dict as_dict(const controllers::ParameterInfo& p) {
  py::dict out;
  out["controller"] = p.controller;
  out["name"] = p.name;
  out["unit"] = p.unit;
  out["help"] = p.help;
  out["min"] = p.min;
  out["max"] = p.max;
  out["live"] = p.live;
  if (p.is_text) {
    out["value"] = p.text;
  } else if (p.values.size() == 1) {
    out["value"] = p.values[0];
  } else if (p.values.empty()) {
    out["value"] = py::none();
  } else {
    out["value"] = p.values;
  }
  return out;
}

}  // namespace

void bind_controller_host(py::module_& module) {
  using py::arg;
  py::class_<PythonReferenceWriter>(
      module, "ReferenceWriter",
      "Publishes a controller's reference input, wbi/<robot>/references/<controller>/<input>: "
      "trajectory points for a robot time (controllers/README.md, 'References'), as a planner "
      "does. Joining keywords as DdsInterface.")
      .def(py::init(&make_reference_writer), arg("robot"), arg("controller"), arg("input"),
           arg("source") = "python", arg("deploy") = py::none(), arg("domain_id") = py::none(),
           arg("discovery") = py::none(), arg("peers") = py::none(), arg("interfaces") = py::none(),
           arg("discovery_server") = py::none(), arg("qos_file") = py::none(),
           arg("security") = py::none(), arg("identity") = py::none())
      .def(
          "write",
          [](PythonReferenceWriter& self, std::int64_t stamp_ns,
             const std::vector<double>& position,
             const std::optional<std::vector<double>>& velocity,
             const std::optional<std::vector<double>>& acceleration) {
            const std::vector<double> none;
            try {
              self.writer().write(stamp_ns, position, velocity.value_or(none),
                                  acceleration.value_or(none));
            } catch (const std::invalid_argument& e) {
              throw py::value_error(e.what());
            }
          },
          arg("stamp_ns"), arg("position"), arg("velocity") = py::none(),
          arg("acceleration") = py::none(),
          "the point for robot time stamp_ns (the state's stamp.source_ns); velocity and "
          "acceleration as many values as position, or None (zero)")
      .def_property_readonly("topic",
                             [](PythonReferenceWriter& self) { return self.writer().topic(); })
      .def_property_readonly("written",
                             [](PythonReferenceWriter& self) { return self.writer().written(); });
  py::class_<PythonHost>(
      module, "ControllerHost",
      "A client of robot `robot`'s controller host (wbi/<robot>/controllers): list, switch and "
      "set parameters while the controllers run. Joining keywords as DdsInterface. A refusal "
      "raises ValueError with the host's one line.")
      .def(py::init(&make_host), arg("robot"), arg("timeout_s") = 5.0, arg("deploy") = py::none(),
           arg("domain_id") = py::none(), arg("discovery") = py::none(), arg("peers") = py::none(),
           arg("interfaces") = py::none(), arg("discovery_server") = py::none(),
           arg("qos_file") = py::none(), arg("security") = py::none(), arg("identity") = py::none())
      .def(
          "controllers",
          [](PythonHost& self) {
            const auto list = self.call([](auto& client) { return client.list(); });
            py::list out;
            for (const auto& c : list) {
              py::dict entry;
              entry["name"] = c.name;
              entry["type"] = c.type;
              entry["active"] = c.active;
              entry["configure_error"] = c.configure_error;
              out.append(entry);
            }
            return out;
          },
          "[{name, type, active, configure_error}] of every hosted controller")
      .def(
          "active",
          [](PythonHost& self) -> std::optional<std::string> {
            for (const auto& c : self.call([](auto& client) { return client.list(); })) {
              if (c.active) {
                return c.name;
              }
            }
            return std::nullopt;
          },
          "the active controller's name, or None")
      .def(
          "switch",
          [](PythonHost& self, const std::string& activate, const std::string& deactivate) {
            return self.call(
                [&](auto& client) { return client.switch_controllers(activate, deactivate); });
          },
          arg("activate") = "", arg("deactivate") = "",
          "deactivates one controller and activates another at one tick boundary; returns what "
          "happened, e.g. 'pd → hold at t = 2.000 s; torque step 0.00 % …'")
      .def(
          "parameters",
          [](PythonHost& self, const std::string& controller) {
            py::list out;
            for (const auto& p :
                 self.call([&](auto& client) { return client.parameters(controller); })) {
              out.append(as_dict(p));
            }
            return out;
          },
          arg("controller"),
          "[{controller, name, unit, help, min, max, live, value}] of a controller's parameters")
      .def(
          "get",
          [](PythonHost& self, const std::string& controller, const std::string& name) {
            for (const auto& p :
                 self.call([&](auto& client) { return client.parameters(controller); })) {
              if (p.name == name) {
                const py::dict entry = as_dict(p);
                return py::object(entry["value"]);
              }
            }
            throw py::value_error(controller + ": no parameter '" + name + "'");
          },
          arg("controller"), arg("name"), "one parameter's value (a float, a list, or a text)")
      .def(
          "set",
          [](PythonHost& self, const std::string& controller, const std::string& name,
             const py::object& value) {
            std::vector<double> values;
            if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)) {
              values.push_back(value.cast<double>());
            } else {
              values = value.cast<std::vector<double>>();
            }
            return self.call(
                [&](auto& client) { return client.set_parameter(controller, name, values); });
          },
          arg("controller"), arg("name"), arg("value"),
          "sets a parameter (a number, or a list for a per-joint one); returns once the host "
          "applied it, e.g. 'pd.gain_scale = 0.5'");
}

}  // namespace wbi::python
