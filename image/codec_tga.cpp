#include <cstdint>
#include <cstring>
#include <vector>

#include "image/codecs.hpp"

namespace aosuite::codecs {
namespace {

std::uint16_t le16(const unsigned char* p) { return std::uint16_t(p[0] | p[1] << 8); }

// Targa's pixel data, run-length encoded or not, as `count` pixels of `depth` bytes.
bool unpack(const unsigned char*& at, const unsigned char* end, bool rle, std::size_t count,
            int depth, std::vector<unsigned char>& out, std::string& why) {
  const std::size_t n = count * std::size_t(depth);
  out.resize(n);
  if (!rle) {
    if (std::size_t(end - at) < n) return why = "the pixel data ends early", false;
    std::memcpy(out.data(), at, n);
    at += n;
    return true;
  }
  // Packets: a header byte, then one pixel repeated (high bit set) or that many pixels raw;
  // 1 + (header & 0x7F) pixels either way. A packet may run across rows, not past the image.
  for (std::size_t done = 0; done < n;) {
    if (at >= end) return why = "the pixel data ends early", false;
    const int header = *at++;
    const std::size_t pixels = std::size_t(header & 0x7F) + 1, bytes = pixels * std::size_t(depth);
    if (bytes > n - done) return why = "a run-length packet runs past the image", false;
    const std::size_t read = header & 0x80 ? std::size_t(depth) : bytes;
    if (std::size_t(end - at) < read) return why = "the pixel data ends early", false;
    for (std::size_t i = 0; i < bytes; ++i) out[done + i] = at[header & 0x80 ? i % depth : i];
    at += read;
    done += bytes;
  }
  return true;
}

}  // namespace

int read_tga(const unsigned char* bytes, std::size_t size, Allocate allocate, void* user,
             std::string& why) {
  if (size < 18) return why = "shorter than a Targa header", 1;
  const unsigned char* h = bytes;
  const int id_length = h[0], colour_map = h[1], type = h[2];
  const int map_length = le16(h + 5), map_entry_bits = h[7];
  const int width = le16(h + 12), height = le16(h + 14), bits = h[16], descriptor = h[17];
  // True colour (2, 10: run-length encoded) at 24 or 32 bits, grey (3, 11) at 8; origin at the
  // bottom or top left. Colour-mapped, 16-bit and right-to-left images: OpenImageIO.
  const bool colour = (type == 2 || type == 10) && (bits == 24 || bits == 32);
  const bool grey = (type == 3 || type == 11) && bits == 8;
  if ((!colour && !grey) || (descriptor & 0x10)) return kNotMine;
  if (width == 0 || height == 0) return why = "an empty image", 1;
  // Offsets, not pointers, until they are known to lie inside the file.
  std::size_t start = 18 + std::size_t(id_length);
  if (colour_map) start += std::size_t(map_length) * std::size_t((map_entry_bits + 7) / 8);
  if (start > size) return why = "the header runs past the file", 1;
  const unsigned char* at = bytes + start;
  const int depth = bits / 8, channels = grey ? 1 : depth;
  const std::size_t count = std::size_t(width) * std::size_t(height);
  const bool rle = type >= 9;
  if (!rle && size - start < count * std::size_t(depth))
    return why = "the pixel data ends early", 1;
  // The allocator's budget first: the header alone may claim gigabytes.
  auto* pixels = static_cast<unsigned char*>(allocate(user, width, height, channels, 1));
  if (!pixels) return why = "refused", 1;
  std::vector<unsigned char> stored;
  if (!unpack(at, bytes + size, rle, count, depth, stored, why)) return 1;
  const bool top_first = descriptor & 0x20;
  for (int y = 0; y < height; ++y) {
    const unsigned char* in = stored.data() + std::size_t(top_first ? y : height - 1 - y) *
                                                  std::size_t(width) * std::size_t(depth);
    unsigned char* out = pixels + std::size_t(y) * std::size_t(width) * std::size_t(channels);
    for (int x = 0; x < width; ++x, in += depth, out += channels) {
      if (grey) {
        out[0] = in[0];
        continue;
      }
      out[0] = in[2], out[1] = in[1], out[2] = in[0];  // stored B, G, R (, A)
      if (depth == 4) out[3] = in[3];
    }
  }
  return 0;
}

}  // namespace aosuite::codecs
