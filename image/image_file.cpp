#include "image/image_file.hpp"

#include <fmt/format.h>

#include "common/file_io.hpp"
#include "image/exr_file.hpp"
#include "image/image_io.hpp"
#include "image/other_formats.hpp"
#include "image/png_layout.hpp"

namespace aosuite {

Picture decode_picture(std::span<const unsigned char> bytes, const std::string& name,
                       std::uint64_t max_bytes) {
  if (!is_png(bytes) && !is_exr(bytes)) return decode_other_format(bytes, name, max_bytes);
  Picture p;
  p.name = name, p.format = is_exr(bytes) ? "EXR" : "PNG";
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

RgbaImage decode_rgba8(std::span<const unsigned char> bytes, const std::string& name,
                       std::uint64_t max_bytes) {
  return is_png(bytes) ? decode_png(bytes, name)
                       : canvas_rgba8(decode_picture(bytes, name, max_bytes));
}

Picture read_picture(const std::filesystem::path& path, std::uint64_t max_bytes) {
  return decode_picture(MappedFile(path, max_bytes).bytes(), path.string(), max_bytes);
}

}  // namespace aosuite
