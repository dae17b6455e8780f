// How the launched processes and the launcher join the deployment: the
// launcher's join options and participant, and each child's environment.
#include <unistd.h>

#include <map>
#include <string>
#include <vector>

#include <wbi/dds/join_options.hpp>
#include <wbi/dds/participant.hpp>

#include "launcher_impl.hpp"

extern char** environ;

namespace wbi::launch {

namespace detail {

std::vector<std::string> Launcher::environment_for(const ProcessSpec& spec) const {
  std::map<std::string, std::string> env;
  for (char** e = environ; *e != nullptr; ++e) {
    const std::string entry = *e;
    const auto eq = entry.find('=');
    env[entry.substr(0, eq)] = eq == std::string::npos ? "" : entry.substr(eq + 1);
  }
  // The processes read the deploy file too, then the environment: the
  // launcher's resolved domain and QoS file, and its flags, go there, so
  // that every process joins as the launcher did (dds/README.md).
  const dds::ParticipantOptions join = join_options();
  env["WBI_DOMAIN_ID"] = std::to_string(join.domain_id);
  if (!join.qos_file.empty()) {
    env["WBI_QOS_FILE"] = join.qos_file;
  }
  const dds::JoinOverrides& flags = options_.join;
  auto joined = [](const std::vector<std::string>& list) {
    std::string text;
    for (const auto& item : list) {
      text += (text.empty() ? "" : ",") + item;
    }
    return text;
  };
  if (flags.discovery) env["WBI_DDS_DISCOVERY"] = dds::discovery_name(*flags.discovery);
  if (flags.peers || flags.discovery_server || flags.interfaces) {
    env["WBI_DDS_DISCOVERY"] = dds::discovery_name(join.discovery);
  }
  if (flags.peers) env["WBI_DDS_PEERS"] = joined(*flags.peers);
  if (flags.interfaces) env["WBI_DDS_INTERFACES"] = joined(*flags.interfaces);
  if (flags.discovery_server) env["WBI_DDS_DISCOVERY_SERVER"] = *flags.discovery_server;
  if (flags.security_directory) env["WBI_DDS_SECURITY_DIRECTORY"] = *flags.security_directory;
  // Each process joins as its own name, not as one identity for all.
  env.erase("WBI_DDS_SECURITY_IDENTITY");
  // wbi_host stops when this process dies, even by SIGKILL (apps/host/main.cpp).
  env[kLauncherPidVariable] = std::to_string(getpid());
  for (const auto& [key, value] : deploy_.environment) {
    env[key] = value;
  }
  for (const auto& [key, value] : spec.environment) {
    env[key] = value;
  }
  std::vector<std::string> entries;
  for (const auto& [key, value] : env) {
    entries.push_back(key + "=" + value);
  }
  return entries;
}

// The launcher's own participant (made when first needed): waits for topics,
// hears heartbeats; the deploy's domain, QoS, network and security.
dds::Participant& Launcher::participant() {
  if (!participant_) {
    participant_.emplace(join_options());
  }
  return *participant_;
}

// defaults < deploy file < environment < flags (dds/README.md, "Joining a deployment").
dds::ParticipantOptions Launcher::join_options() const {
  dds::ParticipantOptions join;
  join.name = "wbi launch";
  deploy::apply_join_keys(deploy_.join, "launcher", join);
  // A process's identity is its own; the launcher's is "launcher" (or the
  // file's) whatever the environment says.
  const std::string identity = join.security.identity;
  dds::apply_environment(join);
  join.security.identity = identity;
  dds::apply(options_.join, join);
  return join;
}

}  // namespace detail

}  // namespace wbi::launch
