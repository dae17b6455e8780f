// Secured start-up that completes: Fast DDS 2.9's DDS Security handshake race
// (dds/README.md, "Secured start-up") can leave a pair of participants that
// discovered each other at the same moment unauthenticated for good, so a
// controller waits for a robot it never sees. A host watches its own
// participant's pending handshakes while it starts; when one has been pending
// for `stall_s` (its own turn: the side whose GUID prefix is the smaller
// one) or twice that (the other side, should the first not restart, e.g. a
// tool), it ends the process with kExitStartStalled and `wbi launch` starts
// it again: a new participant is a new pair, whose handshake is a new draw.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include <wbi/dds/participant.hpp>

namespace wbi::runtime {

struct HandshakeWatchOptions {
  double stall_s = 5.0;    // pending this long on our turn: restart
  double window_s = 10.0;  // after the host has started: only said, never restarted
  double period_s = 0.25;  // how often the participant is asked
};

class HandshakeWatch {
 public:
  // `on_stall(why)` is called at most once, from the watch's thread, when this
  // process should start again. Does nothing for a participant without security.
  HandshakeWatch(const dds::Participant& participant,
                 std::function<void(const std::string&)> on_stall,
                 HandshakeWatchOptions options = {});
  ~HandshakeWatch();
  HandshakeWatch(const HandshakeWatch&) = delete;
  HandshakeWatch& operator=(const HandshakeWatch&) = delete;

  // The host's components run: from window_s on, a stall is no longer this
  // process's to cure by restarting (it may be running an experiment).
  void started();

 private:
  void run();
  // The first remote whose handshake stalled on our watch, as a line; empty if none.
  std::string stalled() const;

  const dds::Participant& participant_;
  std::function<void(const std::string&)> on_stall_;
  HandshakeWatchOptions options_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::chrono::steady_clock::time_point started_at_{};
  bool started_ = false;
  std::thread thread_;
};

}  // namespace wbi::runtime
