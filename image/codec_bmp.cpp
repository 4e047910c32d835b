#include <cstdint>
#include <cstdlib>

#include "image/codecs.hpp"

namespace aosuite::codecs {
namespace {

std::uint32_t le32(const unsigned char* p) {
  return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 |
         std::uint32_t(p[3]) << 24;
}

}  // namespace

int read_bmp(const unsigned char* bytes, std::size_t size, Allocate allocate, void* user,
             std::string& why) {
  if (size < 54) return why = "shorter than a BMP header", 1;
  const std::uint32_t offset = le32(bytes + 10), info = le32(bytes + 14);
  const auto width = std::int32_t(le32(bytes + 18)), height = std::int32_t(le32(bytes + 22));
  const int planes = bytes[26] | bytes[27] << 8, bits = bytes[28] | bytes[29] << 8;
  const std::uint32_t compression = le32(bytes + 30);
  // Uncompressed 24- or 32-bit, with a Windows info header (40 bytes or a later, longer one),
  // rows bottom-up or top-down: what renderers write. A plain 32-bit pixel's fourth byte is
  // reserved, not alpha (many writers leave it 0): read as RGB, as Pillow reads it (BGRX).
  // Palettes, 16 bits, bit fields and run-length encoding: OpenImageIO.
  if (info < 40 || planes != 1 || (bits != 24 && bits != 32) || compression != 0) return kNotMine;
  if (width <= 0 || height == 0 || height == INT32_MIN) return why = "an empty image", 1;
  const int rows = std::abs(height);
  const std::size_t bpp = std::size_t(bits) / 8;
  const std::size_t stride = (std::size_t(width) * bpp + 3) / 4 * 4;  // rows pad to 4 bytes
  if (offset > size || size - offset < stride * std::size_t(rows))
    return why = "the pixel data ends early", 1;
  auto* pixels = static_cast<unsigned char*>(allocate(user, width, rows, 3, 1));
  if (!pixels) return why = "refused", 1;
  for (int y = 0; y < rows; ++y) {
    const unsigned char* in = bytes + offset + std::size_t(height > 0 ? rows - 1 - y : y) * stride;
    unsigned char* out = pixels + std::size_t(y) * std::size_t(width) * 3;
    for (int x = 0; x < width; ++x, in += bpp, out += 3)
      out[0] = in[2], out[1] = in[1], out[2] = in[0];
  }
  return 0;
}

}  // namespace aosuite::codecs
