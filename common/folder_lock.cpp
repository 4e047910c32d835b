#include "common/folder_lock.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iterator>
#include <mutex>
#include <set>
#include <sstream>
#include <string>

#include "common/file_io.hpp"
#include "common/printable.hpp"

namespace aosuite {

namespace fs = std::filesystem;

namespace {

// "pid 1234, since 2026-11-25 19:20:01 UTC: aosuite check suites/default.toml" for the process
// that holds a flock on the file `st` describes; "" when /proc/locks does not say.
std::string holder(const struct stat& st) {
  std::ifstream locks("/proc/locks");
  const std::string id = fmt::format("{:02x}:{:02x}:{}", major(st.st_dev), minor(st.st_dev),
                                     static_cast<unsigned long long>(st.st_ino));
  for (std::string line; std::getline(locks, line);) {
    // "1: FLOCK  ADVISORY  WRITE 1234 08:01:5678 0 EOF"
    std::istringstream words(line);
    std::string n, type, mode, access, file;
    long pid = 0;
    if (!(words >> n >> type >> mode >> access >> pid >> file) || type != "FLOCK" || file != id)
      continue;
    std::ifstream in(fmt::format("/proc/{}/cmdline", pid), std::ios::binary);
    std::string command((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    while (!command.empty() && command.back() == '\0') command.pop_back();
    for (char& c : command) c = c == '\0' ? ' ' : c;
    std::string since;
    struct stat proc {};
    if (::stat(fmt::format("/proc/{}", pid).c_str(), &proc) == 0) {
      std::tm utc{};
      gmtime_r(&proc.st_mtime, &utc);
      char when[32];
      std::strftime(when, sizeof when, ", since %Y-%m-%d %H:%M:%S UTC", &utc);
      since = when;
    }
    return fmt::format("pid {}{}: {}", pid, since, command);
  }
  return "";
}

// The user's folder for lock files, made private (0700) and checked to be the user's own
// folder, not a link or someone else's, since /tmp is shared.
fs::path lock_folder() {
  const char* runtime = std::getenv("XDG_RUNTIME_DIR");
  const fs::path dir = runtime && *runtime
                           ? fs::path(runtime) / "aosuite-locks"
                           : fs::path(fmt::format("/tmp/aosuite-locks-{}", ::getuid()));
  if (::mkdir(dir.c_str(), 0700) != 0 && errno != EEXIST)
    throw FileError(
        fmt::format("{}: cannot make the lock folder: {}", dir.string(), std::strerror(errno)));
  struct stat st {};
  if (::lstat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode) || st.st_uid != ::getuid())
    throw FileError(
        fmt::format("{}: not a folder of this user's, cannot lock there", dir.string()));
  return dir;
}

// "<FNV-1a 64 of the canonical path>-<its last name>.lock": one file per real path, whatever
// names lead to it (a link, "a/../R"), stable across runs and versions of aosuite.
std::string lock_name(const fs::path& canonical) {
  std::uint64_t h = 14695981039346656037ull;
  for (const char c : canonical.native())
    h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  std::string tail = canonical.filename().string().substr(0, 64);
  for (char& c : tail) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return fmt::format("{:016x}-{}.lock", h, tail);
}

// The folders this process holds: a second lock on one of them is the same run naming one
// folder for two jobs (`bless --report X --goldens X`), not another aosuite.
std::mutex held_mutex;
std::set<std::string> held;

}  // namespace

FolderLock::FolderLock(const fs::path& folder, bool wait) {
  std::error_code ec;
  fs::path top;
  for (fs::path p = fs::absolute(folder, ec); !p.empty() && !fs::exists(fs::symlink_status(p, ec));
       p = p.parent_path()) {
    top = p;
    if (p == p.parent_path()) break;
  }
  if (!top.empty() && fs::create_directories(folder, ec))
    made_ = fs::absolute(folder), made_top_ = top;
  const fs::path real = fs::canonical(folder, ec);
  if (ec || !fs::is_directory(real, ec)) {
    throw FileError(
        fmt::format("{}: cannot lock: {}", folder.string(), ec ? ec.message() : "not a folder"));
  }
  {
    const std::lock_guard<std::mutex> g(held_mutex);
    if (!held.insert(real.string()).second) {
      throw FileError(
          fmt::format("{}: named twice in one run; the report, goldens and expected "
                      "folders must be different folders",
                      folder.string()));
    }
  }
  real_ = real.string();
  const auto fail = [&](auto error) {
    if (fd_ >= 0) ::close(fd_);
    const std::lock_guard<std::mutex> g(held_mutex);
    held.erase(real_);
    throw error;
  };
  const fs::path file = lock_folder() / lock_name(real);
  fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd_ < 0) {
    fail(FileError(fmt::format("{}: cannot lock ({}): {}", folder.string(), file.string(),
                               std::strerror(errno))));
  }
  while (::flock(fd_, LOCK_EX | (wait ? 0 : LOCK_NB)) != 0) {
    if (errno == EINTR) continue;
    const int saved = errno;
    struct stat st {};
    const std::string who = ::fstat(fd_, &st) == 0 ? holder(st) : "";
    if (saved != EWOULDBLOCK) {
      fail(FileError(fmt::format("{}: cannot lock: {}", folder.string(), std::strerror(saved))));
    }
    fail(FolderBusy(printable(fmt::format("{}: in use by another aosuite{}; --wait waits for it",
                                          folder.string(), who.empty() ? "" : " (" + who + ")"))));
  }
}

FolderLock::~FolderLock() {
  ::close(fd_);  // releases the lock
  {
    const std::lock_guard<std::mutex> g(held_mutex);
    held.erase(real_);
  }
  std::error_code ec;
  for (fs::path p = made_; !p.empty() && fs::is_empty(p, ec) && fs::remove(p, ec);
       p = p.parent_path()) {
    if (p == made_top_) break;
  }
}

}  // namespace aosuite
