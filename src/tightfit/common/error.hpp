#pragma once
/// Error types. Every error that comes from user input names its source (file or
/// JSON path) and what is wrong, so that the CLI can print it and exit non-zero.
#include <stdexcept>
#include <string>

namespace tightfit {

/// Bad user input: a file that cannot be read, a malformed mesh, an invalid scene.
class InputError : public std::runtime_error {
 public:
  /// `source` is the file name or JSON path, `what` says what is wrong with it.
  InputError(const std::string& source, const std::string& what)
      : std::runtime_error(source.empty() ? what : source + ": " + what), source_(source) {}
  const std::string& source() const { return source_; }

 private:
  std::string source_;
};

/// A numerical procedure failed (a solve did not converge, a factorization failed).
class SolverError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace tightfit
