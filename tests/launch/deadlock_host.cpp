// wbi_test_deadlock_host: wbi_host's job for the launch tests, with one more
// component type, `deadlock`: a periodic loop that stops for good after
// `after_s` seconds (its loop thread blocks, its status thread goes on), as a
// deadlock in a controller's update() looks from outside. Like a real deadlock
// it does not end on SIGTERM either (the runner joins the loop first): the
// launch kills it after its grace period.
#include <condition_variable>
#include <csignal>
#include <iostream>
#include <mutex>
#include <string>

#include <pthread.h>

#include <wbi/dds/participant.hpp>
#include <wbi/deploy/process_host.hpp>
#include <wbi/launch/launcher.hpp>
#include <wbi/runtime/builtin.hpp>
#include <wbi/runtime/console_line.hpp>
#include <wbi/runtime/host.hpp>

namespace {

class Deadlock final : public wbi::runtime::Component {
 public:
  void on_configure(const wbi::runtime::Parameters& parameters,
                    const wbi::runtime::ComponentContext& /*context*/) override {
    after_ns_ = static_cast<std::int64_t>(parameters.get<double>("after_s", 1.0) * 1e9);
  }
  void update(std::int64_t time_ns, std::int64_t /*period_ns*/) override {
    if (start_ns_ < 0) {
      start_ns_ = time_ns;
    }
    if (time_ns - start_ns_ >= after_ns_) {
      std::unique_lock lock(mutex_);
      never_.wait(lock, [] { return false; });
    }
  }

 private:
  std::int64_t after_ns_ = 0;
  std::int64_t start_ns_ = -1;
  std::mutex mutex_;
  std::condition_variable never_;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::cerr << "usage: wbi_test_deadlock_host DEPLOY.yaml --process NAME\n";
    return 1;
  }
  wbi::runtime::Registry registry;
  wbi::runtime::register_builtin_components(registry);
  registry.add<Deadlock>("deadlock", "its loop blocks for good after after_s seconds");
  wbi::launch::stop_when_launcher_dies();
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  try {
    const wbi::deploy::ProcessHost process = wbi::deploy::load_process_host(argv[1], argv[3]);
    // The deploy's join keys, as wbi_host applies them.
    const wbi::runtime::PlacementReader join{
        {},
        [&process](const YAML::Node&, const std::string&, const std::string& identity,
                   wbi::dds::ParticipantOptions& options) {
          wbi::deploy::apply_join_keys(process.join, identity, options);
        }};
    wbi::runtime::Host host(process.document, argv[1], argv[3], registry, join);
    host.start();
    wbi::runtime::print_line(stdout, "wbi_host: running " + std::to_string(host.size()) +
                                         " component(s) from " + argv[1]);
    int signal_number = 0;
    sigwait(&signals, &signal_number);
    return host.stop().empty() ? 0 : 1;
  } catch (const std::exception& error) {
    std::cerr << "wbi_test_deadlock_host: " << error.what() << "\n";
    return 1;
  }
}
