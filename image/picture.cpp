#include "image/picture.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>

#include "image/image_io.hpp"
#include "image/png_layout.hpp"

namespace aosuite {

ImageSize Picture::size() const {
  return is_float ? ImageSize{floats.width, floats.height} : ImageSize{rgba.width(), rgba.height()};
}

std::string Picture::kind() const {
  if (!is_float) return "8-bit " + format;  // decoded to RGBA, whatever channels the file had
  return fmt::format("{}{}, {} channel{}", floats.srgb ? "16-bit " : "", format, floats.channels,
                     floats.channels == 1 ? "" : "s");
}

bool same_kind(const Picture& a, const Picture& b) {
  if (a.is_float != b.is_float) return false;
  const int ca = a.floats.channels, cb = b.floats.channels;
  return !a.is_float || (a.floats.srgb == b.floats.srgb && (ca == cb || ca * cb == 3));
}

void widen_grey(FloatImage& f) {
  if (f.channels != 1) return;
  std::vector<float> rgb(f.data.size() * 3);
  for (std::size_t i = 0; i < f.data.size(); ++i)
    rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = f.data[i];
  f.data = std::move(rgb);
  f.channels = 3;
}

bool is_image_name(const std::filesystem::path& name) {
  static constexpr std::string_view kExtensions[] = {
      ".png", ".exr", ".jpg", ".jpeg", ".tif", ".tiff", ".webp", ".hdr", ".tga", ".bmp", ".gif"};
  std::string ext = name.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return std::ranges::find(kExtensions, ext) != std::end(kExtensions);
}

RgbaImage canvas_rgba8(const Picture& p) {
  if (!p.is_float) return p.rgba;
  if (!p.floats.srgb) {
    throw FileError(fmt::format(
        "{}: a float {} image; Resemble.js compares 8-bit images, as a browser canvas holds "
        "them (for float images: --metric flip, ssim, rmse or psnr)",
        p.name, p.format));
  }
  const FloatImage& f = p.floats;
  RgbaImage out(f.width, f.height);
  const std::size_t pixels = std::size_t(f.width) * std::size_t(f.height);
  for (std::size_t i = 0; i < pixels; ++i) {
    unsigned char* o = out.data() + 4 * i;
    for (std::size_t c = 0; c < 3; ++c) {
      // The high byte of the 16-bit sample, as aosuite's PNG path keeps a 16-bit PNG's
      // (pillow_formats checks the two agree).
      const float v = f.data[i * std::size_t(f.channels) + (f.channels == 3 ? c : 0)];
      o[c] = static_cast<unsigned char>(std::lround(std::clamp(v, 0.0f, 1.0f) * 65535.0f) >> 8);
    }
    o[3] = 255;
  }
  return out;
}

bool is_png(std::span<const unsigned char> bytes) {
  static constexpr unsigned char kMagic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  return bytes.size() >= 8 && std::memcmp(bytes.data(), kMagic, 8) == 0;
}

bool is_exr(std::span<const unsigned char> bytes) {
  static constexpr unsigned char kMagic[4] = {0x76, 0x2f, 0x31, 0x01};
  return bytes.size() >= 4 && std::memcmp(bytes.data(), kMagic, 4) == 0;
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
