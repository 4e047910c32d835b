#include "common/folder_lock.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iterator>
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
  fd_ = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd_ < 0) {
    throw FileError(fmt::format("{}: cannot lock: {}", folder.string(), std::strerror(errno)));
  }
  while (::flock(fd_, LOCK_EX | (wait ? 0 : LOCK_NB)) != 0) {
    if (errno == EINTR) continue;
    const int saved = errno;
    struct stat st {};
    const std::string who = ::fstat(fd_, &st) == 0 ? holder(st) : "";
    ::close(fd_);
    if (saved != EWOULDBLOCK) {
      throw FileError(fmt::format("{}: cannot lock: {}", folder.string(), std::strerror(saved)));
    }
    throw FolderBusy(printable(fmt::format("{}: in use by another aosuite{}; --wait waits for it",
                                           folder.string(), who.empty() ? "" : " (" + who + ")")));
  }
}

FolderLock::~FolderLock() {
  ::close(fd_);  // releases the lock
  std::error_code ec;
  for (fs::path p = made_; !p.empty() && fs::is_empty(p, ec) && fs::remove(p, ec);
       p = p.parent_path()) {
    if (p == made_top_) break;
  }
}

}  // namespace aosuite
