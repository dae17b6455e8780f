// The join options of every DDS verb, declared and parsed here once: the same
// spelling on every verb, listed in each verb's --help. Precedence and meaning:
// dds/README.md, "Joining a deployment".
#pragma once

#include <string>

#include <wbi/dds/join_options.hpp>
#include <wbi/dds/participant.hpp>

#include "options.hpp"

namespace wbi::cli {

// Declares --deploy (unless `with_deploy` is false: `wbi launch FILE` has its
// file), --domain, --discovery, --peers, --interfaces, --discovery-server,
// --qos-file, --security and --identity. `identity`: the verb's default
// identity on a secured deployment, shown in --help (empty: none).
void add_join_options(Options& options, bool with_deploy = true, const std::string& identity = "");

// The flags alone (the top layer). Throws UsageError on a bad value.
dds::JoinOverrides join_flags(const Options& options);

// The participant options of a verb: defaults < --deploy FILE's domain,
// network and security blocks < WBI_* environment < flags. `name` names the
// participant; `default_identity` is the verb's identity on a secured
// deployment when neither --identity nor WBI_DDS_SECURITY_IDENTITY gives one
// (empty: the verb needs one given, and says so). Throws UsageError on a bad flag.
dds::ParticipantOptions join_options(const Options& options, const std::string& name,
                                     const std::string& default_identity);

}  // namespace wbi::cli
