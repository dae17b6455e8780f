// The Foxglove WebSocket protocol, version 1 (subprotocol foxglove.websocket.v1,
// github.com/foxglove/ws-protocol docs/spec.md): the server's JSON messages and
// binary frames, and the client's requests parsed into plain structs. No
// sockets here, so every message is unit-tested as bytes.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

namespace wbi::bridge::protocol {

inline constexpr const char* kSubprotocol = "foxglove.websocket.v1";

// A client message the bridge cannot take (bad JSON, an unknown op, a missing
// field): answered with a status error carrying what(), never fatal.
struct ProtocolError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

enum class StatusLevel { info = 0, warning = 1, error = 2 };

struct Channel {
  std::uint32_t id = 0;
  std::string topic, encoding, schema_name, schema, schema_encoding;
};

// A parameter as the protocol carries it: a float64, a float64 array or a string.
struct Parameter {
  std::string name;
  std::variant<double, std::vector<double>, std::string> value;
};

// ---- server → client, JSON ----
std::string server_info(const std::string& name, const std::vector<std::string>& capabilities,
                        const std::string& session_id);
std::string status(StatusLevel level, const std::string& message);
std::string advertise(std::span<const Channel> channels);
std::string unadvertise(std::span<const std::uint32_t> channel_ids);
// id: the request's id; empty for an update nobody asked for.
std::string parameter_values(std::span<const Parameter> parameters, const std::string& id);

// ---- server → client, binary ----
inline constexpr std::size_t kMessageDataHeaderSize = 13;
using MessageDataHeader = std::array<std::uint8_t, kMessageDataHeaderSize>;
// Opcode 0x01 and the subscription id and receive time (ns) before a payload.
MessageDataHeader message_data_header(std::uint32_t subscription_id, std::uint64_t receive_ns);
// Opcode 0x04: the asset's bytes, or the reason it could not be read.
std::vector<std::uint8_t> fetch_asset_response(std::uint32_t request_id,
                                               const std::optional<std::string>& error,
                                               std::span<const std::uint8_t> data);

// ---- client → server ----
struct Subscription {
  std::uint32_t id = 0;
  std::uint32_t channel_id = 0;
  // wbi's extension (other servers ignore the field): at most this many
  // messages per second on this subscription; 0: every message.
  double max_rate_hz = 0.0;
};
struct Subscribe {
  std::vector<Subscription> subscriptions;
};
struct Unsubscribe {
  std::vector<std::uint32_t> subscription_ids;
};
struct GetParameters {
  std::vector<std::string> names;  // empty: all
  std::string id;
};
struct SetParameters {
  std::vector<Parameter> parameters;
  std::string id;
};
struct SubscribeParameterUpdates {
  std::vector<std::string> names;  // empty: all
};
struct UnsubscribeParameterUpdates {
  std::vector<std::string> names;  // empty: all
};
struct FetchAsset {
  std::string uri;
  std::uint32_t request_id = 0;
};
// An op the bridge knows but does not offer (client publishing, services,
// the connection graph): refused with a status naming it.
struct Unsupported {
  std::string op;
};

using ClientRequest =
    std::variant<Subscribe, Unsubscribe, GetParameters, SetParameters, SubscribeParameterUpdates,
                 UnsubscribeParameterUpdates, FetchAsset, Unsupported>;

// Parses one text frame; throws ProtocolError naming what is wrong.
ClientRequest parse_client_text(const std::string& text);

}  // namespace wbi::bridge::protocol
