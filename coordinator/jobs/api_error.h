// A request the service refuses: the HTTP status and the body {"error", "detail", ...extra}.
#pragma once

#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

namespace tessera {

class ApiError : public std::runtime_error {
 public:
  ApiError(int status, std::string error, const std::string& detail,
           nlohmann::json extra = nlohmann::json::object())
      : std::runtime_error(detail),
        status_(status),
        error_(std::move(error)),
        extra_(std::move(extra)) {}
  int status() const { return status_; }
  nlohmann::json body() const {
    nlohmann::json j = extra_;
    j["error"] = error_;
    j["detail"] = what();
    return j;
  }

 private:
  int status_;
  std::string error_;
  nlohmann::json extra_;
};

}  // namespace tessera
