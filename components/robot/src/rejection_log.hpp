// Internal: what the actuator side does with a refused command or control
// parameters message, so that a bad publisher can neither flood the robot's
// log nor hide among good ones.
//
//  - Log: the first rejection of each kind from each sender is one line, e.g.
//      command from 'pd' rejected: joint index 41 out of range (the robot has 7 joints)
//      [first from 'pd' for this reason; repeats are counted, summary every 10 s]
//    The kind is the error text with its numbers and quoted names masked
//    ("joint index # out of range (the robot has # joints)"), so a stream of
//    one mistake is one kind. Repeats are only counted; every summary period,
//    at the next rejection (and when the log is destroyed), one line per kind
//    that recurred gives its count over the period and in all:
//      rejected from 'pd' in the last 10 s: 2000 × command: joint index # out of range … (2001 in
//      all)
//    Senders beyond the first kMaxSenders share their kinds ("(other
//    senders)"). At most kMaxKinds kinds are kept; rejections beyond them are one more
//    kind, "(other rejections)". Control characters in names and errors (text
//    from the wire) are printed as '?'.
//  - Status: a counter per sender on the owner's StatusReport,
//    "rejected_from/<sender>" (commands and parameters), for the first
//    kMaxSenders senders while the report has room; later senders share
//    "rejected_from/(other senders)".
//
// Thread-safe (a mutex); reject() allocates (an error path) and does its I/O
// on the caller's thread, never on the control loop's.
#pragma once

#include <chrono>
#include <cstdint>
#include <iosfwd>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include <wbi/runtime/status_report.hpp>

namespace wbi::robot {

class RejectionLog {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr std::size_t kMaxKinds = 64;
  static constexpr std::size_t kMaxSenders = 6;

  RejectionLog(runtime::StatusReport& report, std::ostream& log,
               Clock::duration summary_period = std::chrono::seconds(10));
  ~RejectionLog();  // prints the summary of what was not summarised yet
  RejectionLog(const RejectionLog&) = delete;
  RejectionLog& operator=(const RejectionLog&) = delete;

  // A rejection after this long without one of its kind from its sender
  // starts a new burst.
  static constexpr Clock::duration kBurstGap = std::chrono::seconds(1);

  // One refused message: `what` ("command", "control parameters"), the
  // sender's name (the message's controller field) and the error text
  // (without control characters: ActuatorSide passes it so). True when it is
  // the first of a burst of its kind from its sender (its first ever, or the
  // first after kBurstGap without one): the caller's event (COMMANDS_REJECTED).
  bool reject(std::string_view what, std::string_view sender, std::string_view error,
              Clock::time_point now = Clock::now());

  // Rejections counted from `sender` (0 when none), as on the status.
  std::uint64_t count(std::string_view sender) const;
  // Lines written so far (first occurrences and summary lines).
  std::uint64_t lines() const;

  // "joint index # out of range (the robot has # joints)": numbers → '#',
  // quoted text → '…'.
  static std::string kind_of(std::string_view error);
  // Control characters (newline, escape…) → '?': text from the wire as one log line.
  static std::string without_control_characters(std::string_view text);
  // A sender's name as it is printed: without_control_characters; empty → "(unnamed)".
  static std::string printable(std::string_view name);

 private:
  struct Kind {
    std::string sender;  // the sender entry's name: printable, or "(other senders)"
    std::string key;     // what + kind_of(error)
    std::uint64_t count = 0;
    std::uint64_t summarised = 0;  // count at the last summary
    Clock::time_point last;        // of its newest rejection (bursts)
  };
  struct Sender {
    std::string name;  // printable
    runtime::StatusCounter* counter = nullptr;
    std::uint64_t count = 0;
  };

  Sender& sender_entry(const std::string& name);
  void summarise(Clock::time_point now);

  runtime::StatusReport& report_;
  std::ostream& log_;
  const Clock::duration period_;
  mutable std::mutex mutex_;
  std::vector<Kind> kinds_;
  std::vector<Sender> senders_;
  Sender other_senders_;
  Clock::time_point last_summary_;
  std::uint64_t lines_ = 0;
};

}  // namespace wbi::robot
