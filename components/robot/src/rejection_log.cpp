#include "rejection_log.hpp"

#include <algorithm>
#include <cstdio>
#include <ostream>

namespace wbi::robot {

namespace {

constexpr std::size_t kMaxCounterName = 64;  // ComponentStatus: Counter.name is a Name

bool is_digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

std::string seconds(RejectionLog::Clock::duration d) {
  char text[32];
  std::snprintf(text, sizeof text, "%g s", std::chrono::duration<double>(d).count());
  return text;
}

}  // namespace

RejectionLog::RejectionLog(runtime::StatusReport& report, std::ostream& log,
                           Clock::duration summary_period)
    : report_(report), log_(log), period_(summary_period), last_summary_(Clock::now()) {
  kinds_.reserve(kMaxKinds + 1);
  senders_.reserve(kMaxSenders);
  other_senders_.name = "(other senders)";
}

RejectionLog::~RejectionLog() {
  std::lock_guard lock(mutex_);
  summarise(Clock::now());  // the counts not summarised yet
}

std::string RejectionLog::kind_of(std::string_view error) {
  std::string kind;
  kind.reserve(error.size());
  for (std::size_t i = 0; i < error.size(); ++i) {
    const char c = error[i];
    if (c == '\'') {  // a quoted name: masked up to its closing quote
      const std::size_t close = error.find('\'', i + 1);
      kind += "'…'";
      i = close == std::string_view::npos ? error.size() : close;
    } else if (is_digit(c) || ((c == '-' || c == '+') && i + 1 < error.size() &&
                               is_digit(error[i + 1]) && (i == 0 || error[i - 1] == ' '))) {
      // a number: sign, digits, point, exponent
      const auto in_number = [&](std::size_t j) {
        const char d = error[j];
        const char before = error[j - 1];
        return is_digit(d) || d == '.' || ((d == 'e' || d == 'E') && is_digit(before)) ||
               ((d == '-' || d == '+') && (before == 'e' || before == 'E'));
      };
      while (i + 1 < error.size() && in_number(i + 1)) {
        ++i;
      }
      kind += '#';
    } else {
      kind += c;
    }
  }
  return kind;
}

std::string RejectionLog::without_control_characters(std::string_view text) {
  std::string out(text);
  for (char& c : out) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f) {
      c = '?';  // a line stays one line, and no terminal escape goes out
    }
  }
  return out;
}

std::string RejectionLog::printable(std::string_view name) {
  return name.empty() ? "(unnamed)" : without_control_characters(name);
}

RejectionLog::Sender& RejectionLog::sender_entry(const std::string& name) {
  for (Sender& s : senders_) {
    if (s.name == name) {
      return s;
    }
  }
  // Room for this sender's counter, and still one for "(other senders)" and
  // one for the owner's own counters.
  if (senders_.size() < kMaxSenders &&
      report_.counter_count() + 2 < runtime::StatusReport::kMaxCounters) {
    try {
      std::string counter = "rejected_from/" + name;
      counter.resize(std::min(counter.size(), kMaxCounterName));
      runtime::StatusCounter& c = report_.counter(counter);
      senders_.push_back({name, &c, 0});
      return senders_.back();
    } catch (const std::exception&) {
      // the report is full: counted with the others
    }
  }
  if (other_senders_.counter == nullptr) {
    try {
      other_senders_.counter = &report_.counter("rejected_from/(other senders)");
    } catch (const std::exception&) {
      // no room at all: still counted here and in the owner's total
    }
  }
  return other_senders_;
}

bool RejectionLog::reject(std::string_view what, std::string_view sender, std::string_view error,
                          Clock::time_point now) {
  const std::string name = printable(sender);
  std::string key = std::string(what) + ": " + kind_of(error);
  std::lock_guard lock(mutex_);
  bool first_of_burst = false;
  Sender& s = sender_entry(name);
  ++s.count;
  if (s.counter != nullptr) {
    s.counter->add();
  }
  // Kinds per sender entry: senders beyond kMaxSenders share theirs, so that
  // a publisher changing its name at every message fills no table.
  auto kind = std::find_if(kinds_.begin(), kinds_.end(),
                           [&](const Kind& k) { return k.sender == s.name && k.key == key; });
  if (kind == kinds_.end() && kinds_.size() >= kMaxKinds) {
    // full: one more kind for everything else
    key = "(other rejections)";
    kind = std::find_if(kinds_.begin(), kinds_.end(), [&](const Kind& k) { return k.key == key; });
    if (kind == kinds_.end()) {
      kinds_.push_back({"(any)", key, 0, 0, Clock::time_point{}});  // its first: a burst
      kind = kinds_.end() - 1;
      log_ << "rejections: more than " << kMaxKinds
           << " kinds of rejection; further kinds are counted together\n";
      ++lines_;
    }
  }
  if (kind == kinds_.end()) {
    log_ << what << " from '" << name << "' rejected: " << error << " (repeats of this from '"
         << s.name << "' are counted: summary every " << seconds(period_) << ")\n";
    log_.flush();
    ++lines_;
    kinds_.push_back({s.name, key, 1, 1, now});  // logged: nothing to summarise
    first_of_burst = true;
  } else {
    ++kind->count;
    first_of_burst = now - kind->last >= kBurstGap;
    kind->last = now;
  }
  if (now - last_summary_ >= period_) {
    summarise(now);
  }
  return first_of_burst;
}

void RejectionLog::summarise(Clock::time_point now) {
  const auto span = now - last_summary_;
  bool any = false;
  for (Kind& k : kinds_) {
    if (k.count > k.summarised) {
      log_ << "rejected from '" << k.sender << "' in the last " << seconds(span) << ": "
           << (k.count - k.summarised) << " × " << k.key << " (" << k.count << " in all)\n";
      ++lines_;
      k.summarised = k.count;
      any = true;
    }
  }
  if (any) {
    log_.flush();
  }
  last_summary_ = now;
}

std::uint64_t RejectionLog::count(std::string_view sender) const {
  const std::string name = printable(sender);
  std::lock_guard lock(mutex_);
  for (const Sender& s : senders_) {
    if (s.name == name) {
      return s.count;
    }
  }
  return 0;
}

std::uint64_t RejectionLog::lines() const {
  std::lock_guard lock(mutex_);
  return lines_;
}

}  // namespace wbi::robot
