// EXR images through libaosuite_exr.so (image/exr_library.cpp), which lies beside the
// `aosuite` executable and is opened on the first EXR read or written: a process that touches
// none never loads OpenImageIO.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include "image/rgba_image.hpp"

namespace aosuite {

// The EXR's R, G, B channels (or Y alone) as linear floats. Throws FileError naming the file
// and the problem: not an EXR, no R, G, B or Y channel, pixels over kMaxImagePixels or over
// `max_bytes` decoded.
FloatImage decode_exr(std::span<const unsigned char> bytes, const std::string& name,
                      std::uint64_t max_bytes = UINT64_MAX);

// Writes a float image of 1 (Y) or 3 (R, G, B) interleaved channels as EXR via a temporary
// file and rename(2).
void write_exr(const std::filesystem::path& path, int width, int height, const float* pixels,
               int channels = 1);

}  // namespace aosuite
