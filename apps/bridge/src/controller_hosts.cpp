#include "controller_hosts.hpp"

#include <exception>

#include <wbi/msg/controllers.h>
#include <wbi/controllers/host_client.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>

namespace wbi::bridge {

namespace {

std::string robot_description_name(const std::string& robot) {
  return "/" + robot + "/robot_description";
}

protocol::Parameter from_message(const std::string& robot, const msg::ControllerParameter& entry) {
  protocol::Parameter parameter{
      "/" + robot + "/" + entry.controller().to_string() + "/" + entry.name().to_string(), 0.0};
  if (entry.is_text()) {
    parameter.value = entry.text().to_string();
  } else if (entry.values().size() == 1) {
    parameter.value = entry.values()[0];
  } else {
    parameter.value = std::vector<double>(entry.values().begin(), entry.values().end());
  }
  return parameter;
}

std::vector<double> numbers_of(const protocol::Parameter& parameter) {
  if (const auto* number = std::get_if<double>(&parameter.value)) {
    return {*number};
  }
  return std::get<std::vector<double>>(parameter.value);
}

}  // namespace

struct ControllerHosts::Robot {
  std::string name;
  std::string urdf_text;
  std::map<std::string, protocol::Parameter> values;  // by full name
  std::unique_ptr<controllers::HostClient> client;
  std::unique_ptr<dds::Subscriber<msg::ControllerParameters>> table;
};

namespace {
dds::ParticipantOptions named(dds::ParticipantOptions options) {
  options.name += " (parameters)";
  return options;
}
}  // namespace

ControllerHosts::ControllerHosts(const dds::ParticipantOptions& options,
                                 std::chrono::nanoseconds call_timeout, Changed changed)
    : participant_(named(options)), call_timeout_(call_timeout), changed_(std::move(changed)) {
  worker_ = std::thread([this] { work(); });
}

ControllerHosts::~ControllerHosts() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  jobs_ready_.notify_all();
  worker_.join();
  // Subscribers stop their callbacks before the robots they write go.
  for (auto& [name, robot] : robots_) {
    robot->table.reset();
  }
}

void ControllerHosts::add_robot(const std::string& name) {
  {
    std::lock_guard lock(mutex_);
    if (robots_.count(name) != 0) {
      return;
    }
  }
  auto robot = std::make_unique<Robot>();
  robot->name = name;
  robot->client = std::make_unique<controllers::HostClient>(participant_, name, call_timeout_);
  Robot& added = *robot;
  {
    std::lock_guard lock(mutex_);
    robots_[name] = std::move(robot);
    if (first_robot_.empty()) {
      first_robot_ = name;
    }
  }
  // Outside the lock: the latched table's callback may run at once, and takes it.
  added.table = std::make_unique<dds::Subscriber<msg::ControllerParameters>>(
      participant_, dds::topics::controller_parameters(name), dds::qos::kLatched,
      [this, &added](const msg::ControllerParameters& message, const auto&) {
        std::vector<protocol::Parameter> table;
        for (const auto& entry : message.parameters()) {
          table.push_back(from_message(added.name, entry));
        }
        on_table(added, std::move(table));
      });
}

void ControllerHosts::set_robot_description(const std::string& robot,
                                            const std::string& urdf_text) {
  std::lock_guard lock(mutex_);
  if (const auto found = robots_.find(robot); found != robots_.end()) {
    found->second->urdf_text = urdf_text;
  }
}

void ControllerHosts::on_table(Robot& robot, std::vector<protocol::Parameter> table) {
  std::vector<protocol::Parameter> changed;
  {
    std::lock_guard lock(mutex_);
    for (auto& parameter : table) {
      auto& known = robot.values[parameter.name];
      if (known.name.empty() || known.value != parameter.value) {
        changed.push_back(parameter);
        known = std::move(parameter);
      }
    }
  }
  if (!changed.empty() && changed_) {
    changed_(changed);
  }
}

std::vector<protocol::Parameter> ControllerHosts::get(const std::vector<std::string>& names,
                                                      std::vector<std::string>* unknown) const {
  std::lock_guard lock(mutex_);
  std::map<std::string, protocol::Parameter> all;
  for (const auto& [name, robot] : robots_) {
    if (!robot->urdf_text.empty()) {
      all[robot_description_name(name)] = {robot_description_name(name), robot->urdf_text};
      if (name == first_robot_) {
        all["/robot_description"] = {"/robot_description", robot->urdf_text};
      }
    }
    all.insert(robot->values.begin(), robot->values.end());
  }
  std::vector<protocol::Parameter> out;
  if (names.empty()) {
    for (auto& [name, parameter] : all) {
      out.push_back(parameter);
    }
    return out;
  }
  for (const auto& name : names) {
    if (const auto found = all.find(name); found != all.end()) {
      out.push_back(found->second);
    } else if (unknown != nullptr) {
      unknown->push_back(name);
    }
  }
  return out;
}

std::optional<ControllerHosts::Target> ControllerHosts::target_of(
    const std::string& parameter) const {
  // "/<robot>/<controller>/<name>"
  if (parameter.size() < 2 || parameter[0] != '/') {
    return std::nullopt;
  }
  const auto second = parameter.find('/', 1);
  const auto third = second == std::string::npos ? second : parameter.find('/', second + 1);
  if (third == std::string::npos || parameter.find('/', third + 1) != std::string::npos) {
    return std::nullopt;
  }
  const auto robot = robots_.find(parameter.substr(1, second - 1));
  if (robot == robots_.end()) {
    return std::nullopt;
  }
  return Target{robot->second.get(), parameter.substr(second + 1, third - second - 1),
                parameter.substr(third + 1)};
}

void ControllerHosts::set(std::vector<protocol::Parameter> parameters, SetDone done) {
  {
    std::lock_guard lock(mutex_);
    jobs_.push_back([this, parameters = std::move(parameters), done = std::move(done)] {
      apply(parameters, done);
    });
  }
  jobs_ready_.notify_one();
}

bool ControllerHosts::run(const std::string& robot,
                          std::function<void(controllers::HostClient& host)> job) {
  {
    std::lock_guard lock(mutex_);
    const auto found = robots_.find(robot);
    if (found == robots_.end()) {
      return false;
    }
    jobs_.push_back([client = found->second->client.get(), job = std::move(job)] { job(*client); });
  }
  jobs_ready_.notify_one();
  return true;
}

void ControllerHosts::apply(const std::vector<protocol::Parameter>& parameters,
                            const SetDone& done) {
  std::vector<protocol::Parameter> applied;
  std::vector<std::string> refusals;
  for (const auto& parameter : parameters) {
    std::optional<Target> target;
    {
      std::lock_guard lock(mutex_);
      target = target_of(parameter.name);
    }
    if (!target) {
      refusals.push_back(parameter.name +
                         ": no such parameter (names: /<robot>/<controller>/<name>)");
      continue;
    }
    if (std::holds_alternative<std::string>(parameter.value)) {
      refusals.push_back(parameter.name + ": text parameters are set in the deploy file, not live");
      continue;
    }
    try {
      target->robot->client->set_parameter(target->controller, target->name, numbers_of(parameter));
      applied.push_back(parameter);
    } catch (const std::exception& refusal) {
      refusals.push_back(parameter.name + ": " + refusal.what());
    }
  }
  done(std::move(applied), std::move(refusals));
}

void ControllerHosts::work() {
  std::unique_lock lock(mutex_);
  while (true) {
    jobs_ready_.wait(lock, [this] { return stopping_ || !jobs_.empty(); });
    if (stopping_) {
      return;
    }
    auto job = std::move(jobs_.front());
    jobs_.pop_front();
    lock.unlock();
    job();
    lock.lock();
  }
}

}  // namespace wbi::bridge
