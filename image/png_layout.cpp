#include "image/png_layout.hpp"

#include <fmt/format.h>
#include <isa-l/crc.h>

#include <cstring>
#include <memory>

#include "common/file_io.hpp"
#include "common/printable.hpp"
#include "image/inflate.hpp"
#include "image/rgba_image.hpp"

namespace aosuite {
namespace {

constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

bool is(const unsigned char* type, const char* name) { return std::memcmp(type, name, 4) == 0; }

[[noreturn]] void corrupt(const std::string& name, const std::string& why) {
  throw FileError(fmt::format("{}: {}: truncated or corrupt PNG", name, why));
}

// A chunk's type as a message quotes it: in a corrupt file its four bytes may be any bytes.
std::string chunk_type(const unsigned char* type) {
  return printable(std::string_view(reinterpret_cast<const char*>(type), 4));
}

bool legal_depth(int colour, int depth) {
  switch (colour) {
    case 0:
      return depth == 1 || depth == 2 || depth == 4 || depth == 8 || depth == 16;
    case 3:
      return depth == 1 || depth == 2 || depth == 4 || depth == 8;
    case 2:
    case 4:
    case 6:
      return depth == 8 || depth == 16;
    default:
      return false;
  }
}

// Deflate's largest expansion: a length-258 match coded in 1 bit with a 1-bit distance code,
// 258 bytes from 2 bits.
constexpr std::uint64_t kMaxInflateRatio = 1032;

}  // namespace

int PngLayout::bits_per_pixel() const {
  const int samples = colour_type == 2 ? 3 : colour_type == 4 ? 2 : colour_type == 6 ? 4 : 1;
  return samples * bit_depth;
}

std::uint64_t PngLayout::filtered_bytes() const {
  const std::uint64_t bpp = static_cast<std::uint64_t>(bits_per_pixel());
  auto pass_bytes = [&](std::uint64_t w, std::uint64_t h) -> std::uint64_t {
    return w == 0 || h == 0 ? 0 : h * (1 + (w * bpp + 7) / 8);
  };
  if (interlace == 0) return pass_bytes(width, height);
  // Adam7: each pass's first column and row, and its step in each direction.
  static constexpr int kX0[7] = {0, 4, 0, 2, 0, 1, 0}, kY0[7] = {0, 0, 4, 0, 2, 0, 1};
  static constexpr int kDx[7] = {8, 8, 4, 4, 2, 2, 1}, kDy[7] = {8, 8, 8, 4, 4, 2, 2};
  std::uint64_t total = 0;
  for (int p = 0; p < 7; ++p) {
    const std::uint64_t w = (std::uint64_t{width} + kDx[p] - 1 - kX0[p]) / kDx[p];
    const std::uint64_t h = (std::uint64_t{height} + kDy[p] - 1 - kY0[p]) / kDy[p];
    total += pass_bytes(w, h);
  }
  return total;
}

PngHeader peek_png_header(std::span<const unsigned char> png, const std::string& name) {
  if (png.size() < sizeof kSignature || std::memcmp(png.data(), kSignature, 8) != 0) {
    throw FileError(fmt::format("{}: not a PNG file", name));
  }
  if (png.size() < 8 + 25 || be32(&png[8]) != 13 || !is(&png[12], "IHDR")) {
    corrupt(name, "bad PNG header");
  }
  return {be32(&png[16]), be32(&png[20]), png[24], png[25], png[28]};
}

PngLayout walk_png(std::span<const unsigned char> png, const std::string& name,
                   bool check_idat_crcs) {
  const PngHeader h = peek_png_header(png, name);
  if (crc32_gzip_refl(0, &png[12], 17) != be32(&png[29])) corrupt(name, "IHDR CRC mismatch");
  if (h.width == 0 || h.height == 0 || h.width > 0x7fffffffu || h.height > 0x7fffffffu ||
      !legal_depth(h.colour_type, h.bit_depth) || png[26] != 0 || png[27] != 0 || h.interlace > 1) {
    corrupt(name, "bad PNG header");
  }
  const std::uint64_t pixels = std::uint64_t{h.width} * h.height;
  if (h.width > 65535 || h.height > 65535 || pixels > kMaxImagePixels) {
    throw FileError(fmt::format("{}: {}x{} pixels is larger than the {} Mpixel limit", name,
                                h.width, h.height, kMaxImagePixels >> 20));
  }
  PngLayout out;
  out.width = h.width, out.height = h.height;
  out.bit_depth = h.bit_depth, out.colour_type = h.colour_type, out.interlace = h.interlace;
  out.for_decoder.push_back(png.first(8 + 25));
  // Where the IDAT run lies: not seen yet, in it, or after it.
  enum { kBefore, kIn, kAfter } idat_state = kBefore;
  std::size_t pos = 8 + 25, run_begin = 0;
  for (;;) {
    if (pos + 12 > png.size()) corrupt(name, "file ends before IEND");
    const std::uint32_t len = be32(&png[pos]);
    if (len > 0x7fffffffu) corrupt(name, "bad chunk length");
    if (len > png.size() - pos - 12) corrupt(name, "file ends inside a chunk");
    const unsigned char* type = &png[pos + 4];
    const std::size_t chunk_bytes = std::size_t{len} + 12;
    const bool critical = !(type[0] & 0x20);
    const bool check_crc = critical && (check_idat_crcs || !is(type, "IDAT"));
    if (check_crc && crc32_gzip_refl(0, type, len + 4) != be32(&png[pos + 8 + len])) {
      corrupt(name, fmt::format("{} chunk CRC mismatch", chunk_type(type)));
    }
    if (is(type, "IDAT")) {
      if (idat_state == kAfter) corrupt(name, "IDAT chunks not consecutive");
      if (idat_state == kBefore) run_begin = pos;
      idat_state = kIn;
      out.idat.emplace_back(&png[pos + 8], len);
      out.idat_bytes += len;
    } else {
      if (idat_state == kIn) {
        out.for_decoder.push_back(png.subspan(run_begin, pos - run_begin));
        idat_state = kAfter;
      }
      if (is(type, "IEND")) {
        if (idat_state == kBefore) corrupt(name, "no image data");
        if (len != 0) corrupt(name, "IEND chunk not empty");
        out.for_decoder.push_back(png.subspan(pos, chunk_bytes));
        break;
      }
      if (is(type, "PLTE")) {
        if (idat_state != kBefore) corrupt(name, "PLTE chunk after the image data");
        if (out.has_plte) corrupt(name, "second PLTE chunk");
        out.has_plte = true;
        out.for_decoder.push_back(png.subspan(pos, chunk_bytes));
      } else if (is(type, "tRNS")) {
        if (idat_state == kBefore) {
          out.has_trns = true;
          out.for_decoder.push_back(png.subspan(pos, chunk_bytes));
        }
      } else if (is(type, "IHDR")) {
        corrupt(name, "second IHDR chunk");
      } else if (critical) {
        corrupt(name, fmt::format("unknown critical chunk '{}'", chunk_type(type)));
      }
    }
    pos += chunk_bytes;
  }
  if (out.idat_bytes > UINT32_MAX) corrupt(name, "image data over 4 GiB");
  if (out.filtered_bytes() > kMaxInflateRatio * out.idat_bytes) {
    corrupt(name, fmt::format("{} bytes of image data cannot fill {}x{} pixels", out.idat_bytes,
                              out.width, out.height));
  }
  return out;
}

void check_png_stream(const PngLayout& layout, const std::string& name) {
  std::size_t chunk = 0;
  Inflater inflater([&]() -> std::span<const unsigned char> {
    while (chunk < layout.idat.size() && layout.idat[chunk].empty()) ++chunk;
    return chunk < layout.idat.size() ? layout.idat[chunk++] : std::span<const unsigned char>{};
  });
  constexpr std::size_t kScratch = 64 << 10;
  const auto scratch = std::make_unique<unsigned char[]>(kScratch);
  const std::uint64_t want = layout.filtered_bytes();
  std::uint64_t got = 0;
  for (;;) {
    const std::size_t n = inflater.inflate(scratch.get(), kScratch);
    if (inflater.bad()) corrupt(name, "bad image data");
    got += n;
    if (got > want) corrupt(name, "image data longer than the image");
    if (n < kScratch) break;  // the stream's end
  }
  if (got < want) corrupt(name, "bad or short image data");
}

}  // namespace aosuite
