// A small blocking HTTP/1.1 client (Boost.Beast) for tessera-submit: one connection per request,
// to a coordinator named by a URL "http://HOST:PORT" or, when it serves TLS, "https://HOST:PORT"
// (its certificate verified as the worker verifies it, common/protocol/tls.h).
#pragma once

#include <memory>
#include <string>

#include "common/protocol/tls.h"

namespace tessera {

struct HttpReply {
  int status = 0;
  std::string body;
};

class HttpClient {
 public:
  // `url`: "http://HOST[:PORT][/]" (port 80 when left out) or "https://HOST[:PORT][/]" (443),
  // whose certificate must be trusted by `tls` and name HOST; throws std::invalid_argument for
  // another scheme or a malformed URL. `token`, when not empty, goes with every request as
  // "Authorization: Bearer TOKEN" (the coordinator's --api-token).
  HttpClient(const std::string& url, std::string token, const ClientTlsOptions& tls = {});

  // Throws std::runtime_error when the coordinator cannot be reached or answers garbage.
  HttpReply get(const std::string& target) const;
  HttpReply post(const std::string& target, const std::string& content_type,
                 std::string body) const;
  HttpReply del(const std::string& target) const;

  // "http://HOST:PORT" or "https://HOST:PORT", for messages.
  const std::string& base() const { return base_; }

 private:
  HttpReply send(const std::string& method, const std::string& target,
                 const std::string& content_type, std::string body) const;
  std::string host_, port_, token_, base_;
  std::shared_ptr<boost::asio::ssl::context> tls_;  // null for http://
};

}  // namespace tessera
