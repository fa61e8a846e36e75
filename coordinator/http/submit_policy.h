// Who may change state (POST, DELETE): with --api-token only requests that carry it
// (Authorization: Bearer TOKEN); without one only loopback peers, unless --open-submit. A
// request whose Origin is neither its own (Host) nor an --allow-origin entry is refused, so
// no other web page can make a visitor's browser submit or cancel jobs.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <boost/asio/ip/address.hpp>

#include "coordinator/http/http_server.h"

namespace tessera {

struct SubmitPolicy {
  std::string api_token;                     // --api-token or TESSERA_API_TOKEN; empty: none
  bool open_submit = false;                  // without a token, any peer may submit
  std::vector<std::string> allowed_origins;  // --allow-origin, e.g. "https://render.example"
};

// Throws ApiError 403 (foreign origin, or not loopback) or 401 (missing or wrong token).
void check_submitter(const SubmitPolicy& policy, const HttpRequest& request,
                     const boost::asio::ip::address& peer);

// Whether `given` is the token, in a time that reveals neither where they differ nor the
// token's length (their SHA-256 digests are compared without an early exit).
bool token_matches(std::string_view given, std::string_view token);

}  // namespace tessera
