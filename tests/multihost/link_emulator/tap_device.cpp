#include "tap_device.hpp"

#include <fcntl.h>
#include <linux/if.h>
#include <linux/if_tun.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace wbi::link_emulator {

TapDevice::TapDevice(const std::string& name) : name_(name) {
  if (name.empty() || name.size() >= IFNAMSIZ) {
    throw std::runtime_error("TAP device name '" + name + "' must have 1 to " +
                             std::to_string(IFNAMSIZ - 1) + " characters");
  }
  fd_ = ::open("/dev/net/tun", O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) {
    throw std::runtime_error("TAP device '" + name +
                             "': cannot open /dev/net/tun: " + std::strerror(errno));
  }
  ifreq request{};
  request.ifr_flags = IFF_TAP | IFF_NO_PI;
  std::memcpy(request.ifr_name, name.c_str(), name.size());
  if (::ioctl(fd_, TUNSETIFF, &request) < 0) {
    const int error = errno;
    ::close(fd_);
    throw std::runtime_error("TAP device '" + name +
                             "': cannot create it: " + std::strerror(error));
  }
}

TapDevice::~TapDevice() { ::close(fd_); }

}  // namespace wbi::link_emulator
