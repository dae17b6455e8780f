// The model service for remote-model tests: a wbi_host process serving the
// project's arm for one robot name, and proxy options that use it.
#pragma once

#include <fstream>
#include <memory>

#include "arm_peer.hpp"
#include "child_process.hpp"

namespace wbi::test {

// A wbi_host process serving the arm's model for robot `robot`.
inline std::unique_ptr<ChildProcess> start_model_service(const std::string& robot) {
  const auto path = binary_dir() / "tests" / ("remote_model_" + robot + ".yaml");
  std::ofstream(path) << "components:\n  - name: model\n    type: model_service\n"
                         "    parameters:\n      urdf: "
                      << project_model("arm7.urdf").string() << "\n      robot: " << robot << "\n";
  auto service = std::make_unique<ChildProcess>(binary_dir() / "bin" / "wbi_host",
                                                std::vector<std::string>{path.string()});
  EXPECT_TRUE(service->wait_for_output("wbi_host: running", 30s)) << service->output();
  return service;
}

inline wbi::DdsInterfaceOptions remote_options(const std::string& robot) {
  auto options = arm_options(robot);
  options.model_source = wbi::DdsInterfaceOptions::ModelSource::remote;
  options.model_timeout = 2s;  // generous: the machine may be busy
  return options;
}

inline std::unique_ptr<wbi::WholeBodyInterface> connect(const wbi::DdsInterfaceOptions& options,
                                                        const wbi::IdList& joints) {
  auto robot = wbi::make_dds_interface(options);
  robot->add_joints(joints);
  robot->init(20s);
  return robot;
}

}  // namespace wbi::test
