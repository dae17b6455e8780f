// The writer QoS of a recorded topic, kept in its MCAP channel metadata, and
// the wbi QoS profile a player republishes it with.
//
// DDS discovery tells a reader each remote writer's reliability and
// durability, not its history depth; the recorder therefore names the wbi
// profile (deploy/qos_profiles.xml) with that reliability and durability and
// records that profile's history depth.
#pragma once

#include <wbi/dds/participant.hpp>
#include <wbi/mcap/format.hpp>

namespace wbi::recording {

// Metadata keys: "reliability" (reliable|best_effort), "durability"
// (transient_local|volatile), "history_depth", "qos_profile", "writers".
mcap::KeyValues channel_metadata(const dds::TopicInfo& topic);

// The wbi QoS profile to republish a channel with: "qos_profile" when it names
// a known profile, else the one that fits "reliability" and "durability";
// wbi.stream when the metadata says nothing.
const char* profile_for(const mcap::KeyValues& metadata);

}  // namespace wbi::recording
