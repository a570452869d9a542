#include "abu/core/errors.hpp"

#include <fmt/format.h>

namespace abu {

namespace {
std::string input_message(const std::string& file, int line, const std::string& key, const std::string& rule) {
  std::string where = file.empty() ? std::string("input") : file;
  if (line > 0) where += fmt::format(":{}", line);
  if (key.empty()) return fmt::format("{}: {}", where, rule);
  return fmt::format("{}: key '{}': {}", where, key, rule);
}
}  // namespace

InputError::InputError(std::string file, int line, std::string key, std::string rule)
    : std::runtime_error(input_message(file, line, key, rule)),
      file_(std::move(file)),
      line_(line),
      key_(std::move(key)),
      rule_(std::move(rule)) {}

}  // namespace abu
