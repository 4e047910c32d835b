#include "image/png_fast.hpp"

#include <fmt/format.h>
#include <isa-l/crc.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

#include "common/file_io.hpp"
#include "image/png_layout.hpp"
#include "image/png_unfilter.hpp"
#include "image/rgba_image.hpp"

namespace aosuite {
namespace {

FileError corrupt(const std::string& name, const char* why) {
  return FileError(fmt::format("{}: {}: truncated or corrupt PNG", name, why));
}

// Image data handed to inflate at a time: each slice's CRC is computed just before inflate
// reads it, so it comes from memory once and then from cache (a separate first pass over
// all chunks read the compressed data twice).
constexpr std::size_t kSlice = 128 << 10;

// The CRC of a chunk's type, the start of its CRC.
std::uint32_t type_crc(std::span<const unsigned char> data) {
  return crc32_gzip_refl(0, data.data() - 4, 4);
}

}  // namespace

// The image data, a slice at a time; each chunk's CRC is checked once all of it was handed
// over.
struct PngRows::Feed {
  std::string name;
  std::vector<std::span<const unsigned char>> idat;  // the IDAT chunks' data, in order
  // The chunk being handed over, how much of it has been, and the CRC of its type and of
  // those bytes.
  std::size_t chunk = 0, taken = 0;
  std::uint32_t crc = 0;

  // Counts the next n bytes of the current chunk as handed over; checks the CRC of each
  // chunk that this completes (empty ones included).
  void take(std::size_t n) {
    crc = crc32_gzip_refl(crc, idat[chunk].data() + taken, n);
    taken += n;
    while (chunk < idat.size() && taken == idat[chunk].size()) {
      const std::span<const unsigned char> done = idat[chunk];
      if (crc != be32(done.data() + done.size())) throw corrupt(name, "IDAT chunk CRC mismatch");
      taken = 0;
      if (++chunk < idat.size()) crc = type_crc(idat[chunk]);
    }
  }
  void take_rest() {
    while (chunk < idat.size()) take(idat[chunk].size() - taken);
  }
  // The next slice (empty at the end); small chunks are handed over as they are, since
  // inflate costs nothing per piece beyond its last few bytes.
  std::span<const unsigned char> next() {
    while (chunk < idat.size()) {
      const std::span<const unsigned char> rest = idat[chunk].subspan(taken);
      const std::size_t n = std::min(rest.size(), kSlice);
      take(n);  // an empty chunk is only checked
      if (n > 0) return rest.first(n);
    }
    return {};
  }
};

PngRows::PngRows(std::string name)
    : feed_(std::make_unique<Feed>(Feed{std::move(name), {}, 0, 0, 0})),
      inflater_([feed = feed_.get()] { return feed->next(); }) {}
PngRows::PngRows(PngRows&&) noexcept = default;
PngRows& PngRows::operator=(PngRows&&) noexcept = default;
PngRows::~PngRows() = default;

// Checks the file against the one validity rule (png_layout.hpp): the chunks and their
// CRCs here, in the same walk libspng's path makes, but for the image data's; those, the zlib
// stream, its Adler-32 and each row's filter as rows are read.
std::optional<PngRows> PngRows::open(std::span<const unsigned char> png, const std::string& name) {
  // Only the fast kind, from IHDR alone; everything else (and what is not a PNG at all) is
  // the general decoder's to accept or refuse.
  static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (png.size() < 8 + 25 || std::memcmp(png.data(), kSignature, 8) != 0 || be32(&png[8]) != 13 ||
      std::memcmp(&png[12], "IHDR", 4) != 0) {
    return std::nullopt;
  }
  const int depth = png[24], colour = png[25], interlace = png[28];
  if (depth != 8 || (colour != 2 && colour != 6) || interlace != 0) return std::nullopt;
  PngLayout layout = walk_png(png, name, false);
  if (layout.has_plte || layout.has_trns) return std::nullopt;  // a colour key: libspng's
  PngRows out(name);
  out.feed_->idat = std::move(layout.idat);
  out.feed_->crc = type_crc(out.feed_->idat.front());
  out.width_ = layout.width, out.height_ = layout.height, out.bpp_ = colour == 6 ? 4 : 3;
  out.prev_.assign(out.row_len(), 0);
  return out;
}

// A bad CRC in the image data is named first, wherever it lies, as when all of them were
// checked before inflating.
void PngRows::fail(const char* why) {
  feed_->take_rest();
  throw corrupt(feed_->name, why);
}

// Inflates into out[0, n) until it is full or the stream ends; how many bytes it wrote.
// `why` is the error for bad data.
std::size_t PngRows::inflate(unsigned char* out, std::size_t n, const char* why) {
  const std::size_t got = inflater_.inflate(out, n);
  if (inflater_.bad()) fail(inflater_.ran_out() ? "image data ends early" : why);
  return got;
}

void PngRows::inflate_rows(unsigned char* raw, std::uint32_t rows) {
  if (rows == 0 || rows > height_ - row_) {
    throw std::logic_error("PngRows: reads must be 1.. rows left");
  }
  const std::size_t want = (row_len() + 1) * rows;
  if (inflate(raw, want, "bad or short image data") != want) fail("bad or short image data");
  for (std::uint32_t y = 0; y < rows; ++y) {
    if (raw[y * (row_len() + 1)] > 4) fail("unknown row filter");
  }
  row_ += rows;
  if (row_ == height_) finish();
}

// After the last row the stream must end, with nothing more to inflate and a good Adler-32;
// image data after that end is not inflated, but its CRCs are checked.
void PngRows::finish() {
  unsigned char extra = 0;
  if (inflate(&extra, 1, "bad image data") != 0) fail("bad image data");
  if (!inflater_.ended()) fail("image data ends early");
  feed_->take_rest();
}

void PngRows::read(unsigned char* out, std::uint32_t rows) {
  const std::size_t len = row_len();
  // Inflated a row into the buffer and unfiltered to its start, so the same memory becomes
  // the pixels: no second buffer and no extra pass.
  inflate_rows(out + kUnfilterRoomRows * len, rows);
  unfilter_rows(out + kUnfilterRoomRows * len, out, prev_.data(), len, bpp_, rows);
  std::memcpy(prev_.data(), out + (rows - 1) * len, len);
  if (bpp_ == 4) return;
  // RGB to RGBA from the last pixel back, as each pixel moves right.
  for (std::size_t i = std::size_t{rows} * width_; i-- > 0;) {
    const unsigned char r = out[3 * i], g = out[3 * i + 1], b = out[3 * i + 2];
    out[4 * i] = r, out[4 * i + 1] = g, out[4 * i + 2] = b, out[4 * i + 3] = 255;
  }
}

void PngRows::skip(std::uint32_t rows) {
  constexpr std::size_t kScratch = 64 << 10;  // 16 pages
  const auto band =
      static_cast<std::uint32_t>(std::max<std::size_t>(1, kScratch / (row_len() + 1)));
  std::vector<unsigned char> raw(std::size_t{std::min(band, rows)} * (row_len() + 1));
  while (rows > 0) {
    const std::uint32_t n = std::min(band, rows);
    inflate_rows(raw.data(), n);
    rows -= n;
  }
}

std::optional<ImageSize> check_png_fast(std::span<const unsigned char> png,
                                        const std::string& name) {
  std::optional<PngRows> rows = PngRows::open(png, name);
  if (!rows) return std::nullopt;
  rows->skip(rows->height());
  return ImageSize{static_cast<int>(rows->width()), static_cast<int>(rows->height())};
}

std::optional<RgbaImage> decode_png_fast(std::span<const unsigned char> png,
                                         const std::string& name) {
  std::optional<PngRows> rows = PngRows::open(png, name);
  if (!rows) return std::nullopt;
  const std::uint32_t w = rows->width(), h = rows->height();
  PixelBuffer pixels(rows->band_bytes(h));
  rows->read(pixels.data(), h);
  return RgbaImage(std::move(pixels), static_cast<int>(w), static_cast<int>(h));
}

}  // namespace aosuite
