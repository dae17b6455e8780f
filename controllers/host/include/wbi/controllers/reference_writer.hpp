// Publishes a controller's reference input: trajectory points on
// wbi/<robot>/references/<controller>/<input> (idl/references.idl), as a
// planner or a reference generator does (controllers/README.md, "References").
// Points of one input come from one writer, in time order: a point older than
// the last restarts the input (a new run).
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include <wbi/msg/references.h>
#include <wbi/dds/publisher.hpp>

namespace wbi::controllers {

class ReferenceWriter {
 public:
  // source: who sends (in each point, for recordings).
  ReferenceWriter(dds::Participant& participant, const std::string& robot,
                  const std::string& controller, const std::string& input,
                  const std::string& source);

  // The point for robot time stamp_ns (the state's source stamps). velocity and
  // acceleration: as many values as position, or empty (zero). Throws
  // std::invalid_argument on other sizes or more than MAX_REFERENCE_VALUES.
  // Allocates nothing once a point of this size was sent.
  void write(std::int64_t stamp_ns, std::span<const double> position,
             std::span<const double> velocity = {}, std::span<const double> acceleration = {});

  const std::string& topic() const { return topic_; }
  std::uint64_t written() const { return seq_; }

 private:
  std::string topic_;
  dds::Publisher<msg::TrajectoryPoint> publisher_;
  msg::TrajectoryPoint point_;
  std::uint64_t seq_ = 0;
};

}  // namespace wbi::controllers
