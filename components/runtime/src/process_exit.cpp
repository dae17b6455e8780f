#include "wbi/runtime/process_exit.hpp"

#include <mutex>
#include <utility>

namespace wbi::runtime {
namespace {

std::mutex mutex;
std::function<void(int)> handler;
int requested = -1;

}  // namespace

void set_process_exit_handler(std::function<void(int exit_code)> new_handler) {
  std::lock_guard lock(mutex);
  handler = std::move(new_handler);
}

void request_process_exit(int exit_code) {
  std::function<void(int)> call;
  {
    std::lock_guard lock(mutex);
    if (requested >= 0) {
      return;
    }
    requested = exit_code < 0 ? 1 : exit_code;
    call = handler;
  }
  if (call) {
    call(exit_code);
  }
}

int requested_process_exit_code() {
  std::lock_guard lock(mutex);
  return requested;
}

}  // namespace wbi::runtime
