// The robots' controller hosts as the protocol sees them. Parameters: each
// hosted controller's declared parameter is "/<robot>/<controller>/<name>",
// read from the host's latched table (wbi/<robot>/controllers/parameters, so a
// get never waits) and set through the host's service (wbi param's call) on a
// worker thread, so that a slow host never stalls the bridge's I/O thread.
// Also "/robot_description" and "/<robot>/robot_description": the URDF text,
// read only. Services (services.hpp) run their calls here too, one at a time.
#pragma once

#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <wbi/dds/participant.hpp>

#include "protocol.hpp"

namespace wbi::controllers {
class HostClient;
}

namespace wbi::bridge {

class ControllerHosts {
 public:
  // Called on a DDS thread with the parameters whose value changed.
  using Changed = std::function<void(const std::vector<protocol::Parameter>& changed)>;
  // Called on the worker thread with a set's outcome: the values applied, and
  // one line per refusal.
  using SetDone = std::function<void(std::vector<protocol::Parameter> applied,
                                     std::vector<std::string> refusals)>;

  // A participant of its own, joined like `options`': its typed endpoints must
  // not share topics with the bridge's raw readers (a participant's topic has
  // one type support: dds/README.md, "One type per topic in a participant").
  ControllerHosts(const dds::ParticipantOptions& options, std::chrono::nanoseconds call_timeout,
                  Changed changed);
  ~ControllerHosts();
  ControllerHosts(const ControllerHosts&) = delete;
  ControllerHosts& operator=(const ControllerHosts&) = delete;

  // Starts following a robot's host (idempotent); its URDF text, when known,
  // becomes its robot_description (the first robot's is also "/robot_description").
  void add_robot(const std::string& robot);
  void set_robot_description(const std::string& robot, const std::string& urdf_text);

  // Current values; names empty: all. Unknown names are listed in `unknown`.
  std::vector<protocol::Parameter> get(const std::vector<std::string>& names,
                                       std::vector<std::string>* unknown) const;
  // Queues the sets; `done` runs once all were tried.
  void set(std::vector<protocol::Parameter> parameters, SetDone done);
  // Runs `job` on the worker with the robot's host client; false when the
  // robot is not known.
  bool run(const std::string& robot, std::function<void(controllers::HostClient& host)> job);

 private:
  struct Robot;
  struct Target {
    Robot* robot = nullptr;
    std::string controller, name;
  };
  std::optional<Target> target_of(const std::string& parameter) const;
  void on_table(Robot& robot, std::vector<protocol::Parameter> table);
  void work();
  void apply(const std::vector<protocol::Parameter>& parameters, const SetDone& done);

  dds::Participant participant_;
  const std::chrono::nanoseconds call_timeout_;
  Changed changed_;
  mutable std::mutex mutex_;
  std::map<std::string, std::unique_ptr<Robot>> robots_;
  std::string first_robot_;
  std::deque<std::function<void()>> jobs_;
  std::condition_variable jobs_ready_;
  bool stopping_ = false;
  std::thread worker_;
};

}  // namespace wbi::bridge
