// The arm peer (arm_peer.hpp) as a process of its own, for tests that count
// the allocations of the controller's process alone. Usage: proxy_arm_peer
// <robot>; prints "arm peer: running" once its endpoints exist and runs
// until SIGTERM or SIGINT.
#include <csignal>
#include <cstdio>

#include "arm_peer.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: proxy_arm_peer <robot>\n");
    return 1;
  }
  // Blocked before any thread starts, so every thread inherits the mask and
  // sigwait below is the only receiver.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGTERM);
  sigaddset(&stop_signals, SIGINT);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);
  wbi::test::ArmPeer peer(argv[1]);
  std::printf("arm peer: running\n");
  std::fflush(stdout);
  int received = 0;
  sigwait(&stop_signals, &received);
  return 0;
}
