#include "abu/core/text_file.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "abu/core/errors.hpp"

namespace abu {

std::string read_text_file(const std::string& path, std::size_t limit, std::string_view what) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path, 0, "", "cannot read file: it is a directory");
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const int err = errno;
    throw InputError(path, 0, "",
                     fmt::format("cannot read file: {}", err ? std::generic_category().message(err) : "open failed"));
  }
  // In blocks, never more than limit + 1 bytes: a device or pipe without end stops there.
  std::string text;
  constexpr std::size_t block = 1 << 16;
  while (in && text.size() <= limit) {
    const std::size_t at = text.size();
    text.resize(at + block);
    in.read(text.data() + at, std::streamsize(block));
    text.resize(at + std::size_t(in.gcount()));
  }
  if (in.bad()) throw InputError(path, 0, "", "cannot read file: read error");
  if (text.size() > limit)
    throw InputError(path, 0, "", fmt::format("the {} is larger than {} MiB (a device or an endless stream?)", what,
                                              limit >> 20));
  return text;
}

}  // namespace abu
