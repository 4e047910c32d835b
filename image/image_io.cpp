#include "image/image_io.hpp"

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

#include "image/png_fast.hpp"
#include "image/png_layout.hpp"

namespace aosuite {
namespace {

struct SpngDeleter {
  void operator()(spng_ctx* ctx) const { spng_ctx_free(ctx); }
};
using SpngCtx = std::unique_ptr<spng_ctx, SpngDeleter>;

constexpr unsigned char kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

void check_signature(std::span<const unsigned char> png, const std::string& name) {
  if (png.size() < sizeof kPngSignature ||
      std::memcmp(png.data(), kPngSignature, sizeof kPngSignature) != 0) {
    throw FileError(fmt::format("{}: not a PNG file", name));
  }
}

}  // namespace

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
