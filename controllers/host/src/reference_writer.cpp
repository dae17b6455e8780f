#include "wbi/controllers/reference_writer.hpp"

#include <stdexcept>

#include <wbi/dds/topics.hpp>

namespace wbi::controllers {

ReferenceWriter::ReferenceWriter(dds::Participant& participant, const std::string& robot,
                                 const std::string& controller, const std::string& input,
                                 const std::string& source)
    : topic_(dds::topics::reference(robot, controller, input)),
      publisher_(participant, topic_, dds::qos::kCommand) {
  point_.header().robot(robot);
  point_.source(source);
}

void ReferenceWriter::write(std::int64_t stamp_ns, std::span<const double> position,
                            std::span<const double> velocity,
                            std::span<const double> acceleration) {
  const std::size_t n = position.size();
  if (n == 0 || n > msg::MAX_REFERENCE_VALUES) {
    throw std::invalid_argument(topic_ + ": a point has 1 to " +
                                std::to_string(msg::MAX_REFERENCE_VALUES) + " values, not " +
                                std::to_string(n));
  }
  for (const auto& [part, values] :
       {std::pair{"velocity", velocity}, std::pair{"acceleration", acceleration}}) {
    if (!values.empty() && values.size() != n) {
      throw std::invalid_argument(topic_ + ": " + part + " has " + std::to_string(values.size()) +
                                  " values, position " + std::to_string(n));
    }
  }
  point_.header().stamp_ns(stamp_ns);
  point_.header().seq(seq_++);
  point_.position().assign(position.begin(), position.end());
  point_.velocity().assign(velocity.begin(), velocity.end());
  point_.acceleration().assign(acceleration.begin(), acceleration.end());
  publisher_.publish(point_);
}

}  // namespace wbi::controllers
