#include "client/http_client.h"

#include <stdexcept>

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>

namespace tessera {
namespace {

namespace beast = boost::beast;
namespace http = beast::http;
using tcp = boost::asio::ip::tcp;

// The largest answer read: a 16384 x 16384 EXR of three floats, with room for its headers.
constexpr std::uint64_t kMaxReplyBytes = 16384ull * 16384ull * 12ull + (1u << 20);

}  // namespace

HttpClient::HttpClient(const std::string& url, std::string token) : token_(std::move(token)) {
  std::string rest = url;
  if (rest.starts_with("https://"))
    throw std::invalid_argument("--coordinator " + url +
                                ": https is not supported; give the plain http:// address");
  if (rest.starts_with("http://")) rest = rest.substr(7);
  while (rest.ends_with("/")) rest.pop_back();
  if (rest.empty() || rest.find('/') != std::string::npos)
    throw std::invalid_argument("--coordinator " + url + ": expected http://HOST:PORT");
  const std::size_t colon = rest.rfind(':');
  host_ = colon == std::string::npos ? rest : rest.substr(0, colon);
  port_ = colon == std::string::npos ? "80" : rest.substr(colon + 1);
  if (host_.empty() || port_.empty() || port_.find_first_not_of("0123456789") != std::string::npos)
    throw std::invalid_argument("--coordinator " + url + ": expected http://HOST:PORT");
  base_ = "http://" + host_ + ":" + port_;
}

HttpReply HttpClient::get(const std::string& target) const { return send("GET", target, "", ""); }

HttpReply HttpClient::post(const std::string& target, const std::string& content_type,
                           std::string body) const {
  return send("POST", target, content_type, std::move(body));
}

HttpReply HttpClient::send(const std::string& method, const std::string& target,
                           const std::string& content_type, std::string body) const {
  try {
    boost::asio::io_context io;
    tcp::resolver resolver(io);
    beast::tcp_stream stream(io);
    stream.connect(resolver.resolve(host_, port_));
    http::request<http::string_body> request(http::string_to_verb(method), target, 11);
    request.set(http::field::host, host_ + ":" + port_);
    request.set(http::field::user_agent, "tessera-submit");
    if (!token_.empty()) request.set(http::field::authorization, "Bearer " + token_);
    if (!content_type.empty()) request.set(http::field::content_type, content_type);
    request.body() = std::move(body);
    request.prepare_payload();
    http::write(stream, request);
    beast::flat_buffer buffer;
    http::response_parser<http::string_body> parser;
    parser.body_limit(kMaxReplyBytes);
    http::read(stream, buffer, parser);
    beast::error_code ignored;
    stream.socket().shutdown(tcp::socket::shutdown_both, ignored);
    return {static_cast<int>(parser.get().result_int()), std::move(parser.get().body())};
  } catch (const boost::system::system_error& e) {
    throw std::runtime_error(method + " " + base_ + target + ": " + e.code().message());
  }
}

}  // namespace tessera
