#include "wbi/controllers/interface_options.hpp"

#include <filesystem>

#include <wbi/dds/participant.hpp>
#include <wbi/dds_interface.hpp>

namespace wbi::controllers {

namespace {
std::chrono::milliseconds milliseconds(double seconds) {
  return std::chrono::milliseconds(static_cast<std::int64_t>(seconds * 1000));
}
}  // namespace

DdsInterfaceOptions read_interface_options(const runtime::Parameters& parameters,
                                           const runtime::ComponentContext& context) {
  DdsInterfaceOptions options;
  options.robot = parameters.require<std::string>("robot");
  const std::string model = parameters.get<std::string>("model", "local");
  if (model != "local" && model != "remote") {
    throw runtime::ParameterError(parameters.where("model") + ": model is '" + model +
                                  "'; expected local or remote");
  }
  options.model_source = model == "remote" ? DdsInterfaceOptions::ModelSource::remote
                                           : DdsInterfaceOptions::ModelSource::local;
  std::filesystem::path urdf = model == "local" ? parameters.require<std::string>("urdf")
                                                : parameters.get<std::string>("urdf", "");
  if (!urdf.empty() && urdf.is_relative() && !parameters.file().empty() &&
      parameters.file() != "<string>") {
    urdf = std::filesystem::path(parameters.file()).parent_path() / urdf;
  }
  options.urdf = urdf.string();
  options.local_model_backend =
      parameters.get<std::string>("model_backend", options.local_model_backend);
  options.model_timeout = milliseconds(parameters.get<double>(
      "model_timeout_s", std::chrono::duration<double>(options.model_timeout).count()));
  options.controller = parameters.get<std::string>("controller", context.instance);
  const auto claim = parameters.get<std::string>("claim", "claim");
  if (const auto parsed = claim_from_text(claim)) {
    options.claim = *parsed;
  } else {
    throw runtime::ParameterError(parameters.where("claim") + ": claim is '" + claim +
                                  "': expected claim, force or none");
  }
  options.max_age_s = parameters.get<double>("max_age_s", options.max_age_s);
  // The raw sensor samples from the start (else from a controller's first
  // read of them, which then waits for one: DdsInterfaceOptions::read_sensors).
  options.read_sensors = parameters.get<bool>("read_sensors", false);
  // The host's participant: one secured participant per process (see
  // DdsInterfaceOptions::shared_participant).
  options.participant = context.participant->options();
  options.shared_participant = context.participant;
  return options;
}

}  // namespace wbi::controllers
