#include "coordinator/http/http_server.h"

#include <chrono>
#include <optional>

#include <spdlog/spdlog.h>
#include <boost/beast/core.hpp>
#include <nlohmann/json.hpp>

namespace tessera {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
using asio::ip::tcp;

namespace {

constexpr auto kReadTimeout = std::chrono::seconds(30);

class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(tcp::socket socket, std::size_t body_limit, const HttpHandler& handler)
      : stream_(std::move(socket)), body_limit_(body_limit), handler_(handler) {}

  void read() {
    parser_.emplace();
    parser_->body_limit(body_limit_);
    parser_->header_limit(16 * 1024);
    stream_.expires_after(kReadTimeout);
    http::async_read(
        stream_, buffer_, *parser_,
        [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_read(ec); });
  }

 private:
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
    HttpResponse response;
    try {
      response = handler_(request);
    } catch (const std::exception& e) {  // a bug in a handler must not end the service
      spdlog::error("{} {}: {}", std::string(request.method_string()),
                    std::string(request.target()), e.what());
      response = json_response(500, nlohmann::json{{"error", "internal"}, {"detail", e.what()}});
    }
    response.version(request.version());
    response.keep_alive(request.keep_alive());
    write(std::move(response), !request.keep_alive());
  }

  void write(HttpResponse response, bool close_after) {
    if (close_after) response.keep_alive(false);
    response.prepare_payload();
    response_ = std::make_shared<HttpResponse>(std::move(response));
    stream_.expires_after(kReadTimeout);
    http::async_write(stream_, *response_,
                      [self = shared_from_this(), close_after](beast::error_code ec, std::size_t) {
                        self->response_.reset();
                        if (ec || close_after) return self->close();
                        self->read();
                      });
  }

  void close() {
    beast::error_code ignored;
    stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
    stream_.close();
  }

  beast::tcp_stream stream_;
  beast::flat_buffer buffer_;
  std::size_t body_limit_;
  const HttpHandler& handler_;
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

HttpServer::HttpServer(asio::io_context& io, const tcp::endpoint& endpoint, std::size_t body_limit,
                       HttpHandler handler)
    : acceptor_(io, endpoint), body_limit_(body_limit), handler_(std::move(handler)) {
  accept();
}

void HttpServer::accept() {
  acceptor_.async_accept([this](beast::error_code ec, tcp::socket socket) {
    if (!ec) std::make_shared<HttpSession>(std::move(socket), body_limit_, handler_)->read();
    if (acceptor_.is_open()) accept();
  });
}

}  // namespace tessera
