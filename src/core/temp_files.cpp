#include "abu/core/temp_files.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/random.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>

namespace abu {

namespace fs = std::filesystem;

namespace {
std::mutex g_mutex;
std::set<std::string>& registry() {
  static std::set<std::string> paths;
  return paths;
}
}  // namespace

std::string random_suffix(int n) {
  static constexpr char hex[] = "0123456789abcdef";
  std::string s;
  unsigned char bytes[32];
  while (int(s.size()) < n) {
    ssize_t got = getrandom(bytes, sizeof bytes, 0);
    if (got <= 0) throw std::runtime_error(fmt::format("getrandom: {}", std::strerror(errno)));
    for (ssize_t i = 0; i < got && int(s.size()) < n; ++i) s += hex[bytes[i] & 15];
  }
  return s;
}

fs::path create_temporary_next_to(const fs::path& target, std::string_view tag, int& fd) {
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  for (int attempt = 0;; ++attempt) {
    const fs::path tmp = dir / fmt::format(".{}.{}-{}", target.filename().string(), tag, random_suffix());
    fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd >= 0) {
      register_temporary(tmp);
      return tmp;
    }
    if (errno != EEXIST || attempt > 8)
      throw std::runtime_error(fmt::format("cannot create a temporary next to {}: {}", target.string(), std::strerror(errno)));
  }
}

fs::path create_temporary_next_to(const fs::path& target, std::string_view tag) {
  int fd = -1;
  fs::path tmp = create_temporary_next_to(target, tag, fd);
  ::close(fd);
  return tmp;
}

void register_temporary(const fs::path& path) {
  std::lock_guard lock(g_mutex);
  registry().insert(path.string());
}

void unregister_temporary(const fs::path& path) {
  std::lock_guard lock(g_mutex);
  registry().erase(path.string());
}

int remove_registered_temporaries() noexcept {
  std::lock_guard lock(g_mutex);
  int removed = 0;
  for (const auto& p : registry())
    if (::unlink(p.c_str()) == 0) ++removed;
  registry().clear();
  return removed;
}

int rename_no_replace(const fs::path& from, const fs::path& to) noexcept {
  if (::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_NOREPLACE) == 0) return 0;
  if (errno != EINVAL && errno != ENOSYS) return errno;
  // No RENAME_NOREPLACE on this file system: link() refuses an existing name too.
  if (::link(from.c_str(), to.c_str()) != 0) return errno;
  ::unlink(from.c_str());
  return 0;
}

}  // namespace abu
