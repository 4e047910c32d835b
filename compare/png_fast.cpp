#include "compare/png_fast.hpp"

#include <fmt/format.h>
#include <isa-l/crc.h>
#include <isa-l/igzip_lib.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

#include "compare/image_io.hpp"
#include "compare/png_layout.hpp"
#include "compare/png_unfilter.hpp"

namespace aosuite {
namespace {

std::uint32_t be32(const unsigned char* p) {
  return std::uint32_t{p[0]} << 24 | std::uint32_t{p[1]} << 16 | std::uint32_t{p[2]} << 8 | p[3];
}

FileError corrupt(const std::string& name, const char* why) {
  return FileError(fmt::format("{}: {}: truncated or corrupt PNG", name, why));
}

// Image data handed to inflate per call: each slice's CRC is computed just before inflate
// reads it, so it comes from memory once and then from cache (a separate first pass over
// all chunks read the compressed data twice); small enough to stay in L2, large enough that
// ISA-L's cost per call (up to 64 KB of history copied) stays small.
constexpr std::size_t kSlice = 128 << 10;

// The CRC of a chunk's type, the start of its CRC.
std::uint32_t type_crc(std::span<const unsigned char> data) {
  return crc32_gzip_refl(0, data.data() - 4, 4);
}

}  // namespace

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
  out.idat_ = std::move(layout.idat);
  out.crc_ = type_crc(out.idat_.front());
  out.width_ = layout.width, out.height_ = layout.height, out.bpp_ = colour == 6 ? 4 : 3;
  out.prev_.assign(out.row_len(), 0);
  out.state_ = std::make_unique<inflate_state>();
  isal_inflate_init(out.state_.get());
  out.state_->crc_flag = ISAL_ZLIB;
  return out;
}

// Counts the next n bytes of the current chunk as handed to inflate; checks the CRC of each
// chunk that this completes (empty ones included).
void PngRows::take(std::size_t n) {
  crc_ = crc32_gzip_refl(crc_, idat_[chunk_].data() + taken_, n);
  taken_ += n;
  while (chunk_ < idat_.size() && taken_ == idat_[chunk_].size()) {
    const std::span<const unsigned char> done = idat_[chunk_];
    if (crc_ != be32(done.data() + done.size())) throw corrupt(name_, "IDAT chunk CRC mismatch");
    taken_ = 0;
    if (++chunk_ < idat_.size()) crc_ = type_crc(idat_[chunk_]);
  }
}

void PngRows::take_rest() {
  while (chunk_ < idat_.size()) take(idat_[chunk_].size() - taken_);
}

// Gives inflate its next slice of image data, if any is left.
void PngRows::feed() {
  if (chunk_ == idat_.size()) return;
  inflate_state& s = *state_;
  const std::span<const unsigned char> rest = idat_[chunk_].subspan(taken_);
  if (rest.size() >= kSlice || chunk_ + 1 == idat_.size()) {
    const std::size_t n = std::min(rest.size(), kSlice);
    take(n);
    s.next_in = const_cast<unsigned char*>(rest.data());
    s.avail_in = static_cast<std::uint32_t>(n);
    return;
  }
  // Many encoders (libpng) write 8 KB chunks: a call per chunk would copy more history than
  // the chunk holds, so they are joined a slice at a time.
  gathered_.resize(kSlice);
  std::size_t n = 0;
  while (n < kSlice && chunk_ < idat_.size()) {
    const std::span<const unsigned char> part =
        idat_[chunk_].subspan(taken_, std::min(idat_[chunk_].size() - taken_, kSlice - n));
    std::memcpy(gathered_.data() + n, part.data(), part.size());
    take(part.size());
    n += part.size();
  }
  s.next_in = gathered_.data();
  s.avail_in = static_cast<std::uint32_t>(n);
}

// A bad CRC in the image data is named first, wherever it lies, as when all of them were
// checked before inflating.
void PngRows::fail(const char* why) {
  take_rest();
  throw corrupt(name_, why);
}

// Inflates into out[0, n) until it is full or the stream ends; how many bytes it wrote.
// `why` is the error for bad data.
std::uint32_t PngRows::inflate(unsigned char* out, std::uint32_t n, const char* why) {
  inflate_state& s = *state_;
  s.next_out = out;
  s.avail_out = n;
  while (s.avail_out > 0 && s.block_state != ISAL_BLOCK_FINISH) {
    if (s.avail_in == 0) feed();
    // ISA-L may still hold output when no input is left: called until it makes no progress.
    const std::uint32_t out_before = s.avail_out, in_before = s.avail_in;
    if (isal_inflate(&s) != ISAL_DECOMP_OK) fail(why);
    if (s.avail_out == out_before && s.avail_in == in_before) break;
  }
  return n - s.avail_out;
}

void PngRows::inflate_rows(unsigned char* raw, std::uint32_t rows) {
  if (rows == 0 || rows > height_ - row_) {
    throw std::logic_error("PngRows: reads must be 1.. rows left");
  }
  // At most 1 GiB + h bytes in all by kMaxImagePixels, so 32 bits suffice.
  const auto want = static_cast<std::uint32_t>((row_len() + 1) * rows);
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
  if (state_->block_state != ISAL_BLOCK_FINISH) fail("image data ends early");
  take_rest();
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
  constexpr std::size_t kScratch = 64 << 10;  // 16 pages; ISA-L's cost per call stays small
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
