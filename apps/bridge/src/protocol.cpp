#include "protocol.hpp"

#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>

namespace wbi::bridge::protocol {

namespace {

using nlohmann::json;

bool is_array(const json& value) { return value.is_array(); }
bool is_string(const json& value) { return value.is_string(); }

void put_le(std::uint8_t* at, std::uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) {
    at[i] = static_cast<std::uint8_t>(value >> (8 * i));
  }
}

json parameter_json(const Parameter& parameter) {
  json out{{"name", parameter.name}};
  if (const auto* number = std::get_if<double>(&parameter.value)) {
    out["value"] = *number;
    out["type"] = "float64";
  } else if (const auto* numbers = std::get_if<std::vector<double>>(&parameter.value)) {
    out["value"] = *numbers;
    out["type"] = "float64_array";
  } else {
    out["value"] = std::get<std::string>(parameter.value);
  }
  return out;
}

// The field `name` of `message`, of the JSON type `is` checks; ProtocolError otherwise.
template <typename Check>
const json& field(const json& message, const char* name, Check is, const char* what) {
  const auto found = message.find(name);
  if (found == message.end() || !is(*found)) {
    throw ProtocolError(message.value("op", std::string("message")) + ": field '" + name +
                        "' must be " + what);
  }
  return *found;
}

std::uint32_t as_u32(const json& value, const std::string& where) {
  if (!value.is_number_unsigned() || value.get<std::uint64_t>() > 0xffffffffu) {
    throw ProtocolError(where + " must be an unsigned 32-bit integer");
  }
  return value.get<std::uint32_t>();
}

std::vector<std::string> names(const json& message, const char* key) {
  std::vector<std::string> out;
  const auto found = message.find(key);
  if (found == message.end()) {
    return out;
  }
  if (!found->is_array()) {
    throw ProtocolError(message.value("op", std::string()) + ": '" + key +
                        "' must be an array of strings");
  }
  for (const auto& name : *found) {
    if (!name.is_string()) {
      throw ProtocolError(message.value("op", std::string()) + ": '" + key +
                          "' must be an array of strings");
    }
    out.push_back(name.get<std::string>());
  }
  return out;
}

// A request id: the spec says string; a number is accepted and echoed as text.
std::string request_id(const json& message) {
  const auto found = message.find("id");
  if (found == message.end() || found->is_null()) {
    return {};
  }
  return found->is_string() ? found->get<std::string>() : found->dump();
}

Parameter parse_parameter(const json& entry) {
  if (!entry.is_object() || !entry.contains("name") || !entry["name"].is_string()) {
    throw ProtocolError("setParameters: each parameter needs a string 'name'");
  }
  Parameter parameter{entry["name"].get<std::string>(), 0.0};
  const auto value = entry.find("value");
  if (value == entry.end() || value->is_null()) {
    throw ProtocolError("setParameters: " + parameter.name +
                        ": no value (parameters cannot be unset)");
  }
  if (value->is_number()) {
    parameter.value = value->get<double>();
  } else if (value->is_string()) {
    parameter.value = value->get<std::string>();
  } else if (value->is_array()) {
    std::vector<double> numbers;
    for (const auto& number : *value) {
      if (!number.is_number()) {
        throw ProtocolError("setParameters: " + parameter.name + ": an array must hold numbers");
      }
      numbers.push_back(number.get<double>());
    }
    parameter.value = std::move(numbers);
  } else {
    throw ProtocolError("setParameters: " + parameter.name +
                        ": the value must be a number, an array of numbers or a string");
  }
  return parameter;
}

Subscribe parse_subscribe(const json& message) {
  Subscribe request;
  for (const auto& entry : field(message, "subscriptions", is_array, "an array")) {
    if (!entry.is_object()) {
      throw ProtocolError("subscribe: each subscription must be an object");
    }
    Subscription subscription;
    subscription.id = as_u32(entry.value("id", json()), "subscribe: 'id'");
    subscription.channel_id = as_u32(entry.value("channelId", json()), "subscribe: 'channelId'");
    if (const auto rate = entry.find("maxRateHz"); rate != entry.end()) {
      if (!rate->is_number() || !(rate->get<double>() >= 0.0) ||
          !std::isfinite(rate->get<double>())) {
        throw ProtocolError("subscribe: 'maxRateHz' must be a finite number >= 0");
      }
      subscription.max_rate_hz = rate->get<double>();
    }
    request.subscriptions.push_back(subscription);
  }
  return request;
}

}  // namespace

std::string server_info(const std::string& name, const std::vector<std::string>& capabilities,
                        const std::vector<std::string>& supported_encodings,
                        const std::string& session_id) {
  json out{{"op", "serverInfo"},
           {"name", name},
           {"capabilities", capabilities},
           {"metadata", json::object()},
           {"sessionId", session_id}};
  if (!supported_encodings.empty()) {
    out["supportedEncodings"] = supported_encodings;
  }
  return out.dump();
}

std::string advertise_services(std::span<const Service> services) {
  json list = json::array();
  for (const auto& service : services) {
    // Both spellings of the spec: requestSchema/responseSchema (first
    // version) and request/response objects (later clients read these).
    list.push_back({{"id", service.id},
                    {"name", service.name},
                    {"type", service.type},
                    {"requestSchema", service.request_schema},
                    {"responseSchema", service.response_schema},
                    {"request",
                     {{"encoding", service.encoding},
                      {"schemaName", service.type + "_Request"},
                      {"schemaEncoding", "jsonschema"},
                      {"schema", service.request_schema}}},
                    {"response",
                     {{"encoding", service.encoding},
                      {"schemaName", service.type + "_Response"},
                      {"schemaEncoding", "jsonschema"},
                      {"schema", service.response_schema}}}});
  }
  return json{{"op", "advertiseServices"}, {"services", std::move(list)}}.dump();
}

std::string service_call_failure(std::uint32_t service_id, std::uint32_t call_id,
                                 const std::string& message) {
  return json{{"op", "serviceCallFailure"},
              {"serviceId", service_id},
              {"callId", call_id},
              {"message", message}}
      .dump();
}

std::string status(StatusLevel level, const std::string& message) {
  return json{{"op", "status"}, {"level", static_cast<int>(level)}, {"message", message}}.dump();
}

std::string advertise(std::span<const Channel> channels) {
  json list = json::array();
  for (const auto& channel : channels) {
    json entry{{"id", channel.id},
               {"topic", channel.topic},
               {"encoding", channel.encoding},
               {"schemaName", channel.schema_name},
               {"schema", channel.schema}};
    if (!channel.schema_encoding.empty()) {
      entry["schemaEncoding"] = channel.schema_encoding;
    }
    list.push_back(std::move(entry));
  }
  return json{{"op", "advertise"}, {"channels", std::move(list)}}.dump();
}

std::string unadvertise(std::span<const std::uint32_t> channel_ids) {
  return json{{"op", "unadvertise"},
              {"channelIds", std::vector<std::uint32_t>(channel_ids.begin(), channel_ids.end())}}
      .dump();
}

std::string parameter_values(std::span<const Parameter> parameters, const std::string& id) {
  json list = json::array();
  for (const auto& parameter : parameters) {
    list.push_back(parameter_json(parameter));
  }
  json out{{"op", "parameterValues"}, {"parameters", std::move(list)}};
  if (!id.empty()) {
    out["id"] = id;
  }
  return out.dump();
}

MessageDataHeader message_data_header(std::uint32_t subscription_id, std::uint64_t receive_ns) {
  MessageDataHeader header{};
  header[0] = 0x01;
  put_le(&header[1], subscription_id, 4);
  put_le(&header[5], receive_ns, 8);
  return header;
}

std::vector<std::uint8_t> fetch_asset_response(std::uint32_t request_id,
                                               const std::optional<std::string>& error,
                                               std::span<const std::uint8_t> data) {
  const std::string message = error.value_or("");
  std::vector<std::uint8_t> out(1 + 4 + 1 + 4 + message.size() + (error ? 0 : data.size()));
  out[0] = 0x04;
  put_le(&out[1], request_id, 4);
  out[5] = error ? 1 : 0;
  put_le(&out[6], message.size(), 4);
  std::copy(message.begin(), message.end(), out.begin() + 10);
  if (!error) {
    std::copy(data.begin(), data.end(),
              out.begin() + 10 + static_cast<std::ptrdiff_t>(message.size()));
  }
  return out;
}

std::vector<std::uint8_t> service_call_response(std::uint32_t service_id, std::uint32_t call_id,
                                                const std::string& encoding,
                                                std::span<const std::uint8_t> payload) {
  std::vector<std::uint8_t> out(1 + 4 + 4 + 4 + encoding.size() + payload.size());
  out[0] = 0x03;
  put_le(&out[1], service_id, 4);
  put_le(&out[5], call_id, 4);
  put_le(&out[9], encoding.size(), 4);
  std::copy(encoding.begin(), encoding.end(), out.begin() + 13);
  std::copy(payload.begin(), payload.end(),
            out.begin() + 13 + static_cast<std::ptrdiff_t>(encoding.size()));
  return out;
}

ClientBinary parse_client_binary(std::span<const std::uint8_t> frame) {
  const auto u32_at = [&](std::size_t at) {
    std::uint32_t value = 0;
    for (int i = 0; i < 4; ++i) {
      value |= static_cast<std::uint32_t>(frame[at + static_cast<std::size_t>(i)]) << (8 * i);
    }
    return value;
  };
  if (frame.empty()) {
    throw ProtocolError("an empty binary message");
  }
  if (frame[0] == 0x01) {
    if (frame.size() < 5) {
      throw ProtocolError("client message data: shorter than its 5-byte header");
    }
    return ClientMessageData{u32_at(1), frame.subspan(5)};
  }
  if (frame[0] == 0x02) {
    if (frame.size() < 13 || frame.size() < 13 + static_cast<std::size_t>(u32_at(9))) {
      throw ProtocolError("service call request: shorter than its header and encoding");
    }
    const std::size_t encoding_size = u32_at(9);
    return ServiceCallRequest{
        u32_at(1), u32_at(5),
        std::string(frame.begin() + 13,
                    frame.begin() + 13 + static_cast<std::ptrdiff_t>(encoding_size)),
        frame.subspan(13 + encoding_size)};
  }
  throw ProtocolError("unknown binary opcode " + std::to_string(frame[0]));
}

ClientRequest parse_client_text(const std::string& text) {
  const json message = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (message.is_discarded()) {
    throw ProtocolError("not JSON: a text message must be a JSON object with an 'op'");
  }
  if (!message.is_object() || !message.contains("op") || !message["op"].is_string()) {
    throw ProtocolError("a text message must be a JSON object with a string 'op'");
  }
  const std::string op = message["op"].get<std::string>();
  if (op == "subscribe") {
    return parse_subscribe(message);
  }
  if (op == "unsubscribe") {
    Unsubscribe request;
    for (const auto& id : field(message, "subscriptionIds", is_array, "an array")) {
      request.subscription_ids.push_back(as_u32(id, "unsubscribe: each subscription id"));
    }
    return request;
  }
  if (op == "getParameters") {
    return GetParameters{names(message, "parameterNames"), request_id(message)};
  }
  if (op == "setParameters") {
    SetParameters request{{}, request_id(message)};
    for (const auto& entry : field(message, "parameters", is_array, "an array")) {
      request.parameters.push_back(parse_parameter(entry));
    }
    return request;
  }
  if (op == "subscribeParameterUpdates") {
    return SubscribeParameterUpdates{names(message, "parameterNames")};
  }
  if (op == "unsubscribeParameterUpdates") {
    return UnsubscribeParameterUpdates{names(message, "parameterNames")};
  }
  if (op == "fetchAsset") {
    FetchAsset request;
    request.uri = field(message, "uri", is_string, "a string").get<std::string>();
    request.request_id = as_u32(message.value("requestId", json()), "fetchAsset: 'requestId'");
    return request;
  }
  if (op == "advertise") {
    ClientAdvertise request;
    for (const auto& entry : field(message, "channels", is_array, "an array")) {
      if (!entry.is_object()) {
        throw ProtocolError("advertise: each channel must be an object");
      }
      ClientChannel channel;
      channel.id = as_u32(entry.value("id", json()), "advertise: 'id'");
      channel.topic = field(entry, "topic", is_string, "a string").get<std::string>();
      channel.encoding = field(entry, "encoding", is_string, "a string").get<std::string>();
      channel.schema_name = entry.value("schemaName", std::string());
      request.channels.push_back(std::move(channel));
    }
    return request;
  }
  if (op == "unadvertise") {
    ClientUnadvertise request;
    for (const auto& id : field(message, "channelIds", is_array, "an array")) {
      request.channel_ids.push_back(as_u32(id, "unadvertise: each channel id"));
    }
    return request;
  }
  if (op == "subscribeConnectionGraph" || op == "unsubscribeConnectionGraph") {
    return Unsupported{op};
  }
  throw ProtocolError("unknown op '" + op + "'");
}

}  // namespace wbi::bridge::protocol
