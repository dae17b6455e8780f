// WBI_DDS_TRANSPORT between real processes. A peer process that is killed and
// restarted must be heard again each time: with Fast DDS 2.9's shared memory, a
// restarted participant got its predecessor's port number, and its peers kept
// writing into the dead segment (see the "Latency" section of dds/README.md).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>

#include "child_process.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;

// Sets WBI_DDS_TRANSPORT for this process (children get it passed explicitly)
// and restores the previous value.
class TransportEnvironment {
 public:
  explicit TransportEnvironment(const std::string& value) {
    if (const char* old = std::getenv("WBI_DDS_TRANSPORT"); old != nullptr) {
      previous_ = old;
      had_previous_ = true;
    }
    setenv("WBI_DDS_TRANSPORT", value.c_str(), 1);
  }
  ~TransportEnvironment() {
    if (had_previous_) {
      setenv("WBI_DDS_TRANSPORT", previous_.c_str(), 1);
    } else {
      unsetenv("WBI_DDS_TRANSPORT");
    }
  }

 private:
  std::string previous_;
  bool had_previous_ = false;
};

TEST(DdsTransport, AnUnknownTransportIsAClearError) {
  TransportEnvironment environment("carrier-pigeon");
  try {
    wbi::dds::Participant participant("bad_transport");
    FAIL() << "a participant was created with WBI_DDS_TRANSPORT=carrier-pigeon";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("WBI_DDS_TRANSPORT"), std::string::npos)
        << error.what();
    EXPECT_NE(std::string(error.what()).find("carrier-pigeon"), std::string::npos) << error.what();
  }
}

class RestartedPeer : public testing::TestWithParam<const char*> {};

// A talker process publishes samples, each acknowledged by this reader before
// the next, and is killed (SIGKILL: no goodbye) once kPerTalker have arrived;
// a new talker process then does the same, several times. Each new talker
// must be heard, and its wait for acknowledgements needs this process's
// replies to reach it: the direction that a stale shared-memory port broke.
TEST_P(RestartedPeer, EveryNewTalkerProcessIsHeard) {
  constexpr int kTalkers = 4;
  constexpr std::uint64_t kPerTalker = 10;
  TransportEnvironment environment(GetParam());
  wbi::dds::Participant participant("listener");
  wbi::dds::Subscriber<wbi::msg::SensorSample> subscriber(
      participant, wbi::dds::topics::sensors("restart"), wbi::dds::qos::kLatched);
  for (int talker_index = 0; talker_index < kTalkers; ++talker_index) {
    const std::uint64_t before = subscriber.count();
    wbi::test::ChildProcess talker(wbi::test::binary_dir() / "tests" / "wbi_test_talker",
                                   {"restart", "1000000"},
                                   {std::string("WBI_DDS_TRANSPORT=") + GetParam()});
    wbi::dds::Received<wbi::msg::SensorSample> last;
    ASSERT_TRUE(subscriber.wait_newer(last, before + kPerTalker - 1, 20s))
        << "talker " << talker_index << " (transport " << GetParam() << "): received "
        << subscriber.count() - before << " of " << kPerTalker << "\n"
        << talker.output();
    talker.stop(9);
  }
}

INSTANTIATE_TEST_SUITE_P(Transports, RestartedPeer, testing::Values("udp", "shm"));

}  // namespace
