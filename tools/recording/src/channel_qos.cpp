#include "channel_qos.hpp"

#include <array>
#include <string>

namespace wbi::recording {

namespace {

struct ProfileFacts {
  const char* name;
  bool reliable;
  bool transient_local;
  int history_depth;  // of the profile's writer
};

// The writer side of deploy/qos_profiles.xml, first match wins in lookups by
// reliability and durability (so best-effort volatile topics — status, request/reply,
// real-time streams — play back as wbi.status).
constexpr std::array<ProfileFacts, 5> kProfiles{{
    {dds::qos::kStream, true, true, 1},
    {dds::qos::kCommand, true, false, 8},
    {dds::qos::kStatus, false, false, 1},
    {dds::qos::kLatched, true, true, 1},
    {dds::qos::kRequestReply, false, false, 64},
}};

const ProfileFacts& profile_with(bool reliable, bool transient_local) {
  for (const auto& profile : kProfiles) {
    if (profile.reliable == reliable && profile.transient_local == transient_local) {
      return profile;
    }
  }
  return kProfiles[2];  // best effort and transient local: no wbi profile; best effort it is
}

}  // namespace

mcap::KeyValues channel_metadata(const dds::TopicInfo& topic) {
  const bool reliable = topic.writers > 0 && topic.writers_reliable;
  const bool transient_local = topic.writers > 0 && topic.writers_transient_local;
  const auto& profile = profile_with(reliable, transient_local);
  return {
      {"reliability", reliable ? "reliable" : "best_effort"},
      {"durability", transient_local ? "transient_local" : "volatile"},
      {"history_kind", "keep_last"},
      {"history_depth", std::to_string(profile.history_depth)},
      {"qos_profile", profile.name},
      {"writers", std::to_string(topic.writers)},
  };
}

const char* profile_for(const mcap::KeyValues& metadata) {
  if (auto named = metadata.find("qos_profile"); named != metadata.end()) {
    for (const auto& profile : kProfiles) {
      if (named->second == profile.name) {
        return profile.name;
      }
    }
  }
  const auto reliability = metadata.find("reliability");
  const auto durability = metadata.find("durability");
  if (reliability == metadata.end() && durability == metadata.end()) {
    return dds::qos::kStream;
  }
  const bool reliable = reliability == metadata.end() || reliability->second == "reliable";
  const bool transient_local =
      durability != metadata.end() && durability->second == "transient_local";
  return profile_with(reliable, transient_local).name;
}

}  // namespace wbi::recording
