// The one PNG validity rule both decoders follow (the fast decoder, png_fast.hpp, and
// libspng for every other kind, image_io.cpp): a file is accepted by one exactly when it is
// by the other, and truncated is an error for every pixel format.
//
// The rule:
//  - the signature, then IHDR (13 bytes: a legal bit depth for its colour type, compression
//    and filter method 0, interlace 0 or 1, width and height within the pixel limit);
//  - every chunk whole inside the file, up to an IEND chunk of length 0 (bytes after IEND are
//    not read);
//  - critical chunks with good CRCs, and only IHDR (once, first), PLTE (at most once, before
//    the image data), IDAT (one run of consecutive chunks) and IEND;
//  - ancillary chunks are not used (no colour management), so neither their CRCs nor their
//    contents are checked, except tRNS before the image data, which libspng reads and checks;
//  - the IDAT data is one zlib stream (method 8, window <= 32 KB, no preset dictionary) that
//    inflates to exactly the filtered rows (every interlace pass), each with filter 0..4,
//    and then ends with a good Adler-32 (compressed bytes after that end are ignored).
//
// Everything but the zlib stream is checked by walk_png, one pass over the chunk headers
// that also verifies the critical chunks' CRCs, which a decoder had to do anyway. The fast
// decoder checks the IDAT chunks' CRCs itself, as it hands their data to inflate.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace aosuite {

// A PNG's big-endian 32-bit field (chunk lengths, CRCs, IHDR's sizes).
inline std::uint32_t be32(const unsigned char* p) {
  return std::uint32_t{p[0]} << 24 | std::uint32_t{p[1]} << 16 | std::uint32_t{p[2]} << 8 | p[3];
}

struct PngLayout {
  std::uint32_t width = 0, height = 0;
  int bit_depth = 0, colour_type = 0, interlace = 0;
  // Each IDAT chunk's data, in order, and their total length.
  std::vector<std::span<const unsigned char>> idat;
  std::size_t idat_bytes = 0;
  // What libspng needs, whole chunks with their headers and CRCs, in file order: the
  // signature with IHDR, PLTE and tRNS before the image data, the IDAT run, IEND.
  std::vector<std::span<const unsigned char>> for_decoder;
  bool has_plte = false, has_trns = false;

  // Bits per pixel, and the zlib stream's length inflated (filter bytes included).
  int bits_per_pixel() const;
  std::uint64_t filtered_bytes() const;
};

// IHDR's width and height without any other check (the file may still be refused):
// for the memory budget, before anything is decoded. Throws FileError when the file is not a
// PNG or too short to hold IHDR.
struct PngHeader {
  std::uint32_t width = 0, height = 0;
  int bit_depth = 0, colour_type = 0, interlace = 0;
};
PngHeader peek_png_header(std::span<const unsigned char> png, const std::string& name);

// Checks everything in the rule but the zlib stream's contents; throws FileError, naming
// the file, otherwise. Also refuses a file whose image data is too short to possibly fill
// the image (deflate expands at most 1032:1), so that a small file claiming a huge image
// fails before anything is allocated for it. With check_idat_crcs false the IDAT chunks'
// CRCs are left to the caller.
PngLayout walk_png(std::span<const unsigned char> png, const std::string& name,
                   bool check_idat_crcs = true);

// Inflates the whole IDAT stream without keeping it, and checks that it has exactly
// layout.filtered_bytes() bytes and ends with a good checksum (the decoder that fills the
// rows, libspng, stops reading at the last row).
void check_png_stream(const PngLayout& layout, const std::string& name);

}  // namespace aosuite
