#include "view_server.hpp"

#include <deque>
#include <fstream>
#include <memory>
#include <sstream>
#include <utility>

#include <boost/asio.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>

#include "softsim/io/errors.hpp"

namespace softsim::view {

namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;

class Server;

// A WebSocket client. The active one drives the scene and receives its states; any other is
// told so and closed.
class WsSession : public std::enable_shared_from_this<WsSession> {
 public:
  WsSession(tcp::socket socket, Server& server) : ws_(std::move(socket)), server_(server), timer_(ws_.get_executor()) {}
  void run(http::request<http::string_body> request);
  void send(std::string text, bool binary = false);

 private:
  void on_accept(beast::error_code ec);
  void read();
  void on_read(beast::error_code ec);
  void tick();
  void write_next();
  void finish();

  websocket::stream<beast::tcp_stream> ws_;
  Server& server_;
  asio::steady_timer timer_;
  beast::flat_buffer buffer_;
  std::deque<std::pair<std::string, bool>> outgoing_;
  bool writing_ = false, active_ = false, closing_ = false;
  // States on request: a client that draws slower than the states come asks for each one, so
  // the one it gets is the newest, not one queued behind others in the socket.
  bool pull_ = false;
  int requested_ = 0;
  double last_t_ = 0;
  bool has_last_ = false;
  long mesh_sent_ = -2;
  std::string positions_;
};

class Server {
 public:
  Server(haptic::ViewLoop& loop, const haptic::ViewHello& hello, const ViewServerOptions& options)
      : loop_(loop), hello_(hello), options_(options), acceptor_(io_), signals_(io_, SIGINT, SIGTERM) {}

  int listen() {
    beast::error_code ec;
    const auto address = asio::ip::make_address(options_.host, ec);
    if (ec) throw InputError("command line: --host " + options_.host + ": expected an IP address");
    const tcp::endpoint endpoint(address, static_cast<unsigned short>(options_.port));
    acceptor_.open(endpoint.protocol(), ec);
    if (!ec) acceptor_.set_option(asio::socket_base::reuse_address(true), ec);
    if (!ec) acceptor_.bind(endpoint, ec);
    if (!ec) acceptor_.listen(asio::socket_base::max_listen_connections, ec);
    if (ec)
      throw InputError("view: cannot listen on " + options_.host + ":" + std::to_string(options_.port) + ": " +
                       ec.message());
    signals_.async_wait([this](beast::error_code, int) { stop(); });
    accept();
    return acceptor_.local_endpoint().port();
  }
  void run() { io_.run(); }
  void stop() { io_.stop(); }
  // Called from the loop's thread when its frames end by themselves.
  void stop_from_any_thread() {
    asio::post(io_, [this] { stop(); });
  }

  haptic::ViewLoop& loop() { return loop_; }
  const haptic::ViewHello& hello() const { return hello_; }
  const ViewServerOptions& options() const { return options_; }
  // The driving client: the first to connect while none is; false when another one drives.
  bool claim(WsSession* s) {
    if (driver_ && driver_ != s) return false;
    driver_ = s;
    return true;
  }
  void release(WsSession* s) {
    if (driver_ == s) driver_ = nullptr;
  }

 private:
  void accept();

  asio::io_context io_;
  haptic::ViewLoop& loop_;
  haptic::ViewHello hello_;
  ViewServerOptions options_;
  tcp::acceptor acceptor_;
  asio::signal_set signals_;
  WsSession* driver_ = nullptr;
};

// The page's files. Only paths of plain names under the web root (no "..", no hidden files).
std::string content_type(const std::string& path) {
  auto ends = [&](const char* ext) {
    const std::string e(ext);
    return path.size() >= e.size() && path.compare(path.size() - e.size(), e.size(), e) == 0;
  };
  if (ends(".html")) return "text/html; charset=utf-8";
  if (ends(".js") || ends(".mjs")) return "text/javascript; charset=utf-8";
  if (ends(".css")) return "text/css; charset=utf-8";
  if (ends(".json")) return "application/json";
  if (ends(".png")) return "image/png";
  return "application/octet-stream";
}

bool safe_path(const std::string& target) {
  if (target.empty() || target[0] != '/') return false;
  return target.find("..") == std::string::npos && target.find("/.") == std::string::npos &&
         target.find('\\') == std::string::npos;
}

class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(tcp::socket socket, Server& server) : stream_(std::move(socket)), server_(server) {}
  void read() {
    parser_.emplace();
    parser_->header_limit(8192);
    parser_->body_limit(8192);
    stream_.expires_after(std::chrono::seconds(30));
    http::async_read(stream_, buffer_, *parser_,
                     [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_read(ec); });
  }

 private:
  void on_read(beast::error_code ec) {
    if (ec) return;  // closed, timed out or malformed: nothing to answer
    auto request = parser_->release();
    if (websocket::is_upgrade(request)) {
      // A browser names the page that opens a socket: only this server's own page may drive the
      // scene (another site open in the same browser may not). Clients outside a browser send
      // no Origin, or their own host's.
      const auto origin = request.find(http::field::origin);
      if (origin != request.end() && origin->value() != "http://" + std::string(request[http::field::host]))
        return answer(http::status::forbidden, "a WebSocket from another origin\n", "text/plain", false);
      stream_.expires_never();
      std::make_shared<WsSession>(stream_.release_socket(), server_)->run(std::move(request));
      return;
    }
    respond(request);
  }

  void respond(const http::request<http::string_body>& request) {
    const bool keep = request.keep_alive();
    std::string target(request.target());
    if (const auto q = target.find('?'); q != std::string::npos) target.resize(q);
    if (request.method() != http::verb::get && request.method() != http::verb::head)
      return answer(http::status::method_not_allowed, "only GET\n", "text/plain", keep);
    if (!safe_path(target)) return answer(http::status::bad_request, "bad path\n", "text/plain", keep);
    if (target == "/") target = "/index.html";
    std::string file = server_.options().web_root + target;
    if (target.rfind("/three/", 0) == 0) file = server_.options().web_root + "/node_modules" + target;
    std::ifstream in(file, std::ios::binary);
    if (!in) return answer(http::status::not_found, "not found: " + target + "\n", "text/plain", keep);
    std::ostringstream body;
    body << in.rdbuf();
    answer(http::status::ok, body.str(), content_type(file), keep);
  }

  void answer(http::status status, std::string body, const std::string& type, bool keep) {
    auto response = std::make_shared<http::response<http::string_body>>(status, 11);
    response->set(http::field::content_type, type);
    response->set(http::field::cache_control, "no-store");
    response->keep_alive(keep);
    response->body() = std::move(body);
    response->prepare_payload();
    http::async_write(stream_, *response,
                      [self = shared_from_this(), response, keep](beast::error_code ec, std::size_t) {
                        if (ec || !keep) {
                          beast::error_code ignored;
                          self->stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
                          return;
                        }
                        self->read();
                      });
  }

  beast::tcp_stream stream_;
  Server& server_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
};

void Server::accept() {
  acceptor_.async_accept([this](beast::error_code ec, tcp::socket socket) {
    if (!ec) std::make_shared<HttpSession>(std::move(socket), *this)->read();
    if (acceptor_.is_open()) accept();
  });
}

void WsSession::run(http::request<http::string_body> request) {
  ws_.read_message_max(haptic::kViewMaxMessage);
  ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
  ws_.async_accept(request, [self = shared_from_this()](beast::error_code ec) { self->on_accept(ec); });
}

void WsSession::on_accept(beast::error_code ec) {
  if (ec) return;
  if (!server_.claim(this)) {
    // One driver at a time: this client is told why and closed; the driving one goes on.
    closing_ = true;
    send(haptic::format_error("another client drives this scene; one client at a time"));
    return;
  }
  active_ = true;
  server_.loop().new_sender();
  send(haptic::format_hello(server_.hello()));
  read();
  tick();
}

void WsSession::read() {
  ws_.async_read(buffer_, [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_read(ec); });
}

void WsSession::on_read(beast::error_code ec) {
  if (ec) {
    // Closed, timed out, or a protocol violation (a message over the limit is closed by Beast
    // with code 1009, "too big"): this connection ends, the scene goes on.
    finish();
    return;
  }
  if (!ws_.got_text()) {
    send(haptic::format_error("expected a JSON text message"));
  } else {
    const std::string text = beast::buffers_to_string(buffer_.data());
    const auto m = haptic::parse_client_message(text, last_t_, has_last_, server_.hello().max_edge);
    switch (m.kind) {
      case haptic::ClientMessage::Kind::sample:
        last_t_ = m.sample.t;
        has_last_ = true;
        if (!server_.loop().push(m.sample)) send(haptic::format_error("samples arrive faster than the frames take them: dropped"));
        break;
      case haptic::ClientMessage::Kind::stop:
        server_.stop();
        return;
      case haptic::ClientMessage::Kind::hello:
        pull_ = m.pull;
        break;
      case haptic::ClientMessage::Kind::next:
        requested_ = 1;
        break;
      case haptic::ClientMessage::Kind::invalid:
        send(haptic::format_error(m.error));
        break;
    }
  }
  buffer_.consume(buffer_.size());
  read();
}

void WsSession::tick() {
  if (!active_) return;
  // A state only when the previous ones have gone out: a slow client skips states, and the
  // loop never sees it (it publishes into its triple buffer regardless).
  if (!writing_ && outgoing_.empty() && (!pull_ || requested_ > 0) && server_.loop().take_state()) {
    requested_ = 0;
    const haptic::ViewState& s = server_.loop().state();
    if (s.topology.version != mesh_sent_) {
      send(haptic::format_mesh(s.topology));
      mesh_sent_ = s.topology.version;
    }
    send(haptic::format_state(s));
    haptic::format_positions(s, positions_);
    send(positions_, true);
  }
  timer_.expires_after(std::chrono::microseconds(static_cast<long>(1e6 / server_.options().state_rate)));
  timer_.async_wait([self = shared_from_this()](beast::error_code ec) {
    if (!ec) self->tick();
  });
}

void WsSession::send(std::string text, bool binary) {
  // A client that does not read its errors is not kept forever.
  if (outgoing_.size() > 256) {
    finish();
    beast::get_lowest_layer(ws_).close();
    return;
  }
  outgoing_.emplace_back(std::move(text), binary);
  if (!writing_) write_next();
}

void WsSession::write_next() {
  if (outgoing_.empty()) {
    writing_ = false;
    if (closing_)
      ws_.async_close(websocket::close_reason(websocket::close_code::policy_error, "one client at a time"),
                      [self = shared_from_this()](beast::error_code) {});
    return;
  }
  writing_ = true;
  ws_.binary(outgoing_.front().second);
  ws_.async_write(asio::buffer(outgoing_.front().first),
                  [self = shared_from_this()](beast::error_code ec, std::size_t) {
                    if (ec) {
                      self->finish();
                      return;
                    }
                    self->outgoing_.pop_front();
                    self->write_next();
                  });
}

void WsSession::finish() {
  if (active_) server_.release(this);
  active_ = false;
  timer_.cancel();
}

}  // namespace

void serve_view(haptic::ViewLoop& loop, const haptic::ViewHello& hello, const ViewServerOptions& options,
                const std::function<void(int port)>& on_listen) {
  Server server(loop, hello, options);
  const int port = server.listen();
  loop.start([&server] { server.stop_from_any_thread(); });
  if (on_listen) on_listen(port);
  server.run();
  loop.stop();
}

}  // namespace softsim::view
