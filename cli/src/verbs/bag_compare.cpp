// `wbi bag compare A B`: whether two recordings hold the same messages, topic
// by topic in file order, byte for byte; the first difference named (for the
// ground truth: its tick and the quantity). Log and publish times are not
// compared: a `wbi record` file's log times are the wall clock's.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <map>
// GCC 12 reports a false "may be used uninitialized" inside libstdc++'s regex
// compiler in the sanitizer build (as in tools/recording/src/topic_filter.cpp).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <regex>
#pragma GCC diagnostic pop
#include <sstream>
#include <string>
#include <vector>

#include <wbi/msg/sensorsPubSubTypes.h>
#include <wbi/dds/cdr.hpp>
#include <wbi/mcap/reader.hpp>

#include "../options.hpp"
#include "recording_file.hpp"
#include "verbs.hpp"

namespace wbi::cli {

extern const char* const kBagCompareExample;  // also in `wbi bag --help`
const char* const kBagCompareExample = "wbi bag compare run1.mcap run2.mcap";

namespace {

struct TopicMessages {
  std::string type;  // schema name, "" without one
  std::vector<std::vector<std::uint8_t>> data;
};

// Every message's data per topic, in file order (a lockstep run's ground truth
// for 21 s of iCub 3 is some 30 MiB).
std::map<std::string, TopicMessages> read_all(const std::string& file, const std::regex& topics) {
  const mcap::Reader reader(file);
  const auto& info = reader.info();
  require_readable_recording(file, info);
  if (info.truncated) {
    std::cerr << "wbi bag compare: " << truncation_line(file, info) << "\n";
  }
  std::map<std::string, TopicMessages> out;
  auto cursor = reader.messages(mcap::Order::file);
  while (const auto* m = cursor.next()) {
    if (!std::regex_search(m->channel->topic, topics)) {
      continue;
    }
    auto& topic = out[m->channel->topic];
    topic.type = m->schema ? m->schema->name : "";
    topic.data.emplace_back(m->data.begin(), m->data.end());
  }
  return out;
}

std::string number(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

// The first field two samples differ in, bit for bit (a NaN equals itself).
class FirstDifference {
 public:
  const std::string& found() const { return found_; }

  void value(const std::string& name, double a, double b) {
    if (found_.empty() && std::memcmp(&a, &b, sizeof a) != 0) {
      found_ = name + ": " + number(a) + " vs " + number(b);
    }
  }
  template <class Integer>
  void integer(const std::string& name, Integer a, Integer b) {
    if (found_.empty() && a != b) {
      found_ = name + ": " + std::to_string(a) + " vs " + std::to_string(b);
    }
  }
  void text(const std::string& name, const std::string& a, const std::string& b) {
    if (found_.empty() && a != b) {
      found_ = name + ": '" + a + "' vs '" + b + "'";
    }
  }
  template <class Sequence>
  void values(const std::string& name, const Sequence& a, const Sequence& b) {
    if (!found_.empty()) {
      return;
    }
    integer(name + " size", a.size(), b.size());
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
      value(name + "[" + std::to_string(i) + "]", a[i], b[i]);
    }
  }
  template <class Vector3>
  void vector3(const std::string& name, const Vector3& a, const Vector3& b) {
    value(name + ".x", a.x(), b.x());
    value(name + ".y", a.y(), b.y());
    value(name + ".z", a.z(), b.z());
  }
  template <class Wrench>
  void wrench(const std::string& name, const Wrench& a, const Wrench& b) {
    vector3(name + ".force", a.force(), b.force());
    vector3(name + ".torque", a.torque(), b.torque());
  }

 private:
  std::string found_;
};

// GroundTruth (idl/sensors.idl), field by field in the IDL's order.
std::string ground_truth_difference(const msg::GroundTruth& a, const msg::GroundTruth& b) {
  FirstDifference d;
  d.text("header.robot", a.header().robot().to_string(), b.header().robot().to_string());
  d.integer("header.seq", a.header().seq(), b.header().seq());
  d.integer("header.stamp_ns", a.header().stamp_ns(), b.header().stamp_ns());
  d.values("q", a.q(), b.q());
  d.values("dq", a.dq(), b.dq());
  d.values("ddq", a.ddq(), b.ddq());
  d.vector3("base_pose.position", a.base_pose().position(), b.base_pose().position());
  const auto& qa = a.base_pose().orientation();
  const auto& qb = b.base_pose().orientation();
  d.value("base_pose.orientation.w", qa.w(), qb.w());
  d.vector3("base_pose.orientation", qa, qb);
  d.values("base_velocity", a.base_velocity(), b.base_velocity());
  d.values("base_acceleration", a.base_acceleration(), b.base_acceleration());
  d.integer("contact_wrenches size", a.contact_wrenches().size(), b.contact_wrenches().size());
  for (std::size_t i = 0; i < std::min(a.contact_wrenches().size(), b.contact_wrenches().size());
       ++i) {
    d.wrench("contact_wrenches[" + std::to_string(i) + "]", a.contact_wrenches()[i],
             b.contact_wrenches()[i]);
  }
  d.values("applied_torque", a.applied_torque(), b.applied_torque());
  d.integer("push_wrenches size", a.push_wrenches().size(), b.push_wrenches().size());
  for (std::size_t i = 0; i < std::min(a.push_wrenches().size(), b.push_wrenches().size()); ++i) {
    const std::string name = "push_wrenches[" + std::to_string(i) + "]";
    d.text(name + ".link", a.push_wrenches()[i].link().to_string(),
           b.push_wrenches()[i].link().to_string());
    d.wrench(name + ".wrench", a.push_wrenches()[i].wrench(), b.push_wrenches()[i].wrench());
  }
  return d.found().empty() ? "the samples decode equal, their bytes differ" : d.found();
}

// Where message `index` of a topic differs: the ground truth's tick, time and
// quantity; any other type's first differing byte.
std::string describe(const TopicMessages& topic, std::size_t index,
                     const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
  std::ostringstream out;
  out << "message " << index;
  msg::GroundTruth truth_a, truth_b;
  if (topic.type == "wbi::msg::GroundTruth" && dds::decode_cdr<msg::GroundTruth>(a, truth_a) &&
      dds::decode_cdr<msg::GroundTruth>(b, truth_b)) {
    out << " (tick " << truth_a.header().seq()
        << ", t = " << number(1e-9 * static_cast<double>(truth_a.header().stamp_ns()))
        << " s): " << ground_truth_difference(truth_a, truth_b);
    return out.str();
  }
  const auto at = std::mismatch(a.begin(), a.end(), b.begin(), b.end());
  out << ": " << a.size() << " and " << b.size() << " bytes, the first difference at byte "
      << (at.first - a.begin());
  return out.str();
}

int run_compare(Args args) {
  Options options(
      "wbi bag compare A B [options]",
      "Compares two MCAP recordings topic by topic: the same topics, the same number of\n"
      "messages, and each message's data (CDR) byte for byte, in file order. Log and\n"
      "publish times are not compared (a `wbi record` file's log times are the wall\n"
      "clock's). Prints 'identical: …' and exits 0, or the first difference per topic\n"
      "(for wbi::msg::GroundTruth its tick, time and quantity, e.g. 'q[3]: X vs Y')\n"
      "and exits 1. Made for the ground-truth files of lockstep runs (sim_robot's\n"
      "ground_truth_file), which two runs of one deploy file must give the same.");
  options.positional("A", "the first .mcap file");
  options.positional("B", "the second .mcap file");
  options.option("topic", "REGEX", "compare only the topics this matches (search)", "");
  options.example(kBagCompareExample, "two recordings, every topic");
  options.example("wbi bag compare run1.mcap run2.mcap --topic ground_truth",
                  "the ground truth of two lockstep runs (scripts/repro-check does so)");
  if (!options.parse(args)) {
    return kExitOk;
  }
  const std::regex topics(options.get("topic"));
  const auto a = read_all(options.get("A"), topics);
  const auto b = read_all(options.get("B"), topics);
  std::size_t messages = 0;
  std::vector<std::string> differences;
  for (const auto& [name, topic] : a) {
    const auto other = b.find(name);
    if (other == b.end()) {
      differences.push_back(name + ": only in A (" + std::to_string(topic.data.size()) +
                            " messages)");
      continue;
    }
    const auto& da = topic.data;
    const auto& db = other->second.data;
    const std::size_t common = std::min(da.size(), db.size());
    std::size_t i = 0;
    while (i < common && da[i] == db[i]) {
      ++i;
    }
    if (i < common) {
      differences.push_back(name + ": " + describe(topic, i, da[i], db[i]));
    } else if (da.size() != db.size()) {
      differences.push_back(name + ": " + std::to_string(da.size()) + " messages in A, " +
                            std::to_string(db.size()) + " in B (the first " +
                            std::to_string(common) + " identical)");
    }
    messages += common;
  }
  for (const auto& [name, topic] : b) {
    if (a.find(name) == a.end()) {
      differences.push_back(name + ": only in B (" + std::to_string(topic.data.size()) +
                            " messages)");
    }
  }
  if (a.empty() && b.empty()) {
    differences.push_back("no messages to compare in either file");
  }
  if (differences.empty()) {
    std::cout << "identical: " << messages << " messages on " << a.size()
              << " topic(s), byte for byte\n";
    return kExitOk;
  }
  for (const auto& line : differences) {
    std::cout << "differ: " << line << "\n";
  }
  return kExitError;
}

}  // namespace

int run_bag_compare(Args args) { return run_compare(args); }

}  // namespace wbi::cli
