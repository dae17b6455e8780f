#include "simulation_side.hpp"

#include <stdexcept>

#include <fastdds/rtps/common/SerializedPayload.h>
#include <wbi/dds/message_traits.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/mcap/writer.hpp>
#include <wbi/msg/idl_text.hpp>

#include "messages.hpp"

namespace wbi::robot {

// The ground-truth file: one MCAP channel, the tick's sample serialized into
// a payload sized once for the largest sample the type's bounds allow.
class GroundTruthFile {
 public:
  GroundTruthFile(const std::string& path, const std::string& topic)
      : payload_(type_.m_typeSize), writer_(path) {
    const char* name = dds::MessageTraits<wbi::msg::GroundTruth>::kName;
    const auto schema = writer_.add_schema(name, msg::idl_text_for(name));
    channel_ = writer_.add_channel(schema, topic, "cdr",
                                   {{"reliability", "reliable"},
                                    {"durability", "transient_local"},
                                    {"qos_profile", dds::qos::kStream}});
  }

  void write(wbi::msg::GroundTruth& sample) {
    payload_.length = 0;
    payload_.pos = 0;
    if (!type_.serialize(&sample, &payload_)) {
      throw std::runtime_error("ground_truth_file: a sample did not serialize");
    }
    const auto stamp = static_cast<std::uint64_t>(sample.header().stamp_ns());
    writer_.write(channel_, static_cast<std::uint32_t>(sample.header().seq()), stamp, stamp,
                  {payload_.data, payload_.length});
  }

  void close() { writer_.close(); }

 private:
  wbi::msg::GroundTruthPubSubType type_;
  eprosima::fastrtps::rtps::SerializedPayload_t payload_;
  mcap::Writer writer_;
  std::uint16_t channel_ = 0;
};

SimulationSide::SimulationSide(dds::Participant& participant, const std::string& robot,
                               actuation::Duration step_period, bool lockstep,
                               const std::string& ground_truth_file)
    : robot_(robot),
      ground_truth_(participant, dds::topics::ground_truth(robot), dds::qos::kStream),
      clock_(participant, dds::topics::kClock, dds::qos::kStream) {
  clock_message_.step_ns(step_period.count());
  clock_message_.lockstep(lockstep);
  if (!ground_truth_file.empty()) {
    file_ = std::make_unique<GroundTruthFile>(ground_truth_file, dds::topics::ground_truth(robot));
  }
}

SimulationSide::~SimulationSide() = default;

void SimulationSide::publish(const actuation::GroundTruth& truth, std::uint64_t tick,
                             actuation::Time stamp) {
  fill_ground_truth(truth, robot_, tick, stamp.count(), truth_message_);
  ground_truth_.publish(truth_message_);
  if (file_) {
    file_->write(truth_message_);
  }
  clock_message_.time_ns(stamp.count());
  clock_message_.tick(tick);
  clock_.publish(clock_message_);
}

void SimulationSide::close_file() {
  if (file_) {
    file_->close();
    file_.reset();
  }
}

}  // namespace wbi::robot
