// Bad input is reported as "file:line:column: message", never a crash.
#pragma once

#include <stdexcept>
#include <string>

namespace shadowref {

struct SourceLocation {
  std::string file;
  int line = 0;    // 1-based; 0 when unknown
  int column = 0;  // 1-based; 0 when unknown
};

inline std::string formatLocation(const SourceLocation& at) {
  std::string s = at.file.empty() ? std::string("<input>") : at.file;
  if (at.line > 0) {
    s += ':' + std::to_string(at.line);
    s += ':' + std::to_string(at.column > 0 ? at.column : 1);
  }
  return s;
}

// Thrown by everything that reads user input: the scene loader, the mesh importers, -D overrides.
class SceneError : public std::runtime_error {
 public:
  SceneError(SourceLocation where, const std::string& message)
      : std::runtime_error(formatLocation(where) + ": " + message), where_(std::move(where)),
        message_(message) {}
  const SourceLocation& where() const { return where_; }
  const std::string& message() const { return message_; }

 private:
  SourceLocation where_;
  std::string message_;
};

}  // namespace shadowref
