// The HTTP transport (Boost.Beast, after its advanced_server example): one session per
// connection on the single io thread, a body limit (413 beyond it), a timeout before every
// read, keep-alive. Routing is a plain function from request to response (api.h).
#pragma once

#include <functional>
#include <memory>
#include <utility>  // before Asio: Boost 1.74 uses std::exchange without it

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/http.hpp>
#include <nlohmann/json.hpp>

namespace tessera {

using HttpRequest = boost::beast::http::request<boost::beast::http::string_body>;
using HttpResponse = boost::beast::http::response<boost::beast::http::string_body>;
using HttpHandler = std::function<HttpResponse(const HttpRequest&)>;

class HttpServer {
 public:
  HttpServer(boost::asio::io_context& io, const boost::asio::ip::tcp::endpoint& endpoint,
             std::size_t body_limit, HttpHandler handler);
  unsigned short port() const { return acceptor_.local_endpoint().port(); }

 private:
  void accept();
  boost::asio::ip::tcp::acceptor acceptor_;
  std::size_t body_limit_;
  HttpHandler handler_;
};

// A JSON response with the right headers, for handlers and errors alike. Invalid UTF-8 (from
// a scene or a worker's name) is replaced, never thrown.
HttpResponse json_response(unsigned status, const nlohmann::json& body, unsigned version = 11);

}  // namespace tessera
