// Images in formats other than PNG and EXR: JPEG, WebP, TIFF, Radiance HDR, Targa and BMP in
// libaosuite_codecs.so (their own libraries, or a few lines), rare variants through OpenImageIO
// in libaosuite_oiio.so; each library is opened only when such a file is read.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "image/picture.hpp"

namespace aosuite {

// 8-bit files as RGBA (grey as R = G = B, alpha 255 where they have none); 16-bit ones as
// float v / 65535, sRGB-encoded, R, G, B or grey alone (as 16-bit PNGs); float ones as linear
// float (as EXR). Throws FileError naming the file, the format OpenImageIO saw or that it is
// none aosuite reads, and the reason.
Picture decode_other_format(std::span<const unsigned char> bytes, const std::string& name,
                            std::uint64_t max_bytes);

}  // namespace aosuite
