// Reading an input file whole, with a size limit: a scene or a speed profile named as
// /dev/zero, /dev/urandom or a runaway pipe is refused at the limit instead of growing
// without bound (docs/robustness.md).
//
//   std::string text = abu::read_text_file(path, abu::scene_size_limit, "scene");
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace abu {

/// Scenes are a few kB (a 12-ball shaft scene ~10 kB): 16 MiB is far beyond any.
inline constexpr std::size_t scene_size_limit = std::size_t(16) << 20;
/// A speed profile of 10^6 points is ~30 MB.
inline constexpr std::size_t profile_size_limit = std::size_t(256) << 20;

/// The file's bytes. Throws InputError (path, line 0) if it cannot be opened or read, is a
/// directory, or holds more than `limit` bytes ("`what` larger than N MiB").
std::string read_text_file(const std::string& path, std::size_t limit, std::string_view what);

}  // namespace abu
