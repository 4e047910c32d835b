// The decoders inside libaosuite_codecs.so (image/codecs_library.cpp is its entry point), one
// file each; the contract is aosuite_read_image's (image/image_library.hpp).
#pragma once

#include <cstddef>
#include <string>

namespace aosuite::codecs {

// What a decoder returns: 0 decoded, 1 failed (`why` says so in one line; "refused" when the
// allocator refused the size), kNotMine for a variant it leaves to OpenImageIO.
inline constexpr int kNotMine = 2;

using Allocate = void* (*)(void* user, int width, int height, int channels, int sample);

// Baseline and progressive JPEG, grey or colour (CMYK: kNotMine), libjpeg-turbo.
int read_jpeg(const unsigned char* bytes, std::size_t size, Allocate allocate, void* user,
              std::string& why);
// WebP as RGBA, libwebp.
int read_webp(const unsigned char* bytes, std::size_t size, Allocate allocate, void* user,
              std::string& why);
// TIFF's first image, strips of interleaved grey or RGB with up to 4 samples of 8 or 16 bits
// or 32-bit float, any compression libtiff has; anything else (tiles, planes, palettes,
// CMYK, YCbCr) kNotMine. libtiff.
int read_tiff(const unsigned char* bytes, std::size_t size, Allocate allocate, void* user,
              std::string& why);
// Radiance HDR (RGBE, top to bottom), decoded as Radiance's rgbe.c: m * 2^(e - 136).
int read_hdr(const unsigned char* bytes, std::size_t size, Allocate allocate, void* user,
             std::string& why);

// Targa: true colour at 24 or 32 bits or grey at 8, run-length encoded or not (colour-mapped,
// 16-bit, right-to-left: kNotMine).
int read_tga(const unsigned char* bytes, std::size_t size, Allocate allocate, void* user,
             std::string& why);
// BMP: uncompressed 24- or 32-bit (the fourth byte reserved, as Pillow reads it), either row
// order (palettes, 16 bits, bit fields, RLE: kNotMine).
int read_bmp(const unsigned char* bytes, std::size_t size, Allocate allocate, void* user,
             std::string& why);

}  // namespace aosuite::codecs
