// Temporary files next to their targets, created exclusively (O_CREAT|O_EXCL|O_NOFOLLOW,
// a random suffix: a planted file or symbolic link is never opened), and a process-wide
// registry of the temporaries that exist, so that a stop request that cannot wait for
// the computation to unwind still removes them (docs/robustness.md "Output files").
#pragma once

#include <filesystem>
#include <string_view>

namespace abu {

/// An exclusively created, empty, registered temporary `DIR/.NAME.<tag>-<random>` in the
/// directory of `target` (which must exist). Returns its path; throws std::runtime_error
/// with errno's message.
std::filesystem::path create_temporary_next_to(const std::filesystem::path& target, std::string_view tag = "tmp");
/// As above, and opened for writing: the file descriptor is returned in `fd`.
std::filesystem::path create_temporary_next_to(const std::filesystem::path& target, std::string_view tag, int& fd);

/// A random lower-case hex string of `n` characters (getrandom).
std::string random_suffix(int n = 16);

/// Adds / removes a path to / from the registry of temporaries.
void register_temporary(const std::filesystem::path& path);
void unregister_temporary(const std::filesystem::path& path);
/// Unlinks every registered temporary (the signal thread, when the computation does not
/// stop in time). Returns how many were removed.
int remove_registered_temporaries() noexcept;

/// Renames `from` to `to` unless `to` exists (renameat2 RENAME_NOREPLACE, or link+unlink
/// where the file system lacks it). Returns 0 or an errno value.
int rename_no_replace(const std::filesystem::path& from, const std::filesystem::path& to) noexcept;

}  // namespace abu
