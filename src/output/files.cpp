// Outputs written together or not at all (files.hpp).
#include "abu/output/files.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <stdexcept>

#include "abu/core/errors.hpp"
#include "abu/core/temp_files.hpp"
#include "abu/output/format.hpp"
#include "chart_registry.hpp"

namespace abu {

namespace fs = std::filesystem;

namespace {
// Commits are atomic with respect to the signal thread: it waits for a commit under way.
std::mutex g_commit_mutex;

// Test hook (tests/cli/check_robustness.sh): the K-th rename into place fails, to check
// that the old files come back.
int failing_rename() {
  const char* env = std::getenv("ABU_TEST_FAIL_RENAME");
  return env ? std::atoi(env) : 0;
}
}  // namespace

namespace detail {
std::mutex& chart_mutex() {
  static std::mutex m;
  return m;
}
std::set<std::string>& failed_chart_outputs() {
  static std::set<std::string> paths;
  return paths;
}
std::set<std::string>& reserved_outputs() {
  static std::set<std::string> paths;
  return paths;
}
}  // namespace detail

TargetKind check_output_target(const fs::path& target, std::string_view option) {
  struct stat st {};
  if (::lstat(target.c_str(), &st) != 0) {
    if (errno == ENOENT) return TargetKind::absent;
    throw InputError(std::string(option), 0, escaped(target.string()),
                     fmt::format("cannot inspect the output: {}", std::strerror(errno)));
  }
  if (S_ISREG(st.st_mode)) return TargetKind::regular;
  if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) return TargetKind::in_place;
  const char* what = S_ISDIR(st.st_mode)   ? "a directory"
                     : S_ISLNK(st.st_mode) ? "a symbolic link (give the path it points to)"
                                           : "neither a regular file, a character device nor a FIFO";
  throw InputError(std::string(option), 0, escaped(target.string()),
                   fmt::format("the output exists and is {}: it is not replaced", what));
}

void check_output_directory(const fs::path& dir, std::string_view option) {
  struct stat st {};
  if (::stat(dir.c_str(), &st) != 0) {
    if (errno != ENOENT)
      throw InputError(std::string(option), 0, escaped(dir.string()),
                       fmt::format("cannot inspect the output directory: {}", std::strerror(errno)));
    // It will be created, with its missing parents: none of them may be a symbolic link to a
    // path that does not exist (creating it would fail with a raw filesystem error, exit 1).
    for (fs::path p = dir; !p.empty(); p = p.parent_path()) {
      struct stat part {};
      if (::stat(p.c_str(), &part) == 0) break;  // the first existing ancestor
      if (::lstat(p.c_str(), &part) == 0 && S_ISLNK(part.st_mode))
        throw InputError(std::string(option), 0, escaped(dir.string()),
                         fmt::format("{} is a symbolic link to a path that does not exist: the output directory cannot "
                                     "be created there (give another directory, or remove the link)",
                                     escaped(p.string())));
      if (p == p.parent_path()) break;
    }
    return;
  }
  if (!S_ISDIR(st.st_mode))
    throw InputError(std::string(option), 0, escaped(dir.string()), "the output directory exists and is not a directory");
}

fs::path OutputTransaction::temporary_for(const fs::path& target) {
  const TargetKind kind = check_output_target(target);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  check_output_directory(dir);
  if (!fs::exists(dir)) {
    // Remember which directories we create, outermost first, to undo them on failure.
    std::vector<fs::path> missing;
    for (fs::path d = dir; !d.empty() && !fs::exists(d); d = d.parent_path()) missing.push_back(d);
    fs::create_directories(dir);
    created_dirs_.insert(created_dirs_.end(), missing.begin(), missing.end());
  }
  fs::path tmp = create_temporary_next_to(target, "tmp");
  staged_.push_back({tmp, target, kind});
  return tmp;
}

namespace {
// Opens `path` with `flags` (no O_CREAT: the file exists, created exclusively or a device)
// and writes all of `content`, retrying interrupted and partial writes; throws with errno's
// message naming the file.
void write_all(const fs::path& path, int flags, std::string_view content) {
  const int fd = ::open(path.c_str(), flags);
  if (fd < 0) throw std::runtime_error(fmt::format("cannot write {}: {}", escaped(path.string()), std::strerror(errno)));
  std::size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = errno;
      ::close(fd);
      throw std::runtime_error(fmt::format("cannot write {}: {}", escaped(path.string()), std::strerror(err)));
    }
    done += std::size_t(n);
  }
  if (::close(fd) != 0)
    throw std::runtime_error(fmt::format("cannot write {}: {}", escaped(path.string()), std::strerror(errno)));
}
}  // namespace

fs::path OutputTransaction::stage(const fs::path& target, std::string_view content) {
  const fs::path tmp = temporary_for(target);
  // The temporary was created exclusively; O_NOFOLLOW again in case it was swapped.
  write_all(tmp, O_WRONLY | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, content);
  return tmp;
}

fs::path OutputTransaction::reserve(const fs::path& target) {
  fs::path tmp = temporary_for(target);
  std::lock_guard lock(detail::chart_mutex());
  detail::reserved_outputs().insert(tmp.string());
  return tmp;
}

fs::path OutputTransaction::reserve_data(const fs::path& target) { return temporary_for(target); }

namespace {
// Copies a staged file into a target written in place (a character device or a FIFO).
void copy_in_place(const fs::path& from, const fs::path& to) {
  std::string content;
  {
    const int in = ::open(from.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
    if (in < 0) throw std::runtime_error(fmt::format("cannot read {}: {}", escaped(from.string()), std::strerror(errno)));
    char buffer[65536];
    for (;;) {
      const ssize_t n = ::read(in, buffer, sizeof buffer);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      content.append(buffer, std::size_t(n));
    }
    ::close(in);
  }
  write_all(to, O_WRONLY | O_NOFOLLOW | O_CLOEXEC, content);
}
}  // namespace

void OutputTransaction::retire(const fs::path& target) { retired_.push_back(target); }

void OutputTransaction::commit() {
  std::lock_guard commit_lock(g_commit_mutex);
  std::vector<Entry> entries;
  {
    std::lock_guard lock(detail::chart_mutex());
    for (const auto& e : staged_) {
      if (detail::failed_chart_outputs().count(e.temporary.string())) {
        std::error_code ec;
        fs::remove(e.temporary, ec);
        unregister_temporary(e.temporary);
        continue;
      }
      entries.push_back(e);
    }
  }
  // Every target checked before the first rename (it may have changed since staging).
  for (auto& e : entries) e.kind = check_output_target(e.target);
  // Old files aside, new ones in; on failure everything back as it was.
  std::vector<std::pair<fs::path, fs::path>> aside;  // old file's new name, target
  std::vector<fs::path> moved_in;
  const auto roll_back = [&] {
    for (const auto& target : moved_in) ::unlink(target.c_str());
    for (const auto& [old, target] : aside) rename_no_replace(old, target);
  };
  const int fail_at = failing_rename();
  int renames = 0;
  for (const auto& e : entries) {
    if (e.kind != TargetKind::regular) continue;
    fs::path old = e.target.parent_path() / fmt::format(".{}.old-{}", e.target.filename().string(), random_suffix());
    if (e.target.parent_path().empty()) old = old.filename();
    if (const int err = rename_no_replace(e.target, old)) {
      roll_back();
      throw std::runtime_error(
          fmt::format("cannot move the old {} aside: {}; nothing replaced", escaped(e.target.string()), std::strerror(err)));
    }
    aside.emplace_back(old, e.target);
  }
  for (const auto& target : retired_) {
    std::error_code ec;
    const bool replaced = std::any_of(entries.begin(), entries.end(), [&](const Entry& e) { return e.target == target; });
    if (replaced || !fs::is_regular_file(fs::symlink_status(target, ec))) continue;
    fs::path old = target.parent_path() / fmt::format(".{}.old-{}", target.filename().string(), random_suffix());
    if (target.parent_path().empty()) old = old.filename();
    if (const int err = rename_no_replace(target, old)) {
      roll_back();
      throw std::runtime_error(
          fmt::format("cannot move the old {} aside: {}; nothing replaced", escaped(target.string()), std::strerror(err)));
    }
    aside.emplace_back(old, target);
  }
  for (const auto& e : entries) {
    if (e.kind == TargetKind::in_place) continue;
    ++renames;
    const int err = renames == fail_at ? EIO : rename_no_replace(e.temporary, e.target);
    if (err) {
      roll_back();
      throw std::runtime_error(fmt::format("cannot move {} into place: {}; the previous files are restored",
                                           escaped(e.target.string()), std::strerror(err)));
    }
    moved_in.push_back(e.target);
    unregister_temporary(e.temporary);
  }
  for (const auto& [old, target] : aside) ::unlink(old.c_str());
  committed_ = true;
  // Devices and FIFOs last: their writes cannot be undone.
  for (const auto& e : entries) {
    if (e.kind != TargetKind::in_place) continue;
    copy_in_place(e.temporary, e.target);
    ::unlink(e.temporary.c_str());
    unregister_temporary(e.temporary);
  }
}

OutputTransaction::~OutputTransaction() {
  std::error_code ec;
  for (const auto& staged : staged_) {
    {
      std::lock_guard lock(detail::chart_mutex());
      detail::reserved_outputs().erase(staged.temporary.string());
      detail::failed_chart_outputs().erase(staged.temporary.string());
    }
    if (committed_) continue;
    fs::remove(staged.temporary, ec);
    unregister_temporary(staged.temporary);
  }
  if (committed_) {
    for (const auto& staged : staged_) {
      if (fs::exists(staged.temporary, ec) && staged.kind == TargetKind::in_place) fs::remove(staged.temporary, ec);
      unregister_temporary(staged.temporary);
    }
    return;
  }
  for (const auto& dir : created_dirs_) fs::remove(dir, ec);  // only if empty
}

void hold_output_commits() noexcept { g_commit_mutex.lock(); }  // never released: the process ends

}  // namespace abu
