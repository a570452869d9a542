// Error types shared by all modules. Library code never aborts: bad input raises
// InputError (the CLI maps it to exit code 2 and writes nothing), numerical breakdown
// raises NumericalError with where and why (exit code 3).
#pragma once

#include <stdexcept>
#include <string>

namespace abu {

/// Invalid user input: a scene file, a command-line value. `line` is 0 when the input
/// has no line (command-line options). what() is the complete one-line message
/// "FILE:LINE: key 'KEY': RULE".
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, int line, std::string key, std::string rule);
  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& key() const { return key_; }
  const std::string& rule() const { return rule_; }

 private:
  std::string file_;
  int line_;
  std::string key_;
  std::string rule_;
};

/// A computation that did not reach its result: Newton not converging, step size
/// underflow, an equilibrium that should exist but was not found.
class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A valid request the analyzer does not handle yet (e.g. n != 2 balls for equilibria).
class NotSupportedError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace abu
