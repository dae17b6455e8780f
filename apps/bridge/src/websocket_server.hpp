// A WebSocket server for the Foxglove protocol, on Boost.Beast: accepts
// clients that offer the subprotocol foxglove.websocket.v1, hands their
// messages to the handlers (on the server's one I/O thread) and writes each
// client's SendQueue. Nothing about channels or DDS here.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "send_queue.hpp"

namespace wbi::bridge {

using ClientId = std::uint64_t;

struct ServerOptions {
  std::string address = "127.0.0.1";
  std::uint16_t port = 8765;  // 0: any free port (port() tells which)
  std::size_t client_queue_bytes = 8u << 20;
  // A larger client message is refused with a status error and skipped; one
  // over 16 times this closes the connection (WebSocket close code 1009).
  std::size_t max_client_message_bytes = 1u << 20;
};

struct ServerHandlers {
  std::function<void(ClientId, const std::string& peer)> opened;
  std::function<void(ClientId, const std::string& text)> text;
  std::function<void(ClientId, std::span<const std::uint8_t> bytes)> binary;
  std::function<void(ClientId)> closed;
};

class WebSocketServer {
 public:
  // Binds and listens; throws std::runtime_error naming the address when it cannot.
  WebSocketServer(const ServerOptions& options, ServerHandlers handlers);
  ~WebSocketServer();  // closes every client and joins the I/O thread
  WebSocketServer(const WebSocketServer&) = delete;
  WebSocketServer& operator=(const WebSocketServer&) = delete;

  std::uint16_t port() const;

  // Any thread. False when the client is gone.
  bool send(ClientId client, OutgoingMessage message);
  // Each client's data messages dropped since the last call, per channel.
  std::map<std::uint32_t, std::uint64_t> take_drops(ClientId client);
  std::size_t client_count() const;
  // Calls `tick` on the I/O thread every `period` until destruction.
  void every(std::chrono::milliseconds period, std::function<void()> tick);

  struct Impl;  // the .cpp's (its sessions name it)

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace wbi::bridge
