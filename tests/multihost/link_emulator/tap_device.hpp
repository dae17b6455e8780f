// A TAP device (a virtual Ethernet interface whose frames this process reads
// and writes). The interface may be moved to another network namespace
// (`ip link set NAME netns NS`) while it is open: the descriptor stays valid.
#pragma once

#include <string>

namespace wbi::link_emulator {

class TapDevice {
 public:
  // Creates the interface NAME (at most 15 characters) with IFF_TAP | IFF_NO_PI,
  // non-blocking. Throws std::runtime_error naming NAME and the reason
  // (no /dev/net/tun, not permitted, name taken).
  explicit TapDevice(const std::string& name);
  ~TapDevice();
  TapDevice(const TapDevice&) = delete;
  TapDevice& operator=(const TapDevice&) = delete;

  int fd() const { return fd_; }
  const std::string& name() const { return name_; }

 private:
  std::string name_;
  int fd_ = -1;
};

}  // namespace wbi::link_emulator
