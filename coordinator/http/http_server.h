// The HTTP transport (Boost.Beast, after its advanced_server example): HTTP or HTTPS, one
// session per connection on the io thread, a body limit (413 beyond it), a timeout before every
// read, keep-alive, a cap on open connections. A handler gets each request with a callback that it
// calls once, now or later (after work on another thread): the session lives until the
// response is written.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <utility>  // before Asio: Boost 1.74 uses std::exchange without it

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ssl/context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/http.hpp>
#include <nlohmann/json.hpp>

#include "coordinator/http/shared_body.h"
#include "coordinator/net/backoff.h"
#include "coordinator/net/log_limiter.h"

namespace tessera {

using HttpRequest = boost::beast::http::request<boost::beast::http::string_body>;
using HttpResponse = boost::beast::http::response<SharedStringBody>;
// Answers the request; call it once, from any thread (the write is posted to the io thread).
using HttpRespond = std::function<void(HttpResponse)>;
using HttpHandler = std::function<void(
    HttpRequest request, const boost::asio::ip::tcp::endpoint& peer, HttpRespond respond)>;

struct HttpServerOptions {
  std::size_t body_limit = 32u << 20;
  // Connections beyond it are closed as soon as they are accepted: each one holds a
  // descriptor and up to body_limit bytes.
  int max_connections = 256;
  // HTTPS when set (--tls-cert): a client that does not complete the TLS handshake within the
  // read timeout is dropped without an answer.
  std::shared_ptr<boost::asio::ssl::context> tls;
};

class HttpServer {
 public:
  HttpServer(boost::asio::io_context& io, const boost::asio::ip::tcp::endpoint& endpoint,
             HttpServerOptions options, HttpHandler handler);
  unsigned short port() const { return acceptor_.local_endpoint().port(); }
  int open_connections() const { return *open_; }

 private:
  void accept();
  void on_accept(boost::system::error_code ec, boost::asio::ip::tcp::socket socket);
  boost::asio::ip::tcp::acceptor acceptor_;
  boost::asio::steady_timer retry_;
  HttpServerOptions options_;
  std::shared_ptr<const HttpHandler> handler_;
  std::shared_ptr<std::atomic<int>> open_;  // sessions alive; shared as they may outlive us
  Backoff accept_backoff_;
  LogLimiter accept_errors_, refused_;
};

// A JSON response with the right headers, for handlers and errors alike. Invalid UTF-8 (from
// a scene or a worker's name) is replaced, never thrown.
HttpResponse json_response(unsigned status, const nlohmann::json& body, unsigned version = 11);

}  // namespace tessera
