#include "wbi/runtime/process_exit.hpp"

#include <mutex>
#include <utility>

namespace wbi::runtime {
namespace {

std::mutex mutex;
std::function<void(int)> handler;
std::optional<int> requested;

}  // namespace

void set_process_exit_handler(std::function<void(int exit_code)> new_handler) {
  std::lock_guard lock(mutex);
  handler = std::move(new_handler);
}

void request_process_exit(int exit_code) {
  std::function<void(int)> call;
  int code = 0;
  {
    std::lock_guard lock(mutex);
    if (requested) {
      return;
    }
    code = exit_code < 0 ? 1 : exit_code;
    requested = code;
    call = handler;
  }
  if (call) {
    call(code);
  }
}

std::optional<int> requested_process_exit_code() {
  std::lock_guard lock(mutex);
  return requested;
}

}  // namespace wbi::runtime
