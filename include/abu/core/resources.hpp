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

/// The share of MemAvailable a command may plan to hold: the rest is the system's and the
/// estimates' margin.
inline constexpr double kUsableMemoryShare = 0.8;

/// Refuses, before any work, what would hold more than kUsableMemoryShare of the memory this
/// machine has available: InputError(option) "SUBJECT would hold about X (DETAIL), more than
/// 80 % of the Y this machine has available; REMEDY". Nothing where MemAvailable is unknown.
void require_memory(double bytes, const std::string& option, const std::string& subject, const std::string& detail,
                    const std::string& remedy);
/// The same for what would be written into `dir` against its free space.
void require_disk(double bytes, const std::filesystem::path& dir, const std::string& option,
                  const std::string& subject, const std::string& detail, const std::string& remedy);

}  // namespace abu
