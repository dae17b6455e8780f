// A Foxglove-protocol client for the bridge's tests, on Boost.Beast: the
// handshake with a chosen subprotocol, text and binary frames, and reads
// bounded in time (a read that times out leaves the client closed: the test
// has failed by then).
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>  // before Boost: 1.74's asio/awaitable.hpp needs std::exchange
#include <vector>

#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>
#include <nlohmann/json.hpp>

namespace wbi::test {

class WsTestClient {
 public:
  struct Frame {
    bool text = false;
    std::string bytes;
    nlohmann::json json() const { return nlohmann::json::parse(bytes); }
    std::uint32_t subscription() const { return read_le(1, 4); }
    std::uint64_t receive_ns() const { return read_le(5, 8); }
    std::string payload() const { return bytes.substr(13); }
    std::uint64_t read_le(std::size_t at, int count) const {
      std::uint64_t value = 0;
      for (int i = 0; i < count; ++i) {
        value |= static_cast<std::uint64_t>(static_cast<std::uint8_t>(bytes.at(at + i))) << (8 * i);
      }
      return value;
    }
  };

  // Throws boost::system::system_error when the handshake is refused.
  explicit WsTestClient(std::uint16_t port,
                        const std::string& subprotocol = "foxglove.websocket.v1")
      : ws_(io_) {
    boost::asio::ip::tcp::endpoint endpoint(boost::asio::ip::make_address("127.0.0.1"), port);
    boost::beast::get_lowest_layer(ws_).connect(endpoint);
    ws_.set_option(boost::beast::websocket::stream_base::decorator(
        [subprotocol](boost::beast::websocket::request_type& request) {
          request.set(boost::beast::http::field::sec_websocket_protocol, subprotocol);
        }));
    ws_.read_message_max(64u << 20);
    ws_.handshake("127.0.0.1:" + std::to_string(port), "/");
  }

  void send_text(const std::string& text) {
    ws_.text(true);
    ws_.write(boost::asio::buffer(text));
  }
  void send_json(const nlohmann::json& message) { send_text(message.dump()); }
  void send_binary(const std::vector<std::uint8_t>& bytes) {
    ws_.binary(true);
    ws_.write(boost::asio::buffer(bytes));
  }

  // The next frame, or nullopt when none came within `timeout`.
  std::optional<Frame> read(std::chrono::milliseconds timeout) {
    if (closed_) {
      return std::nullopt;
    }
    bool done = false;
    boost::system::error_code error;
    buffer_.consume(buffer_.size());
    ws_.async_read(buffer_, [&](boost::system::error_code ec, std::size_t) {
      error = ec;
      done = true;
    });
    io_.restart();
    io_.run_for(timeout);
    if (!done) {
      closed_ = true;
      boost::beast::get_lowest_layer(ws_).close();
      io_.restart();
      io_.run_for(std::chrono::seconds(1));
      return std::nullopt;
    }
    if (error) {
      closed_ = true;
      return std::nullopt;
    }
    return Frame{ws_.got_text(), boost::beast::buffers_to_string(buffer_.data())};
  }

  // Reads until a JSON message with this op (others are skipped, binary
  // frames too); nullopt after `timeout`.
  std::optional<nlohmann::json> next_json(const std::string& op,
                                          std::chrono::milliseconds timeout) {
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < end) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
          end - std::chrono::steady_clock::now());
      const auto frame = read(std::max(left, std::chrono::milliseconds(1)));
      if (!frame) {
        return std::nullopt;
      }
      if (frame->text) {
        auto message = frame->json();
        if (message.value("op", "") == op) {
          return message;
        }
      }
    }
    return std::nullopt;
  }

 private:
  boost::asio::io_context io_;
  boost::beast::websocket::stream<boost::beast::tcp_stream> ws_;
  boost::beast::flat_buffer buffer_;
  bool closed_ = false;
};

}  // namespace wbi::test
