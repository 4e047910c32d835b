#include "compare/image_io.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <fmt/std.h>
#include <poll.h>
#include <spng.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <utility>

#include "compare/picture.hpp"
#include "compare/png_fast.hpp"
#include "compare/png_layout.hpp"

namespace aosuite {
namespace {

struct SpngDeleter {
  void operator()(spng_ctx* ctx) const { spng_ctx_free(ctx); }
};
using SpngCtx = std::unique_ptr<spng_ctx, SpngDeleter>;

constexpr unsigned char kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

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

void check_signature(std::span<const unsigned char> png, const std::string& name) {
  if (png.size() < sizeof kPngSignature ||
      std::memcmp(png.data(), kPngSignature, sizeof kPngSignature) != 0) {
    throw FileError(fmt::format("{}: not a PNG file", name));
  }
}

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

void write_file_atomic(const std::filesystem::path& path, std::span<const unsigned char> bytes) {
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
  if (::rename(tmp.c_str(), path.c_str()) != 0) abandon("cannot rename into place");
}

namespace {

// libspng reads only what the rule uses (png_layout.hpp): IHDR, PLTE and tRNS before the
// image data, the IDAT run and IEND, from the file's bytes in place. Ancillary chunks it
// would judge by rules of its own never reach it, so both decoders refuse the same files.
struct Feed {
  std::span<const std::span<const unsigned char>> pieces;
  std::size_t piece = 0, offset = 0;

  static int read(spng_ctx*, void* user, void* dest, std::size_t length) {
    auto& f = *static_cast<Feed*>(user);
    auto* out = static_cast<unsigned char*>(dest);
    while (length > 0) {
      if (f.piece == f.pieces.size()) return SPNG_IO_EOF;
      const auto& p = f.pieces[f.piece];
      const std::size_t n = std::min(length, p.size() - f.offset);
      std::memcpy(out, p.data() + f.offset, n);
      out += n, length -= n, f.offset += n;
      if (f.offset == p.size()) ++f.piece, f.offset = 0;
    }
    return 0;
  }
};

// A libspng decoder positioned after IHDR for a file that passed the rule's walk and stream
// check.
class SpngDecoder {
 public:
  SpngDecoder(const PngLayout& layout, const std::string& name)
      : name_(name), feed_{layout.for_decoder}, ctx_(spng_ctx_new(0)) {
    if (!ctx_) throw FileError(fmt::format("{}: out of memory", name));
    check(spng_set_png_stream(ctx_.get(), &Feed::read, &feed_), "cannot read");
    // Bound ancillary chunks too, so a hostile file cannot make us allocate gigabytes.
    check(spng_set_chunk_limits(ctx_.get(), 64u << 20, 64u << 20), "cannot read");
    spng_ihdr ihdr{};
    check(spng_get_ihdr(ctx_.get(), &ihdr), "bad PNG header");
  }
  spng_ctx* get() const { return ctx_.get(); }
  void check(int rc, const char* stage) const {
    if (rc != 0 && rc != SPNG_EOI) {
      throw FileError(
          fmt::format("{}: {} ({}): truncated or corrupt PNG?", name_, stage, spng_strerror(rc)));
    }
  }

 private:
  const std::string& name_;
  Feed feed_;
  SpngCtx ctx_;
};

}  // namespace

RgbaImage decode_png_general(std::span<const unsigned char> png, const std::string& name) {
  check_signature(png, name);
  const PngLayout layout = walk_png(png, name);
  check_png_stream(layout, name);  // before any pixel memory: libspng stops at the last row
  const SpngDecoder spng(layout, name);
  std::size_t size = 0;
  spng.check(spng_decoded_image_size(spng.get(), SPNG_FMT_RGBA8, &size), "cannot decode");
  RgbaImage rgba(static_cast<int>(layout.width), static_cast<int>(layout.height));
  spng.check(spng_decode_image(spng.get(), rgba.data(), size, SPNG_FMT_RGBA8, SPNG_DECODE_TRNS),
             "cannot decode");
  return rgba;
}

FloatImage decode_png16(std::span<const unsigned char> png, const std::string& name) {
  check_signature(png, name);
  const PngLayout layout = walk_png(png, name);
  check_png_stream(layout, name);
  const SpngDecoder spng(layout, name);
  std::size_t size = 0;
  spng.check(spng_decoded_image_size(spng.get(), SPNG_FMT_RGBA16, &size), "cannot decode");
  std::vector<std::uint16_t> rgba(size / 2);
  spng.check(spng_decode_image(spng.get(), rgba.data(), size, SPNG_FMT_RGBA16, SPNG_DECODE_TRNS),
             "cannot decode");
  // Grey (with or without alpha) stays one channel; alpha is not compared, as for 8-bit images.
  FloatImage f;
  f.width = static_cast<int>(layout.width), f.height = static_cast<int>(layout.height);
  f.channels = (layout.colour_type & 2) ? 3 : 1;
  f.srgb = true;
  const std::size_t pixels = std::size_t(f.width) * std::size_t(f.height);
  f.data.resize(pixels * std::size_t(f.channels));
  for (std::size_t i = 0; i < pixels; ++i) {
    for (int c = 0; c < f.channels; ++c) {
      f.data[i * std::size_t(f.channels) + std::size_t(c)] =
          float(rgba[i * 4 + std::size_t(c)]) / 65535.0f;
    }
  }
  return f;
}

RgbaImage decode_png(std::span<const unsigned char> png, const std::string& name) {
  check_signature(png, name);
  if (auto fast = decode_png_fast(png, name)) return *std::move(fast);
  return decode_png_general(png, name);
}

ImageSize check_png(std::span<const unsigned char> png, const std::string& name) {
  check_signature(png, name);
  if (const auto size = check_png_fast(png, name)) return *size;
  // The general decoder a row at a time: the image is never held whole.
  const PngLayout layout = walk_png(png, name);
  check_png_stream(layout, name);
  const SpngDecoder spng(layout, name);
  spng.check(spng_decode_image(spng.get(), nullptr, 0, SPNG_FMT_RGBA8,
                               SPNG_DECODE_TRNS | SPNG_DECODE_PROGRESSIVE),
             "cannot decode");
  std::vector<unsigned char> row(std::size_t{layout.width} * 4);
  int rc = 0;
  do {
    rc = spng_decode_row(spng.get(), row.data(), row.size());
    spng.check(rc, "cannot decode");
  } while (rc != SPNG_EOI);
  return {static_cast<int>(layout.width), static_cast<int>(layout.height)};
}

RgbaImage read_png(const std::filesystem::path& path) {
  return decode_png(MappedFile(path).bytes(), path.string());
}

std::vector<unsigned char> encode_png_rgba8(RgbaView rgba, int compression_level) {
  SpngCtx ctx(spng_ctx_new(SPNG_CTX_ENCODER));
  if (!ctx) throw FileError("PNG encoder: out of memory");
  spng_set_option(ctx.get(), SPNG_ENCODE_TO_BUFFER, 1);
  spng_set_option(ctx.get(), SPNG_IMG_COMPRESSION_LEVEL, compression_level);
  // Trying all five filters per row costs ~40 % of encode time for little size on renders.
  spng_set_option(ctx.get(), SPNG_FILTER_CHOICE, SPNG_FILTER_CHOICE_SUB | SPNG_FILTER_CHOICE_UP);
  spng_ihdr ihdr{};
  ihdr.width = static_cast<std::uint32_t>(rgba.width);
  ihdr.height = static_cast<std::uint32_t>(rgba.height);
  ihdr.bit_depth = 8;
  ihdr.color_type = SPNG_COLOR_TYPE_TRUECOLOR_ALPHA;
  int rc = spng_set_ihdr(ctx.get(), &ihdr);
  if (rc == 0) {
    rc = spng_encode_image(ctx.get(), rgba.data, rgba.bytes(), SPNG_FMT_PNG, SPNG_ENCODE_FINALIZE);
  }
  std::size_t len = 0;
  std::unique_ptr<void, decltype(&std::free)> buf(
      rc == 0 ? spng_get_png_buffer(ctx.get(), &len, &rc) : nullptr, &std::free);
  if (rc != 0 || !buf) throw FileError(fmt::format("PNG encoder: {}", spng_strerror(rc)));
  const auto* p = static_cast<const unsigned char*>(buf.get());
  return {p, p + len};
}

void write_png_rgba8(const std::filesystem::path& path, RgbaView rgba, int compression_level) {
  write_file_atomic(path, encode_png_rgba8(rgba, compression_level));
}

}  // namespace aosuite
