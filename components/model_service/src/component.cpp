#include "wbi/model_service/component.hpp"

#include <filesystem>
#include <map>
#include <string_view>

#include <wbi/dds/topics.hpp>
#include <wbi/model/backend.hpp>
#include <wbi/robot_config/robot_config.hpp>

namespace wbi::model_service {

namespace {

std::string resolve(const std::string& path, const runtime::Parameters& parameters) {
  const std::filesystem::path given(path);
  if (given.is_relative() && !parameters.file().empty() && parameters.file().front() != '<') {
    const auto beside = std::filesystem::path(parameters.file()).parent_path() / given;
    if (std::filesystem::exists(beside)) {
      return beside.string();
    }
  }
  return path;
}

}  // namespace

ModelServiceComponent::ModelServiceComponent() = default;
ModelServiceComponent::~ModelServiceComponent() { release(); }

void ModelServiceComponent::on_configure(const runtime::Parameters& parameters,
                                         const runtime::ComponentContext& context) {
  // The robot: a URDF, or a robot config file (deploy/robots/*.yaml) whose URDF,
  // base and joint armature are the simulation's, so that the served model is
  // the simulated one.
  std::string urdf;
  model::LoadOptions options;
  if (parameters.has("robot_config")) {
    if (parameters.has("urdf")) {
      throw runtime::ParameterError(parameters.where("urdf") +
                                    ": urdf: give urdf or robot_config, not both (the robot "
                                    "config names its URDF)");
    }
    try {
      const robot_config::RobotConfig config = robot_config::load_robot_config(
          resolve(parameters.require<std::string>("robot_config"), parameters));
      urdf = config.urdf;
      options.fixed_base = config.fixed_base;
      options.armature = robot_config::armature_by_joint(config);
    } catch (const std::exception& error) {  // the config's "file:line: key: what"
      throw runtime::ParameterError(parameters.where("robot_config") +
                                    ": robot_config: " + error.what());
    }
  } else {
    urdf = resolve(parameters.require<std::string>("urdf"), parameters);
  }
  options.joints = parameters.get<std::vector<std::string>>("joints", {});
  options.fixed_base = parameters.get<bool>("fixed_base", options.fixed_base);
  // Armature by joint name; over the robot config's joint by joint.
  for (const auto& [joint, value] : parameters.get<std::map<std::string, double>>("armature", {})) {
    options.armature[joint] = value;
  }
  const bool worker_thread = parameters.get<bool>("worker_thread", false);
  const std::string robot = parameters.get<std::string>("robot", "");
  const std::string backend = parameters.get<std::string>("backend", "wbi");
  parameters.reject_unknown();  // before the (slow) loading and any DDS entity
  try {
    model::check_model_backend_name(backend);
  } catch (const std::invalid_argument& error) {
    throw runtime::ParameterError(parameters.where("backend") + ": " + error.what());
  }

  try {
    model_ = model::make_model_backend(backend, urdf, options);
  } catch (const std::exception& error) {
    // The loader names the armature when an entry of it is wrong (unknown or fixed
    // joint, negative or not finite): point at that parameter rather than at urdf.
    const bool armature = std::string_view(error.what()).find("armature") != std::string::npos;
    throw runtime::ParameterError(parameters.where(armature ? "armature" : "urdf") +
                                  ": cannot load the model: " + error.what());
  }
  robot_ = robot.empty() ? model_->model().name : robot;
  evaluator_ = std::make_unique<Evaluator>(*model_, robot_);

  description_ = std::make_unique<dds::Publisher<msg::RobotDescription>>(
      *context.participant, dds::topics::model_description(robot_), dds::qos::kLatched);
  msg::RobotDescription description = evaluator_->description(urdf);
  description.header().stamp_ns(context.clock->now_ns());
  description_->publish(description);

  participant_ = context.participant;
  worker_thread_ = worker_thread;
}

void ModelServiceComponent::on_activate() {
  dds::ServerOptions server_options;
  server_options.handle_on_dds_thread = !worker_thread_;
  server_ = std::make_unique<dds::Server<msg::ModelRequest, msg::ModelReply>>(
      *participant_, dds::topics::model_service(robot_),
      [this](const msg::ModelRequest& request, msg::ModelReply& reply) {
        evaluator_->evaluate(request, reply);
      },
      server_options);
}

void ModelServiceComponent::on_deactivate() { server_.reset(); }

dds::ServerStats ModelServiceComponent::stats() const {
  return server_ ? server_->stats() : dds::ServerStats{};
}

void ModelServiceComponent::release() {
  server_.reset();  // first: no handler runs after this
  description_.reset();
  evaluator_.reset();
  model_.reset();
}

void register_components(runtime::Registry& registry) {
  registry.add<ModelServiceComponent>(
      "model_service", "loads a URDF, publishes its description, answers model requests");
}

}  // namespace wbi::model_service
