#include "common/file_io.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <poll.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <utility>

namespace aosuite {
namespace {

[[noreturn]] void fail_errno(const std::filesystem::path& path, const char* what) {
  throw FileError(fmt::format("{}: {}: {}", path.string(), what, std::strerror(errno)));
}

struct Fd {
  int fd;
  explicit Fd(int f) : fd(f) {}
  Fd(Fd&& o) noexcept : fd(std::exchange(o.fd, -1)) {}
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  Fd& operator=(Fd&&) = delete;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

namespace {

// Anonymous pipes (a shell's `|`, `<(...)`, /dev/stdin) live on pipefs; a named FIFO lives
// on a real file system.
bool is_anonymous_pipe(const struct stat& st) {
  static const dev_t pipefs = [] {
    int fds[2];
    struct stat p {};
    if (::pipe2(fds, O_CLOEXEC) != 0) return dev_t{0};
    const int rc = ::fstat(fds[0], &p);
    ::close(fds[0]), ::close(fds[1]);
    return rc == 0 ? p.st_dev : dev_t{0};
  }();
  return S_ISFIFO(st.st_mode) && pipefs != 0 && st.st_dev == pipefs;
}

int fifo_wait_ms() {
  if (const char* env = std::getenv("AOSUITE_FIFO_WAIT_MS")) {
    char* end = nullptr;
    const long ms = std::strtol(env, &end, 10);
    if (end != env && *end == '\0' && ms >= 0 && ms <= 24L * 3600 * 1000) return int(ms);
  }
  return kFifoWaitMs;
}

// Opens `path` for reading without blocking: opening a named FIFO blocks until a writer
// opens it, forever if none does. Such a FIFO gets a bounded wait for its first byte
// instead (the writer of `mkfifo f; producer > f & aosuite compare f ...` is usually
// already waiting in its own open); after that, and for everything else, reads block as
// usual. An anonymous pipe always had a writer, and reads end-of-file once it is gone.
Fd open_for_reading(const std::filesystem::path& path, struct stat& st) {
  Fd f{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK)};
  if (f.fd < 0) fail_errno(path, "cannot open");
  if (::fstat(f.fd, &st) != 0) fail_errno(path, "cannot stat");
  if (S_ISDIR(st.st_mode)) throw FileError(fmt::format("{}: is a directory", path.string()));
  if (S_ISFIFO(st.st_mode) && !is_anonymous_pipe(st)) {
    const int wait_ms = fifo_wait_ms();
    pollfd p{f.fd, POLLIN, 0};
    int n = 0;
    while ((n = ::poll(&p, 1, wait_ms)) < 0 && errno == EINTR) {
    }
    if (n < 0) fail_errno(path, "cannot wait for data");
    if (n == 0) {
      throw FileError(
          fmt::format("{}: a FIFO with no data after {} ms (no writer?)", path.string(), wait_ms));
    }
  }
  const int flags = ::fcntl(f.fd, F_GETFL);
  if (flags < 0 || ::fcntl(f.fd, F_SETFL, flags & ~O_NONBLOCK) != 0) {
    fail_errno(path, "cannot read");
  }
  return f;
}

[[noreturn]] void too_large(const std::filesystem::path& path, std::uint64_t max_bytes) {
  throw FileError(
      fmt::format("{}: file larger than the {} MiB memory budget", path.string(), max_bytes >> 20));
}

// Reads to end-of-file, however large the file said it was (0 for pipes and /proc files).
std::vector<unsigned char> read_all(const std::filesystem::path& path, int fd,
                                    const struct stat& st, std::uint64_t max_bytes) {
  std::vector<unsigned char> bytes;
  std::size_t size = S_ISREG(st.st_mode) && st.st_size > 0 ? std::size_t(st.st_size) : 0;
  if (size > max_bytes) too_large(path, max_bytes);
  bytes.resize(std::max<std::size_t>(size + 1, 64 << 10));  // + 1: to see the end at once
  std::size_t done = 0;
  for (;;) {
    if (done == bytes.size()) {
      if (done > max_bytes) too_large(path, max_bytes);
      const std::uint64_t cap = max_bytes == UINT64_MAX ? max_bytes : max_bytes + 1;
      bytes.resize(std::min<std::uint64_t>(std::uint64_t{bytes.size()} * 2, cap));
    }
    const ssize_t n = ::read(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail_errno(path, "cannot read");
    if (n == 0) break;
    done += static_cast<std::size_t>(n);
  }
  if (done > max_bytes) too_large(path, max_bytes);
  bytes.resize(done);
  return bytes;
}

}  // namespace

std::vector<unsigned char> read_file(const std::filesystem::path& path, std::uint64_t max_bytes) {
  struct stat st {};
  const Fd f = open_for_reading(path, st);
  return read_all(path, f.fd, st, max_bytes);
}

std::vector<unsigned char> read_regular_file(const std::filesystem::path& path,
                                             std::uint64_t max_bytes) {
  // O_NONBLOCK: a FIFO must not hold the run until a writer comes; it is refused below.
  const Fd f{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
  if (f.fd < 0) fail_errno(path, "cannot open");
  struct stat st {};
  if (::fstat(f.fd, &st) != 0) fail_errno(path, "cannot stat");
  if (!S_ISREG(st.st_mode)) {
    const char* kind = S_ISDIR(st.st_mode)                          ? "a folder"
                       : S_ISFIFO(st.st_mode)                       ? "a FIFO"
                       : S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) ? "a device"
                                                                    : "a socket";
    throw FileError(fmt::format("{}: is {}, not a regular file", path.string(), kind));
  }
  return read_all(path, f.fd, st, max_bytes);
}

void check_no_link_out(const std::filesystem::path& path, const std::filesystem::path& root,
                       std::string_view opt_in) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path real = fs::weakly_canonical(path, ec);
  if (ec || real == fs::absolute(path, ec).lexically_normal()) return;  // no link on the way
  const fs::path inside = fs::weakly_canonical(root, ec);
  const auto [end, at] = std::mismatch(inside.begin(), inside.end(), real.begin(), real.end());
  if (!ec && end == inside.end()) return;  // a link within the folder
  throw FileError(fmt::format("{}: is a link out of {} (to {}); {}", path.string(), root.string(),
                              real.string(), opt_in));
}

MappedFile::MappedFile(const std::filesystem::path& path, std::uint64_t max_bytes) {
  struct stat st {};
  const Fd f = open_for_reading(path, st);
  if (S_ISREG(st.st_mode) && std::uint64_t(st.st_size) > max_bytes) too_large(path, max_bytes);
  if (S_ISREG(st.st_mode) && st.st_size > 0) {
    void* p = ::mmap(nullptr, static_cast<std::size_t>(st.st_size), PROT_READ,
                     MAP_PRIVATE | MAP_POPULATE, f.fd, 0);
    if (p != MAP_FAILED) {
      data_ = static_cast<const unsigned char*>(p);
      size_ = static_cast<std::size_t>(st.st_size);
      return;
    }
  }
  fallback_ = read_all(path, f.fd, st, max_bytes);
  data_ = fallback_.data();
  size_ = fallback_.size();
  mapped_ = false;
}

MappedFile::~MappedFile() {
  if (mapped_ && data_) ::munmap(const_cast<unsigned char*>(data_), size_);
}

namespace {

// Writes `bytes` to a new temporary beside `path`, with the permissions a plain create would
// give, and syncs it; returns its name. Nothing is left behind when it throws.
std::string write_temporary(const std::filesystem::path& path,
                            std::span<const unsigned char> bytes) {
  const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : ".";
  std::string tmp = (dir / fmt::format(".{}.tmp-XXXXXX", path.filename().string())).string();
  Fd f{::mkstemp(tmp.data())};
  if (f.fd < 0) fail_errno(path, "cannot create a temporary file beside it");
  auto abandon = [&](const char* what) {
    const int saved = errno;
    ::unlink(tmp.c_str());
    errno = saved;
    fail_errno(path, what);
  };
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(f.fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) abandon("cannot write");
    done += static_cast<std::size_t>(n);
  }
  // mkstemp creates 0600; give the file the permissions a plain create would.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  if (::fchmod(f.fd, 0666 & ~mask) != 0 || ::fsync(f.fd) != 0) abandon("cannot finish writing");
  if (::close(f.fd) != 0) {
    f.fd = -1;
    abandon("cannot close");
  }
  f.fd = -1;
  return tmp;
}

void rename_into_place(const std::string& tmp, const std::filesystem::path& path) {
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int saved = errno;
    ::unlink(tmp.c_str());
    errno = saved;
    fail_errno(path, "cannot rename into place");
  }
}

}  // namespace

void write_file_atomic(const std::filesystem::path& path, std::span<const unsigned char> bytes) {
  rename_into_place(write_temporary(path, bytes), path);
}

StagedFiles::~StagedFiles() {
  for (const auto& [path, tmp] : staged_) ::unlink(tmp.c_str());
}

void StagedFiles::stage(const std::filesystem::path& path, std::span<const unsigned char> bytes) {
  staged_.emplace_back(path, write_temporary(path, bytes));
}

void StagedFiles::commit() {
  while (!staged_.empty()) {
    rename_into_place(staged_.front().second, staged_.front().first);
    staged_.erase(staged_.begin());
  }
}

void write_text(const std::filesystem::path& path, std::string_view text) {
  write_file_atomic(path, {reinterpret_cast<const unsigned char*>(text.data()), text.size()});
}

}  // namespace aosuite
