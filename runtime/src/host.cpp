#include "wbi/runtime/host.hpp"

#include <filesystem>
#include <set>
#include <stdexcept>

#include <yaml-cpp/yaml.h>

#include <wbi/dds/domain_id.hpp>
#include <wbi/dds/join_options.hpp>
#include <wbi/dds/participant.hpp>

namespace wbi::runtime {

namespace {

std::string at(const std::string& file, const YAML::Node& node) {
  return file + ":" + std::to_string(node.Mark().line + 1);
}

// Rejects keys of `map` outside `known`.
void check_keys(const std::string& file, const YAML::Node& map, const std::set<std::string>& known,
                const std::string& context) {
  for (const auto& entry : map) {
    const std::string key = entry.first.Scalar();
    if (known.count(key) == 0) {
      std::string list;
      for (const auto& name : known) {
        list += list.empty() ? "" : ", ";
        list += name;
      }
      throw ParameterError(at(file, entry.first) + ": " + context + ": unknown key '" + key +
                           "' (known: " + list + ")");
    }
  }
}

template <class T>
T scalar(const std::string& file, const YAML::Node& map, const std::string& key, const T& fallback,
         const std::string& context, const char* kind) {
  const YAML::Node node = map[key];
  if (!node) {
    return fallback;
  }
  try {
    if (!node.IsScalar()) {
      throw YAML::Exception(node.Mark(), "not a scalar");
    }
    return node.as<T>();
  } catch (const YAML::Exception&) {
    throw ParameterError(at(file, node) + ": " + context + ": '" + key + "' must be " + kind);
  }
}

}  // namespace

Host::Host(const std::string& file, const Registry& registry, PlacementReader placement) {
  load(file, false, file, registry, placement);
}

Host::Host(const YAML::Node& document, const std::string& file, const std::string& identity,
           const Registry& registry, PlacementReader placement) {
  build(document, file, identity, registry, placement, /*paths_from_file=*/true);
}

std::unique_ptr<Host> Host::from_string(const std::string& yaml, const Registry& registry,
                                        const std::string& file, PlacementReader placement) {
  std::unique_ptr<Host> host(new Host());
  host->load(yaml, true, file, registry, placement);
  return host;
}

namespace {
YAML::Node parse(const std::string& source, bool is_text, const std::string& file) {
  try {
    return is_text ? YAML::Load(source) : YAML::LoadFile(source);
  } catch (const YAML::BadFile&) {
    throw ParameterError(file + ": cannot read the host file");
  } catch (const YAML::Exception& error) {
    throw ParameterError(file + ":" + std::to_string(error.mark.line + 1) + ": " + error.msg);
  }
}
}  // namespace

YAML::Node read_host_file(const std::string& file) { return parse(file, false, file); }

void Host::load(const std::string& source, bool is_text, const std::string& file,
                const Registry& registry, const PlacementReader& placement) {
  build(parse(source, is_text, file), file, "", registry, placement,
        /*paths_from_file=*/!is_text);
}

void Host::build(const YAML::Node& root, const std::string& file, const std::string& identity,
                 const Registry& registry, const PlacementReader& placement, bool paths_from_file) {
  if (!root.IsMap()) {
    throw ParameterError(file + ": a host file is a map with a 'components' list");
  }
  const std::string context = "host file";
  // The runtime's own keys, and those the placement reader reads.
  // `plugins` is read by the program before it makes the registry (plugins.hpp).
  std::set<std::string> known{"domain_id",       "qos_file",   "clock",
                              "status_period_s", "components", "plugins"};
  if (placement) {
    known.insert(placement.keys.begin(), placement.keys.end());
  }
  check_keys(file, root, known, context);

  dds::ParticipantOptions options;
  const std::string domain_kind = "an integer in " + dds::domain_id_range();
  options.domain_id =
      scalar<int>(file, root, "domain_id", options.domain_id, context, domain_kind.c_str());
  if (options.domain_id < 0 || options.domain_id > dds::kMaxDomainId) {
    throw ParameterError(at(file, root["domain_id"]) + ": host file: 'domain_id' must be in " +
                         dds::domain_id_range());
  }
  // The deploy file's QoS file (relative to it), as `wbi launch` passes it in
  // WBI_QOS_FILE: a process started by hand on another host gets the same QoS.
  if (const std::string qos_file =
          scalar<std::string>(file, root, "qos_file", "", context, "a path");
      !qos_file.empty()) {
    const auto path = std::filesystem::path(paths_from_file ? file : "").parent_path() / qos_file;
    if (!std::filesystem::exists(path)) {
      throw ParameterError(at(file, root["qos_file"]) +
                           ": host file: 'qos_file': no such file: " + path.string());
    }
    options.qos_file = path.string();
  }
  const std::string clock = scalar<std::string>(file, root, "clock", "system", context, "a string");
  const double status_period_s =
      scalar<double>(file, root, "status_period_s", 1.0, context, "a number of seconds");
  if (status_period_s < 0.0) {
    throw ParameterError(at(file, root["status_period_s"]) +
                         ": host file: 'status_period_s' must be >= 0");
  }
  const YAML::Node list = root["components"];
  if (!list || !list.IsSequence()) {
    throw ParameterError((list ? at(file, list) : file) +
                         ": host file: 'components' must be a list of components");
  }

  // Check every entry before creating anything.
  struct Spec {
    std::string name;
    std::string type;
    double rate_hz;
    YAML::Node parameters;
  };
  std::vector<Spec> specs;
  std::set<std::string> names;
  for (const auto& item : list) {
    if (!item.IsMap()) {
      throw ParameterError(at(file, item) + ": host file: a component is a map with name and type");
    }
    check_keys(file, item, {"name", "type", "rate_hz", "parameters"}, "component");
    std::string name;
    std::string type;
    name = scalar<std::string>(file, item, "name", "", "component", "a string");
    if (name.empty()) {
      throw ParameterError(at(file, item) + ": component: missing 'name'");
    }
    const std::string who = "component '" + name + "'";
    type = scalar<std::string>(file, item, "type", "", who, "a string");
    if (type.empty()) {
      throw ParameterError(at(file, item) + ": " + who + ": missing 'type'");
    }
    if (!registry.contains(type)) {
      try {
        (void)registry.create(type);
      } catch (const std::invalid_argument& error) {
        throw ParameterError(at(file, item["type"]) + ": " + who + ": " + error.what());
      }
    }
    const double rate_hz = scalar<double>(file, item, "rate_hz", 0.0, who, "a number [Hz]");
    if (!(rate_hz >= 0.0)) {
      throw ParameterError(at(file, item["rate_hz"]) + ": " + who + ": 'rate_hz' must be >= 0");
    }
    if (!names.insert(name).second) {
      throw ParameterError(at(file, item) + ": " + who + ": the name is used twice");
    }
    // Copy-constructed: assigning a YAML::Node aliases it (and throws for a missing key).
    specs.push_back(Spec{name, type, rate_hz, item["parameters"]});
  }

  // One process of a deploy file is named after it: events, discovery and
  // claim lines then say "controller", not which program hosts it.
  options.name = identity.empty() ? "wbi_host" : identity;
  try {
    // Across hosts and DDS Security (deploy/README.md); the identity is the process's name.
    if (placement) {
      placement.read(root, file, identity, options);
    }
    dds::apply_environment(options);
  } catch (const ParameterError&) {
    throw;
  } catch (const std::exception& error) {
    throw ParameterError(error.what());
  }
  participant_ = std::make_unique<dds::Participant>(options);
  if (clock == "system") {
    clock_ = std::make_unique<SystemClock>();
  } else if (clock == "simulation") {
    clock_ = std::make_unique<SimulationClock>(*participant_);
  } else {
    throw ParameterError(at(file, root["clock"]) +
                         ": host file: 'clock' must be system or simulation, got '" + clock + "'");
  }
  for (const auto& spec : specs) {
    RunnerOptions runner_options;
    runner_options.rate_hz = spec.rate_hz;
    runner_options.status_period_s = status_period_s;
    ComponentContext component_context{spec.name, spec.type, participant_.get(), clock_.get()};
    Entry entry{std::make_unique<ComponentRunner>(registry.create(spec.type), component_context,
                                                  runner_options),
                Parameters(spec.parameters, file, "component '" + spec.name + "'")};
    components_.push_back(std::move(entry));
  }
}

Host::~Host() { stop(); }

void Host::start() {
  for (auto& entry : components_) {
    try {
      entry.runner->configure(entry.parameters);
      entry.runner->activate();
    } catch (...) {
      stop();
      throw;
    }
  }
}

std::vector<std::string> Host::stop() {
  std::vector<std::string> errors;
  for (auto it = components_.rbegin(); it != components_.rend(); ++it) {
    ComponentRunner& runner = *it->runner;
    try {
      if (runner.state() == LifecycleState::active) {
        runner.deactivate();
      }
      if (runner.state() == LifecycleState::inactive) {
        runner.cleanup();
      }
      if (runner.state() != LifecycleState::finalized) {
        runner.shutdown();
      }
    } catch (const std::exception& error) {
      errors.emplace_back(error.what());
      if (runner.state() != LifecycleState::finalized) {
        try {
          runner.shutdown();
        } catch (const std::exception& again) {
          errors.emplace_back(again.what());
        }
      }
    }
  }
  return errors;
}

ComponentRunner& Host::component(const std::string& instance) {
  for (auto& entry : components_) {
    if (entry.runner->context().instance == instance) {
      return *entry.runner;
    }
  }
  throw std::invalid_argument("no component named '" + instance + "'");
}

}  // namespace wbi::runtime
