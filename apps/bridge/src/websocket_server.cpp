#include "websocket_server.hpp"

#include <array>
#include <future>
#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>  // before Boost: 1.74's asio/awaitable.hpp uses std::exchange without it

#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>

#include "protocol.hpp"

namespace wbi::bridge {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;
using error_code = boost::system::error_code;

namespace {

constexpr std::size_t kHardLimitFactor = 16;

// Whether a Sec-WebSocket-Protocol list ("a, b") offers `wanted`.
bool offers(std::string_view list, std::string_view wanted) {
  while (!list.empty()) {
    const auto comma = list.find(',');
    auto item = list.substr(0, comma);
    while (!item.empty() && item.front() == ' ') {
      item.remove_prefix(1);
    }
    while (!item.empty() && item.back() == ' ') {
      item.remove_suffix(1);
    }
    if (item == wanted) {
      return true;
    }
    list = comma == std::string_view::npos ? std::string_view() : list.substr(comma + 1);
  }
  return false;
}

}  // namespace

class Session;

// A periodic call on the I/O thread (WebSocketServer::every).
struct Ticker {
  asio::steady_timer timer;
  std::chrono::milliseconds period;
  std::function<void()> tick;
};

struct WebSocketServer::Impl {
  Impl(const ServerOptions& options_, ServerHandlers handlers_)
      : options(options_), handlers(std::move(handlers_)), acceptor(io) {}

  void accept_next();
  void opened(const std::shared_ptr<Session>& session);
  void closed(ClientId id);
  std::shared_ptr<Session> find(ClientId id) const;
  void arm(const std::shared_ptr<Ticker>& ticker);

  ServerOptions options;
  ServerHandlers handlers;
  asio::io_context io;
  tcp::acceptor acceptor;
  std::uint16_t port = 0;
  std::thread thread;
  mutable std::mutex mutex;
  std::map<ClientId, std::shared_ptr<Session>> sessions;  // open ones only
  ClientId next_id = 1;
  std::vector<std::shared_ptr<Ticker>> tickers;
};

void WebSocketServer::Impl::arm(const std::shared_ptr<Ticker>& ticker) {
  ticker->timer.expires_after(ticker->period);
  ticker->timer.async_wait([this, ticker](error_code ec) {
    if (!ec) {
      ticker->tick();
      arm(ticker);
    }
  });
}

// One client: the HTTP upgrade, then a read loop and a write loop.
class Session : public std::enable_shared_from_this<Session> {
 public:
  Session(tcp::socket socket, ClientId id, WebSocketServer::Impl& server)
      : queue(server.options.client_queue_bytes),
        id_(id),
        server_(server),
        ws_(std::move(socket)) {}

  void start() {
    beast::get_lowest_layer(ws_).expires_after(std::chrono::seconds(10));
    http::async_read(
        ws_.next_layer(), buffer_, request_,
        [self = shared_from_this()](error_code ec, std::size_t) { self->on_request(ec); });
  }

  void send(OutgoingMessage message) {
    if (queue.push(std::move(message))) {
      asio::post(ws_.get_executor(), [self = shared_from_this()] { self->write_next(); });
    }
  }

  void close() {
    error_code ignored;
    beast::get_lowest_layer(ws_).socket().shutdown(tcp::socket::shutdown_both, ignored);
    beast::get_lowest_layer(ws_).socket().close(ignored);
  }

  ClientId id() const { return id_; }
  std::string peer() const {
    error_code ec;
    const auto endpoint = beast::get_lowest_layer(ws_).socket().remote_endpoint(ec);
    return ec ? std::string("?")
              : endpoint.address().to_string() + ":" + std::to_string(endpoint.port());
  }

  SendQueue queue;

 private:
  void on_request(error_code ec) {
    if (ec) {
      return;  // not HTTP, or gone before its request: never a client
    }
    const auto offered = request_[http::field::sec_websocket_protocol];
    if (!websocket::is_upgrade(request_) ||
        !offers(std::string_view(offered.data(), offered.size()), protocol::kSubprotocol)) {
      refuse();
      return;
    }
    beast::get_lowest_layer(ws_).expires_never();
    ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
    ws_.set_option(websocket::stream_base::decorator([](websocket::response_type& response) {
      response.set(http::field::sec_websocket_protocol, protocol::kSubprotocol);
      response.set(http::field::server, "wbi bridge");
    }));
    ws_.read_message_max(server_.options.max_client_message_bytes * kHardLimitFactor);
    ws_.auto_fragment(false);  // one frame per message: fewer writes for a sample
    ws_.async_accept(request_, [self = shared_from_this()](error_code accept_error) {
      if (!accept_error) {
        self->server_.opened(self);
        self->read_next();
      }
    });
  }

  // A plain HTTP request, or a WebSocket without the subprotocol: told why.
  void refuse() {
    auto response = std::make_shared<http::response<http::string_body>>(http::status::bad_request,
                                                                        request_.version());
    response->set(http::field::content_type, "text/plain");
    response->body() = std::string(
                           "wbi bridge speaks the Foxglove WebSocket protocol: connect with "
                           "the WebSocket subprotocol ") +
                       protocol::kSubprotocol + "\n";
    response->prepare_payload();
    http::async_write(
        ws_.next_layer(), *response,
        [self = shared_from_this(), response](error_code, std::size_t) { self->close(); });
  }

  void read_next() {
    ws_.async_read(buffer_, [self = shared_from_this()](error_code ec, std::size_t bytes) {
      self->on_read(ec, bytes);
    });
  }

  void on_read(error_code ec, std::size_t bytes) {
    if (ec) {
      server_.closed(id_);
      return;
    }
    if (bytes > server_.options.max_client_message_bytes) {
      send(OutgoingMessage::json(protocol::status(
          protocol::StatusLevel::error,
          "message of " + std::to_string(bytes) + " bytes refused: the limit is " +
              std::to_string(server_.options.max_client_message_bytes) + " bytes")));
    } else if (ws_.got_text()) {
      if (server_.handlers.text) {
        server_.handlers.text(id_, beast::buffers_to_string(buffer_.data()));
      }
    } else if (server_.handlers.binary) {
      const auto data = buffer_.cdata();
      server_.handlers.binary(id_, std::span<const std::uint8_t>(
                                       static_cast<const std::uint8_t*>(data.data()), data.size()));
    }
    buffer_.consume(buffer_.size());
    read_next();
  }

  void write_next() {
    auto next = queue.take();
    if (!next) {
      return;
    }
    writing_ = std::move(*next);
    auto done = [self = shared_from_this()](error_code ec, std::size_t) {
      self->writing_.reset();
      if (!ec) {
        self->write_next();
      }
    };
    if (writing_->text) {
      ws_.text(true);
      ws_.async_write(asio::buffer(*writing_->text), std::move(done));
      return;
    }
    ws_.binary(true);
    buffers_[0] = writing_->channel_id
                      ? asio::const_buffer(writing_->header.data(), writing_->header.size())
                      : asio::const_buffer();
    buffers_[1] = writing_->payload ? asio::buffer(*writing_->payload) : asio::const_buffer();
    ws_.async_write(buffers_, std::move(done));
  }

  ClientId id_;
  WebSocketServer::Impl& server_;
  websocket::stream<beast::tcp_stream> ws_;
  beast::flat_buffer buffer_;
  http::request<http::string_body> request_;
  std::optional<OutgoingMessage> writing_;
  std::array<asio::const_buffer, 2> buffers_;
};

void WebSocketServer::Impl::accept_next() {
  acceptor.async_accept([this](error_code ec, tcp::socket socket) {
    if (ec) {
      return;  // closed: the server is stopping
    }
    socket.set_option(tcp::no_delay(true));
    std::make_shared<Session>(std::move(socket), next_id++, *this)->start();
    accept_next();
  });
}

void WebSocketServer::Impl::opened(const std::shared_ptr<Session>& session) {
  {
    std::lock_guard lock(mutex);
    sessions[session->id()] = session;
  }
  if (handlers.opened) {
    handlers.opened(session->id(), session->peer());
  }
}

void WebSocketServer::Impl::closed(ClientId id) {
  {
    std::lock_guard lock(mutex);
    if (sessions.erase(id) == 0) {
      return;
    }
  }
  if (handlers.closed) {
    handlers.closed(id);
  }
}

std::shared_ptr<Session> WebSocketServer::Impl::find(ClientId id) const {
  std::lock_guard lock(mutex);
  const auto found = sessions.find(id);
  return found == sessions.end() ? nullptr : found->second;
}

WebSocketServer::WebSocketServer(const ServerOptions& options, ServerHandlers handlers)
    : impl_(std::make_unique<Impl>(options, std::move(handlers))) {
  const std::string where = options.address + ":" + std::to_string(options.port);
  try {
    const tcp::endpoint endpoint(asio::ip::make_address(options.address), options.port);
    impl_->acceptor.open(endpoint.protocol());
    impl_->acceptor.set_option(asio::socket_base::reuse_address(true));
    impl_->acceptor.bind(endpoint);
    impl_->acceptor.listen();
    impl_->port = impl_->acceptor.local_endpoint().port();
  } catch (const boost::system::system_error& error) {
    throw std::runtime_error("cannot listen on " + where + ": " + error.code().message());
  }
  impl_->accept_next();
  impl_->thread = std::thread([this] { impl_->io.run(); });
}

WebSocketServer::~WebSocketServer() {
  std::promise<void> closed;
  asio::post(impl_->io, [this, &closed] {
    error_code ignored;
    impl_->acceptor.close(ignored);
    for (auto& ticker : impl_->tickers) {
      ticker->timer.cancel();
    }
    std::lock_guard lock(impl_->mutex);
    for (auto& [id, session] : impl_->sessions) {
      session->close();
    }
    closed.set_value();
  });
  closed.get_future().wait_for(
      std::chrono::seconds(2));  // bounded: a stuck handler must not hang the exit
  impl_->io.stop();
  if (impl_->thread.joinable()) {
    impl_->thread.join();
  }
  std::lock_guard lock(impl_->mutex);
  impl_->sessions.clear();
}

std::uint16_t WebSocketServer::port() const { return impl_->port; }

bool WebSocketServer::send(ClientId client, OutgoingMessage message) {
  const auto session = impl_->find(client);
  if (!session) {
    return false;
  }
  session->send(std::move(message));
  return true;
}

std::map<std::uint32_t, std::uint64_t> WebSocketServer::take_drops(ClientId client) {
  const auto session = impl_->find(client);
  return session ? session->queue.take_drops() : std::map<std::uint32_t, std::uint64_t>{};
}

std::size_t WebSocketServer::client_count() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->sessions.size();
}

void WebSocketServer::every(std::chrono::milliseconds period, std::function<void()> tick) {
  auto ticker =
      std::make_shared<Ticker>(Ticker{asio::steady_timer(impl_->io), period, std::move(tick)});
  asio::post(impl_->io, [this, ticker] {
    impl_->tickers.push_back(ticker);
    impl_->arm(ticker);
  });
}

}  // namespace wbi::bridge
