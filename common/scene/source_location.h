// Where something was written in a scene file, for error messages users can act on.
#pragma once

#include <stdexcept>
#include <string>

namespace tessera {

struct SourceLocation {
  std::string file;  // as the user named it (relative to the scene's folder)
  int line = 0;      // 1-based
  int column = 0;    // 1-based

  std::string to_string() const {
    return file + ":" + std::to_string(line) + ":" + std::to_string(column);
  }
};

// A user error in a scene: a syntax error, a bad value, a missing or refused file.
// what() reads "file:line:col: message".
class SceneError : public std::runtime_error {
 public:
  SceneError(SourceLocation where, const std::string& message)
      : std::runtime_error(where.to_string() + ": " + message),
        where_(std::move(where)),
        message_(message) {}
  const SourceLocation& where() const { return where_; }
  const std::string& message() const { return message_; }

 private:
  SourceLocation where_;
  std::string message_;
};

}  // namespace tessera
