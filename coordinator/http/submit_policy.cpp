#include "coordinator/http/submit_policy.h"

#include <algorithm>
#include <cctype>

#include "common/protocol/sha256.h"
#include "coordinator/jobs/api_error.h"

namespace tessera {

namespace http = boost::beast::http;

namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  std::ranges::transform(out, out.begin(),
                         [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

bool is_loopback(const boost::asio::ip::address& peer) {
  if (peer.is_v6() && peer.to_v6().is_v4_mapped())
    return boost::asio::ip::make_address_v4(boost::asio::ip::v4_mapped, peer.to_v6()).is_loopback();
  return peer.is_loopback();
}

// "http://host:8080" is the request's own origin when its host part is the Host header.
bool same_origin(std::string_view origin, std::string_view host) {
  const auto scheme_end = origin.find("://");
  if (scheme_end == std::string_view::npos || host.empty()) return false;
  return lower(origin.substr(scheme_end + 3)) == lower(host);
}

}  // namespace

bool token_matches(std::string_view given, std::string_view token) {
  const Sha256Digest a = sha256(given), b = sha256(token);
  return constant_time_equal(std::string_view(reinterpret_cast<const char*>(a.data()), a.size()),
                             std::string_view(reinterpret_cast<const char*>(b.data()), b.size()));
}

void check_submitter(const SubmitPolicy& policy, const HttpRequest& request,
                     const boost::asio::ip::address& peer) {
  if (const auto it = request.find(http::field::origin); it != request.end()) {
    const std::string_view origin(it->value().data(), it->value().size());
    const auto host = request[http::field::host];
    const bool allowed = same_origin(origin, std::string_view(host.data(), host.size())) ||
                         std::ranges::find(policy.allowed_origins, std::string(origin)) !=
                             policy.allowed_origins.end();
    if (!allowed)
      throw ApiError(Refusal::forbidden, "cross_origin",
                     "requests from " + std::string(origin) +
                         " may not change state here (start the coordinator with --allow-origin " +
                         std::string(origin) + " to allow it)");
  }
  if (!policy.api_token.empty()) {
    const auto auth = request[http::field::authorization];
    const std::string_view given(auth.data(), auth.size());
    constexpr std::string_view kBearer = "Bearer ";
    if (!given.starts_with(kBearer) ||
        !token_matches(given.substr(kBearer.size()), policy.api_token))
      throw ApiError(Refusal::unauthorized, "unauthorized",
                     "this coordinator needs its API token: Authorization: Bearer TOKEN");
    return;
  }
  if (!policy.open_submit && !is_loopback(peer))
    throw ApiError(Refusal::forbidden, "forbidden",
                   "only this machine may submit or cancel; start the coordinator with "
                   "--api-token TOKEN (or --open-submit on a trusted network)");
}

}  // namespace tessera
