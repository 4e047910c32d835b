#include "compare/picture.hpp"

#include <fmt/format.h>

#include <cstring>

#include "compare/exr_file.hpp"
#include "compare/image_io.hpp"
#include "compare/png_layout.hpp"

namespace aosuite {

ImageSize Picture::size() const {
  return is_float ? ImageSize{floats.width, floats.height} : ImageSize{rgba.width(), rgba.height()};
}

std::string Picture::kind() const {
  if (!is_float) return "8-bit RGBA";
  return fmt::format("{}, {} channel{}", floats.srgb ? "16-bit PNG" : "EXR", floats.channels,
                     floats.channels == 1 ? "" : "s");
}

bool is_exr(std::span<const unsigned char> bytes) {
  static constexpr unsigned char kMagic[4] = {0x76, 0x2f, 0x31, 0x01};
  return bytes.size() >= 4 && std::memcmp(bytes.data(), kMagic, 4) == 0;
}

Picture decode_picture(std::span<const unsigned char> bytes, const std::string& name,
                       std::uint64_t max_bytes) {
  Picture p;
  p.name = name;
  if (is_exr(bytes)) {
    p.is_float = true;
    p.floats = decode_exr(bytes, name, max_bytes);
    return p;
  }
  const PngHeader h = peek_png_header(bytes, name);
  const std::uint64_t pixels = std::uint64_t(h.width) * h.height;
  const std::uint64_t need = pixels * (h.bit_depth == 16 ? 3 * sizeof(float) + 8 : 4);
  if (need > max_bytes) {
    throw FileError(
        fmt::format("{}: {}x{} pixels need {} MiB decoded, over the {} MiB memory "
                    "budget (--memory-limit MIB)",
                    name, h.width, h.height, (need + (1 << 20) - 1) >> 20, max_bytes >> 20));
  }
  if (h.bit_depth == 16) {
    p.is_float = true;
    p.floats = decode_png16(bytes, name);
  } else {
    p.rgba = decode_png(bytes, name);
  }
  return p;
}

Picture read_picture(const std::filesystem::path& path, std::uint64_t max_bytes) {
  return decode_picture(MappedFile(path, max_bytes).bytes(), path.string(), max_bytes);
}

FloatImage to_float(RgbaView rgba) {
  FloatImage f;
  f.width = rgba.width, f.height = rgba.height, f.channels = 3, f.srgb = true;
  f.data.resize(std::size_t(rgba.width) * std::size_t(rgba.height) * 3);
  float* out = f.data.data();
  for (int y = 0; y < rgba.height; ++y) {
    const unsigned char* in = rgba.row(y);
    for (int x = 0; x < rgba.width; ++x, in += 4, out += 3) {
      out[0] = float(in[0]) / 255.0f, out[1] = float(in[1]) / 255.0f,
      out[2] = float(in[2]) / 255.0f;
    }
  }
  return f;
}

}  // namespace aosuite
