#include "coordinator/http/http_server.h"

#include <chrono>
#include <optional>
#include <type_traits>

#include <spdlog/spdlog.h>
#include <boost/asio/post.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/ssl.hpp>
#include <nlohmann/json.hpp>

namespace tessera {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace ssl = asio::ssl;
using asio::ip::tcp;

namespace {

constexpr auto kReadTimeout = std::chrono::seconds(30);

using TlsStream = beast::ssl_stream<beast::tcp_stream>;

// Stream: beast::tcp_stream (HTTP) or TlsStream (HTTPS).
template <class Stream>
class HttpSession : public std::enable_shared_from_this<HttpSession<Stream>> {
  static constexpr bool kTls = std::is_same_v<Stream, TlsStream>;

 public:
  template <class... StreamArgs>
  HttpSession(std::size_t body_limit, std::shared_ptr<const HttpHandler> handler,
              std::shared_ptr<std::atomic<int>> open, StreamArgs&&... stream_args)
      : stream_(std::forward<StreamArgs>(stream_args)...),
        body_limit_(body_limit),
        handler_(std::move(handler)),
        open_(std::move(open)) {
    ++*open_;
  }
  ~HttpSession() { --*open_; }

  void start() {
    if constexpr (kTls) {
      lowest().expires_after(kReadTimeout);
      stream_.async_handshake(ssl::stream_base::server,
                              [self = this->shared_from_this()](beast::error_code ec) {
                                if (ec) return beast::get_lowest_layer(self->stream_).close();
                                self->read();
                              });
    } else {
      read();
    }
  }

 private:
  beast::tcp_stream& lowest() { return beast::get_lowest_layer(stream_); }

  void read() {
    parser_.emplace();
    parser_->body_limit(body_limit_);
    parser_->header_limit(16 * 1024);
    lowest().expires_after(kReadTimeout);
    http::async_read(stream_, buffer_, *parser_,
                     [self = this->shared_from_this()](beast::error_code ec, std::size_t) {
                       self->on_read(ec);
                     });
  }

  void on_read(beast::error_code ec) {
    if (ec == http::error::end_of_stream || ec == beast::error::timeout) return close();
    if (ec == http::error::body_limit) {
      // The rest of the body is never read: answer, then close the connection.
      return write(json_response(
                       413, nlohmann::json{{"error", "payload_too_large"},
                                           {"detail", "the body is over the limit of " +
                                                          std::to_string(body_limit_) + " bytes"}}),
                   true);
    }
    if (ec) {
      if (ec != asio::error::operation_aborted && ec != asio::error::connection_reset)
        return write(
            json_response(400, nlohmann::json{{"error", "bad_http"}, {"detail", ec.message()}}),
            true);
      return close();
    }
    HttpRequest request = parser_->release();
    const unsigned version = request.version();
    const bool keep_alive = request.keep_alive();
    beast::error_code peer_error;
    const tcp::endpoint peer = lowest().socket().remote_endpoint(peer_error);
    if (peer_error) return close();
    // Until the response is written the session reads nothing more (no pipelining), so one
    // connection never has two requests in work.
    HttpRespond respond = [self = this->shared_from_this(), version,
                           keep_alive](HttpResponse response) {
      asio::post(self->stream_.get_executor(),
                 [self, version, keep_alive, response = std::move(response)]() mutable {
                   response.version(version);
                   response.keep_alive(keep_alive);
                   self->write(std::move(response), !keep_alive);
                 });
    };
    const std::string method(request.method_string()), target(request.target());
    try {
      (*handler_)(std::move(request), peer, respond);
    } catch (const std::exception& e) {  // a bug in a handler must not end the service
      spdlog::error("{} {}: {}", method, target, e.what());
      respond(json_response(500, nlohmann::json{{"error", "internal"}, {"detail", e.what()}}));
    }
  }

  void write(HttpResponse response, bool close_after) {
    if (close_after) response.keep_alive(false);
    response.prepare_payload();
    response_ = std::make_shared<HttpResponse>(std::move(response));
    lowest().expires_after(kReadTimeout);
    http::async_write(
        stream_, *response_,
        [self = this->shared_from_this(), close_after](beast::error_code ec, std::size_t) {
          self->response_.reset();
          if (ec || close_after) return self->close();
          self->read();
        });
  }

  void close() {
    if constexpr (kTls) {
      // close_notify first, so the client can tell the end from a truncation; bounded.
      lowest().expires_after(std::chrono::seconds(5));
      stream_.async_shutdown(
          [self = this->shared_from_this()](beast::error_code) { self->lowest().close(); });
    } else {
      beast::error_code ignored;
      stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
      stream_.close();
    }
  }

  Stream stream_;
  beast::flat_buffer buffer_;
  std::size_t body_limit_;
  std::shared_ptr<const HttpHandler> handler_;
  std::shared_ptr<std::atomic<int>> open_;
  std::optional<http::request_parser<http::string_body>> parser_;
  std::shared_ptr<HttpResponse> response_;
};

}  // namespace

HttpResponse json_response(unsigned status, const nlohmann::json& body, unsigned version) {
  HttpResponse res{static_cast<http::status>(status), version};
  res.set(http::field::content_type, "application/json");
  res.set(http::field::cache_control, "no-store");
  res.body() = body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  return res;
}

HttpServer::HttpServer(asio::io_context& io, const tcp::endpoint& endpoint,
                       HttpServerOptions options, HttpHandler handler)
    : acceptor_(io, endpoint),
      retry_(io),
      options_(options),
      handler_(std::make_shared<const HttpHandler>(std::move(handler))),
      open_(std::make_shared<std::atomic<int>>(0)) {
  accept();
}

void HttpServer::accept() {
  acceptor_.async_accept(
      [this](beast::error_code ec, tcp::socket socket) { on_accept(ec, std::move(socket)); });
}

void HttpServer::on_accept(beast::error_code ec, tcp::socket socket) {
  if (ec == asio::error::operation_aborted || !acceptor_.is_open()) return;
  if (ec) {
    // At the descriptor limit accept fails at once, again and again: wait, doubling the wait.
    const auto delay = accept_backoff_.next();
    if (const auto suppressed = accept_errors_.allow())
      spdlog::warn("HTTP accept failed: {} (retrying in {} ms){}", ec.message(), delay.count(),
                   suppressed_note(*suppressed));
    retry_.expires_after(delay);
    retry_.async_wait([this](beast::error_code wait_ec) {
      if (!wait_ec) accept();
    });
    return;
  }
  accept_backoff_.reset();
  if (*open_ >= options_.max_connections) {
    if (const auto suppressed = refused_.allow())
      spdlog::warn("refused an HTTP connection: {} are open, the limit{}", options_.max_connections,
                   suppressed_note(*suppressed));
    beast::error_code ignored;
    socket.close(ignored);
  } else {
    if (options_.tls)
      std::make_shared<HttpSession<TlsStream>>(options_.body_limit, handler_, open_,
                                               std::move(socket), *options_.tls)
          ->start();
    else
      std::make_shared<HttpSession<beast::tcp_stream>>(options_.body_limit, handler_, open_,
                                                       std::move(socket))
          ->start();
  }
  accept();
}

}  // namespace tessera
