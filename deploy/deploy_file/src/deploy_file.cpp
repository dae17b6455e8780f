#include "wbi/deploy/deploy_file.hpp"

#include <set>
#include <stdexcept>

#include <wbi/dds/join_options.hpp>

#include "process_entry.hpp"
#include "yaml_fields.hpp"

namespace wbi::deploy {

namespace {

using detail::YamlFields;

// The one range check of a deploy file's domain id: dds's, which also checks
// WBI_DOMAIN_ID and --domain, with this file's line.
int read_domain_id(const YamlFields& in, const YAML::Node& node) {
  try {
    return dds::domain_id_named(node.IsScalar() ? node.Scalar() : "",
                                in.where(node) + ": domain_id");
  } catch (const std::invalid_argument& error) {
    throw std::runtime_error(error.what());
  }
}

std::vector<SummarySpec> read_summaries(const YamlFields& in, const YAML::Node& summary,
                                        const std::set<std::string>& processes) {
  const bool list = summary.IsSequence();
  if (list && summary.size() == 0) {
    in.fail(summary, "summary", "expected {process, match} or a non-empty list of them");
  }
  std::vector<SummarySpec> summaries;
  for (std::size_t i = 0; i < (list ? summary.size() : 1); ++i) {
    const YAML::Node entry = list ? summary[i] : summary;
    const std::string field = list ? "summary[" + std::to_string(i) + "]" : "summary";
    in.only_keys(entry, field, {"process", "match"});
    SummarySpec spec;
    spec.process = in.scalar<std::string>(entry["process"], field + ".process", "a process name");
    spec.match = in.scalar<std::string>(entry["match"], field + ".match", "a text to find");
    if (processes.count(spec.process) == 0) {
      in.fail(entry["process"], field + ".process", "no process named '" + spec.process + "'");
    }
    summaries.push_back(spec);
  }
  return summaries;
}

void read_processes(const YamlFields& in, const YAML::Node& root, DeployFile& deploy) {
  const YAML::Node processes = root["processes"];
  if (!processes || !processes.IsSequence() || processes.size() == 0) {
    in.fail(processes ? processes : root, "processes", "expected a non-empty list of processes");
  }
  const std::vector<std::string> plugins =
      root["plugins"] ? in.string_list(root["plugins"], "plugins") : std::vector<std::string>{};
  std::set<std::string> names;
  for (std::size_t i = 0; i < processes.size(); ++i) {
    const std::string field = "processes[" + std::to_string(i) + "]";
    ProcessSpec process = detail::read_process(in, processes[i], field, plugins);
    if (!names.insert(process.name).second) {
      in.fail(processes[i]["name"], field + ".name", "'" + process.name + "' is used twice");
    }
    deploy.processes.push_back(std::move(process));
  }
  if (const YAML::Node summary = root["summary"]) {
    deploy.summaries = read_summaries(in, summary, names);
  }
}

}  // namespace

DeployFile read_deploy_file(const std::filesystem::path& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path.string());
  } catch (const YAML::BadFile&) {
    throw std::runtime_error(path.string() + ": cannot read the deploy file");
  } catch (const YAML::Exception& error) {
    throw std::runtime_error(path.string() + ":" + std::to_string(error.mark.line + 1) +
                             ": YAML syntax error: " + error.msg);
  }
  return read_deploy_file(root, path);
}

DeployFile read_deploy_file(const YAML::Node& root, const std::filesystem::path& path) {
  if (!root.IsMap()) {
    throw std::runtime_error(path.string() +
                             ": a deploy file is a mapping with a 'processes' list");
  }
  const YamlFields in(path.string());
  in.only_keys(root, "",
               {"domain_id", "qos_file", "environment", "summary", "processes", "plugins",
                kNetworkKey, kSecurityKey});
  DeployFile deploy;
  deploy.path = path;
  // The join keys first: they are all a tool pointed at the file needs.
  deploy.join = read_placement_blocks(root, path.string());
  if (root["domain_id"]) {
    deploy.join.domain_id = read_domain_id(in, root["domain_id"]);
  }
  if (const YAML::Node qos_file = root["qos_file"]) {
    const auto qos_path = path.parent_path() / in.non_empty_text(qos_file, "qos_file");
    if (!std::filesystem::exists(qos_path)) {
      in.fail(qos_file, "qos_file", "no such file: " + qos_path.string());
    }
    deploy.join.qos_file = qos_path.string();
  }
  if (root["environment"]) {
    deploy.environment = in.string_map(root["environment"], "environment");
  }
  read_processes(in, root, deploy);
  return deploy;
}

}  // namespace wbi::deploy
