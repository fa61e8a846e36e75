#include "client/http_client.h"

#include <stdexcept>

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/ssl.hpp>

namespace tessera {
namespace {

namespace beast = boost::beast;
namespace http = beast::http;
using tcp = boost::asio::ip::tcp;

// The largest answer read: a 16384 x 16384 EXR of three floats, with room for its headers.
constexpr std::uint64_t kMaxReplyBytes = 16384ull * 16384ull * 12ull + (1u << 20);

HttpReply exchange(auto& stream, http::request<http::string_body>& request) {
  http::write(stream, request);
  beast::flat_buffer buffer;
  http::response_parser<http::string_body> parser;
  parser.body_limit(kMaxReplyBytes);
  http::read(stream, buffer, parser);
  return {static_cast<int>(parser.get().result_int()), std::move(parser.get().body())};
}

}  // namespace

HttpClient::HttpClient(const std::string& url, std::string token, const ClientTlsOptions& tls)
    : token_(std::move(token)) {
  const std::string expected = ": expected http://HOST:PORT or https://HOST:PORT";
  std::string rest = url;
  const bool https = rest.starts_with("https://");
  if (https)
    rest = rest.substr(8);
  else if (rest.starts_with("http://"))
    rest = rest.substr(7);
  while (rest.ends_with("/")) rest.pop_back();
  if (rest.empty() || rest.find('/') != std::string::npos)
    throw std::invalid_argument("--coordinator " + url + expected);
  const std::size_t colon = rest.rfind(':');
  host_ = colon == std::string::npos ? rest : rest.substr(0, colon);
  port_ = colon == std::string::npos ? (https ? "443" : "80") : rest.substr(colon + 1);
  if (host_.empty() || port_.empty() || port_.find_first_not_of("0123456789") != std::string::npos)
    throw std::invalid_argument("--coordinator " + url + expected);
  base_ = (https ? "https://" : "http://") + host_ + ":" + port_;
  if (https) tls_ = make_client_tls(tls);
}

HttpReply HttpClient::get(const std::string& target) const { return send("GET", target, "", ""); }

HttpReply HttpClient::post(const std::string& target, const std::string& content_type,
                           std::string body) const {
  return send("POST", target, content_type, std::move(body));
}

HttpReply HttpClient::del(const std::string& target) const {
  return send("DELETE", target, "", "");
}

HttpReply HttpClient::send(const std::string& method, const std::string& target,
                           const std::string& content_type, std::string body) const {
  try {
    http::request<http::string_body> request(http::string_to_verb(method), target, 11);
    request.set(http::field::host, host_ + ":" + port_);
    request.set(http::field::user_agent, "tessera-submit");
    if (!token_.empty()) request.set(http::field::authorization, "Bearer " + token_);
    if (!content_type.empty()) request.set(http::field::content_type, content_type);
    request.body() = std::move(body);
    request.prepare_payload();
    boost::asio::io_context io;
    tcp::resolver resolver(io);
    beast::error_code ignored;
    if (!tls_) {
      beast::tcp_stream stream(io);
      stream.connect(resolver.resolve(host_, port_));
      HttpReply reply = exchange(stream, request);
      stream.socket().shutdown(tcp::socket::shutdown_both, ignored);
      return reply;
    }
    beast::ssl_stream<beast::tcp_stream> stream(io, *tls_);
    expect_peer_name(stream.native_handle(), host_);
    beast::get_lowest_layer(stream).connect(resolver.resolve(host_, port_));
    stream.handshake(boost::asio::ssl::stream_base::client);
    HttpReply reply = exchange(stream, request);
    stream.shutdown(ignored);  // the coordinator may close first: nothing is lost by then
    return reply;
  } catch (const boost::system::system_error& e) {
    throw std::runtime_error(method + " " + base_ + target + ": " + e.code().message());
  }
}

}  // namespace tessera
