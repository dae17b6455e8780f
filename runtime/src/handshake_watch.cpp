#include "wbi/runtime/handshake_watch.hpp"

#include <cstdio>
#include <utility>

namespace wbi::runtime {

namespace {
std::chrono::nanoseconds seconds(double s) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::duration<double>(s));
}
}  // namespace

HandshakeWatch::HandshakeWatch(const dds::Participant& participant,
                               std::function<void(const std::string&)> on_stall,
                               HandshakeWatchOptions options)
    : participant_(participant), on_stall_(std::move(on_stall)), options_(options) {
  if (participant_.options().security.enabled()) {
    thread_ = std::thread([this] { run(); });
  }
}

HandshakeWatch::~HandshakeWatch() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) {
    thread_.join();
  }
}

void HandshakeWatch::started() {
  std::lock_guard lock(mutex_);
  started_ = true;
  started_at_ = std::chrono::steady_clock::now();
}

std::string HandshakeWatch::stalled() const {
  const std::string& own = participant_.info().guid_prefix;
  for (const auto& pending : participant_.stalled_handshakes(seconds(options_.stall_s))) {
    const bool our_turn = own < pending.remote.guid_prefix;
    if (!our_turn && pending.waited_s < 2.0 * options_.stall_s) {
      continue;  // the other side restarts first
    }
    const dds::ParticipantInfo& remote = pending.remote;
    char waited[32];
    std::snprintf(waited, sizeof waited, "%.1f", pending.waited_s);
    return "the DDS Security handshake with participant '" + remote.name + "'" +
           (remote.pid > 0 ? " (pid " + std::to_string(remote.pid) + ")" : "") +
           " has been pending for " + waited +
           " s (the Fast DDS 2.9 handshake race, dds/README.md \"Secured start-up\")";
  }
  return {};
}

void HandshakeWatch::run() {
  std::unique_lock lock(mutex_);
  while (!stop_) {
    wake_.wait_for(lock, seconds(options_.period_s), [this] { return stop_; });
    if (stop_) {
      return;
    }
    if (started_ && std::chrono::steady_clock::now() - started_at_ >= seconds(options_.window_s)) {
      return;  // started for good: a later newcomer's stall is the newcomer's to cure
    }
    lock.unlock();
    const std::string why = stalled();
    if (!why.empty()) {
      on_stall_(why);
      return;
    }
    lock.lock();
  }
}

}  // namespace wbi::runtime
