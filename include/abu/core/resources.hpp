// What this machine has for the work at hand: memory and disk, read before big work so that
// a command refuses up front what cannot fit instead of failing (or being killed) half way
// (docs/robustness.md).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace abu {

/// MemAvailable of /proc/meminfo [bytes]; nullopt where there is none.
std::optional<double> available_memory();
/// Free bytes for an unprivileged user on the file system holding `dir` (or its nearest
/// existing ancestor); nullopt if it cannot be read.
std::optional<double> free_bytes(std::filesystem::path dir);
/// "1.23 GB".
std::string gigabytes(double bytes);

}  // namespace abu
