// An image as the metrics take it, whatever file it came from: 8-bit sRGB RGBA (8-bit PNGs,
// as Resemble.js and FLIP's LDR mode see them) or float samples (EXR, and 16-bit PNGs kept at
// 16 bits). Float images hold one channel (grey, Y) or three (R, G, B), interleaved.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "compare/rgba_image.hpp"

namespace aosuite {

struct Picture {
  std::string name;  // the file, for messages
  bool is_float = false;
  RgbaImage rgba;     // !is_float
  FloatImage floats;  // is_float
  ImageSize size() const;
  // What the image is, for messages: "8-bit RGBA", "16-bit PNG, 3 channels", "EXR, 1 channel".
  std::string kind() const;
};

// Whether these bytes start an OpenEXR file.
bool is_exr(std::span<const unsigned char> bytes);

// The file as a Picture: PNG of any kind (16-bit ones as float), or EXR (through
// libaosuite_exr.so, opened on the first EXR). Throws FileError naming the file and the
// problem. `max_bytes` bounds the file and the decoded pixels alike.
Picture read_picture(const std::filesystem::path& path, std::uint64_t max_bytes = UINT64_MAX);
Picture decode_picture(std::span<const unsigned char> bytes, const std::string& name,
                       std::uint64_t max_bytes = UINT64_MAX);

// A float image of an RGBA8 one: R, G, B as v / 255, still sRGB-encoded.
FloatImage to_float(RgbaView rgba);

}  // namespace aosuite
