#include "abu/core/resources.hpp"

#include <fmt/format.h>

#include "abu/core/errors.hpp"
#include <sys/statvfs.h>

#include <fstream>
#include <system_error>

namespace abu {

std::optional<double> available_memory() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kb = 0;
  std::string unit;
  while (in >> key >> kb >> unit)
    if (key == "MemAvailable:") return kb * 1024;
  return std::nullopt;
}

std::optional<double> free_bytes(std::filesystem::path dir) {
  std::error_code ec;
  dir = std::filesystem::absolute(dir, ec);
  while (!dir.empty() && !std::filesystem::exists(dir, ec) && dir != dir.parent_path()) dir = dir.parent_path();
  struct statvfs fs {};
  if (::statvfs(dir.c_str(), &fs) != 0) return std::nullopt;
  return double(fs.f_bavail) * double(fs.f_frsize);
}

std::string gigabytes(double bytes) { return fmt::format("{:.3g} GB", bytes / 1e9); }

void require_memory(double bytes, const std::string& option, const std::string& subject, const std::string& detail,
                    const std::string& remedy) {
  const auto available = available_memory();
  if (!available || bytes <= kUsableMemoryShare * *available) return;
  throw InputError(option, 0, "",
                   fmt::format("{} would hold about {} ({}), more than {:.0f} % of the {} this machine has available; {}",
                               subject, gigabytes(bytes), detail, 100 * kUsableMemoryShare, gigabytes(*available),
                               remedy));
}

void require_disk(double bytes, const std::filesystem::path& dir, const std::string& option,
                  const std::string& subject, const std::string& detail, const std::string& remedy) {
  const auto free = free_bytes(dir);
  if (!free || bytes <= *free) return;
  throw InputError(option, 0, "",
                   fmt::format("{} would write about {} ({}) into {}, where {} are free; {}", subject,
                               gigabytes(bytes), detail, dir.string(), gigabytes(*free), remedy));
}

}  // namespace abu
