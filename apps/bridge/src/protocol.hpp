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

// A service the bridge offers; requests and responses in `encoding` (json).
struct Service {
  std::uint32_t id = 0;
  std::string name, type, encoding, request_schema, response_schema;  // JSON schemas
};

// ---- server → client, JSON ----
// supported_encodings: what clients may publish and call services with.
std::string server_info(const std::string& name, const std::vector<std::string>& capabilities,
                        const std::vector<std::string>& supported_encodings,
                        const std::string& session_id);
std::string advertise_services(std::span<const Service> services);
std::string service_call_failure(std::uint32_t service_id, std::uint32_t call_id,
                                 const std::string& message);
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

// Opcode 0x03: a service's response, in the request's encoding.
std::vector<std::uint8_t> service_call_response(std::uint32_t service_id, std::uint32_t call_id,
                                                const std::string& encoding,
                                                std::span<const std::uint8_t> payload);

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
struct ClientChannel {
  std::uint32_t id = 0;
  std::string topic, encoding, schema_name;
};
struct ClientAdvertise {
  std::vector<ClientChannel> channels;
};
struct ClientUnadvertise {
  std::vector<std::uint32_t> channel_ids;
};
// An op the bridge knows but does not offer (the connection graph): refused
// with a status naming it.
struct Unsupported {
  std::string op;
};

using ClientRequest = std::variant<Subscribe, Unsubscribe, GetParameters, SetParameters,
                                   SubscribeParameterUpdates, UnsubscribeParameterUpdates,
                                   FetchAsset, ClientAdvertise, ClientUnadvertise, Unsupported>;

// Parses one text frame; throws ProtocolError naming what is wrong.
ClientRequest parse_client_text(const std::string& text);

// Binary client frames. The spans point into the frame.
struct ClientMessageData {  // opcode 0x01
  std::uint32_t channel_id = 0;
  std::span<const std::uint8_t> payload;
};
struct ServiceCallRequest {  // opcode 0x02
  std::uint32_t service_id = 0;
  std::uint32_t call_id = 0;
  std::string encoding;
  std::span<const std::uint8_t> payload;
};
using ClientBinary = std::variant<ClientMessageData, ServiceCallRequest>;
ClientBinary parse_client_binary(std::span<const std::uint8_t> frame);

}  // namespace wbi::bridge::protocol
