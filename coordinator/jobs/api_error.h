// A request the service refuses: why (a Refusal, which coordinator/http/refusal_status.h maps
// to an HTTP status) and the body {"error", "detail", ...extra}. The jobs layer refuses without
// knowing HTTP.
#pragma once

#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

namespace tessera {

enum class Refusal {
  bad_request,             // malformed, or a setting out of range
  unauthorized,            // no token, or a wrong one
  forbidden,               // not allowed from this peer or origin
  not_found,               // no such job, route or page
  method_not_allowed,      // the route does not answer this method
  too_large,               // over a limit on bytes
  unsupported_media_type,  // a body type the service does not read
  unprocessable,           // well-formed, but over a limit on time, memory or work
  too_many_jobs,           // the client's cap on unfinished jobs
  busy,                    // the service cannot take it now; try again
  cannot_store,            // the job store is full or failing
};

class ApiError : public std::runtime_error {
 public:
  ApiError(Refusal refusal, std::string error, const std::string& detail,
           nlohmann::json extra = nlohmann::json::object())
      : std::runtime_error(detail),
        refusal_(refusal),
        error_(std::move(error)),
        extra_(std::move(extra)) {}
  Refusal refusal() const { return refusal_; }
  nlohmann::json body() const {
    nlohmann::json j = extra_;
    j["error"] = error_;
    j["detail"] = what();
    return j;
  }

 private:
  Refusal refusal_;
  std::string error_;
  nlohmann::json extra_;
};

}  // namespace tessera
