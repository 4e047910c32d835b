#include <cmath>
#include <cstdio>
#include <cstring>
#include <string_view>
#include <vector>

#include "image/codecs.hpp"

namespace aosuite::codecs {
namespace {

// The bytes after the header, read as Radiance's rgbe.c reads them.
class Scanlines {
 public:
  Scanlines(const unsigned char* at, const unsigned char* end) : at_(at), end_(end) {}

  // One scanline of `width` RGBE pixels into `out`: new-style run-length encoded when it
  // starts 2, 2 and the width (as rgbe.c, for 8 <= width < 32768), else flat, and once flat,
  // flat for the rest of the file. False with `why` when the data ends early or is malformed.
  bool next(int width, unsigned char* out, std::string& why) {
    const bool encodable = width >= 8 && width < 0x8000;
    if (flat_ || !encodable || end_ - at_ < 4 || at_[0] != 2 || at_[1] != 2 || (at_[2] & 0x80)) {
      flat_ = true;
      return take(out, std::size_t(width) * 4, why);
    }
    if ((at_[2] << 8 | at_[3]) != width) {
      why = "a run-length encoded scanline of another width";
      return false;
    }
    at_ += 4;
    for (int c = 0; c < 4; ++c) {
      for (int x = 0; x < width;) {
        if (at_ >= end_) return truncated(why);
        int count = *at_++;
        const bool run = count > 128;
        if (run) count -= 128;
        if (count == 0 || count > width - x) {
          why = "bad run-length encoded data";
          return false;
        }
        if (run) {
          if (at_ >= end_) return truncated(why);
          for (const unsigned char v = *at_++; count > 0; --count) out[4 * x++ + c] = v;
        } else {
          if (end_ - at_ < count) return truncated(why);
          for (; count > 0; --count) out[4 * x++ + c] = *at_++;
        }
      }
    }
    return true;
  }

 private:
  bool take(unsigned char* out, std::size_t n, std::string& why) {
    if (std::size_t(end_ - at_) < n) return truncated(why);
    std::memcpy(out, at_, n);
    at_ += n;
    return true;
  }
  static bool truncated(std::string& why) {
    why = "the pixel data ends early";
    return false;
  }
  const unsigned char* at_;
  const unsigned char* end_;
  bool flat_ = false;
};

// The next header line (without its newline), or false at the end of the bytes.
bool line(const unsigned char*& at, const unsigned char* end, std::string_view& out) {
  const auto* nl = static_cast<const unsigned char*>(std::memchr(at, '\n', std::size_t(end - at)));
  if (!nl) return false;
  out = std::string_view(reinterpret_cast<const char*>(at), std::size_t(nl - at));
  at = nl + 1;
  return true;
}

}  // namespace

int read_hdr(const unsigned char* bytes, std::size_t size, Allocate allocate, void* user,
             std::string& why) {
  const unsigned char *at = bytes, *end = bytes + size;
  std::string_view text;
  // Header lines up to the empty one; the format must be RGBE (XYZE is left to OpenImageIO).
  while (true) {
    if (!line(at, end, text)) {
      why = "the header does not end";
      return 1;
    }
    if (text.empty()) break;
    if (text.starts_with("FORMAT=") && text != "FORMAT=32-bit_rle_rgbe") return kNotMine;
  }
  int width = 0, height = 0;
  char tail = 0;
  // Top to bottom, left to right, as nearly every writer stores it; other orders: OpenImageIO.
  if (!line(at, end, text) ||
      std::sscanf(std::string(text).c_str(), "-Y %d +X %d%c", &height, &width, &tail) != 2)
    return kNotMine;
  if (width <= 0 || height <= 0) {
    why = "an empty image";
    return 1;
  }
  auto* pixels = static_cast<float*>(allocate(user, width, height, 3, 4));
  if (!pixels) {
    why = "refused";
    return 1;
  }
  Scanlines scanlines(at, end);
  std::vector<unsigned char> rgbe(std::size_t(width) * 4);
  for (int y = 0; y < height; ++y) {
    if (!scanlines.next(width, rgbe.data(), why)) return 1;
    float* out = pixels + std::size_t(y) * std::size_t(width) * 3;
    for (int x = 0; x < width; ++x) {
      const unsigned char* p = &rgbe[std::size_t(x) * 4];
      // rgbe.c's rgbe2float: 0 for exponent 0, else each mantissa times 2^(e - 136).
      const float f = p[3] ? std::ldexp(1.0f, int(p[3]) - 136) : 0.0f;
      for (int c = 0; c < 3; ++c) out[3 * x + c] = float(p[c]) * f;
    }
  }
  return 0;
}

}  // namespace aosuite::codecs
