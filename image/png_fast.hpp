// A fast decoder for the PNGs renderers and screenshot tools actually write: 8-bit RGB or
// RGBA, not interlaced. Inflate is most of a compare's run time, so it is the project's own,
// tuned to PNG data (inflate.hpp): 11.3 ms for the noisy peers-bench 1080p image here,
// against 15.5 ms for ISA-L's (which is 10-20% faster on smooth renders), about 20 ms for
// libdeflate's and twice that for zlib's streaming inflate inside libspng. Every other kind
// of PNG goes to libspng.
//
// Rows can be read a band at a time, so a comparison need not hold either image: on the
// virtual machines this runs on, memory the process has not touched before costs up to
// 3 ms per MB to fault in (the host reclaims pages the guest frees), more than decoding it.
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "image/inflate.hpp"
#include "image/png_unfilter.hpp"
#include "image/rgba_image.hpp"

namespace aosuite {

// One PNG of the fast kind, inflated and unfiltered top to bottom on demand. The PNG's
// bytes must outlive it.
class PngRows {
 public:
  // Checks the chunks (the image data's CRCs are checked as it is read); nullopt when the
  // file is not a PNG or of a kind left to libspng.
  // Throws FileError for a corrupt or truncated file of its own kind.
  static std::optional<PngRows> open(std::span<const unsigned char> png, const std::string& name);
  PngRows(PngRows&&) noexcept;
  PngRows& operator=(PngRows&&) noexcept;
  ~PngRows();

  std::uint32_t width() const { return width_; }
  std::uint32_t height() const { return height_; }
  // The buffer read() needs for `rows` rows: the filtered rows are inflated into it too,
  // kUnfilterRoomRows rows from its start (png_unfilter.hpp).
  std::size_t band_bytes(std::uint32_t rows) const {
    return std::max((std::size_t{rows} + kUnfilterRoomRows) * (row_len() + 1),
                    std::size_t{rows} * width_ * 4);
  }
  // The next `rows` rows (1..rows left) as packed RGBA8 at the start of `out`
  // (band_bytes(rows) long).
  // Reading the last row also checks that the stream ends there with a good checksum, and
  // the CRCs of any image data after that end.
  // Throws FileError for bad data, naming the file; a CRC mismatch anywhere in the image
  // data is what is reported when there is one, as if every CRC had been checked first.
  void read(unsigned char* out, std::uint32_t rows);
  // Checks the next `rows` rows as read() would, without unfiltering them.
  void skip(std::uint32_t rows);

 private:
  struct Feed;
  explicit PngRows(std::string name);
  std::size_t row_len() const { return std::size_t{width_} * std::size_t(bpp_); }
  void inflate_rows(unsigned char* raw, std::uint32_t rows);
  std::size_t inflate(unsigned char* out, std::size_t n, const char* why);
  [[noreturn]] void fail(const char* why);
  void finish();

  std::uint32_t width_ = 0, height_ = 0, row_ = 0;  // row_: rows read so far
  int bpp_ = 0;
  std::vector<unsigned char> prev_;  // the last row unfiltered (zeros before row 0)
  // The file's name and IDAT chunks, handed to the inflater a slice at a time (on the heap:
  // the inflater holds on to it, and a PngRows moves).
  std::unique_ptr<Feed> feed_;
  Inflater inflater_;
};

// The whole image, or nullopt when the file is of a kind left to libspng.
std::optional<RgbaImage> decode_png_fast(std::span<const unsigned char> png,
                                         const std::string& name);

// Everything decode_png_fast checks (chunk CRCs, the zlib stream and its checksum, the row
// filters) without unfiltering the pixels; the image's size.
std::optional<ImageSize> check_png_fast(std::span<const unsigned char> png,
                                        const std::string& name);

}  // namespace aosuite
