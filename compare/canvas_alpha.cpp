#include "compare/canvas_alpha.hpp"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace aosuite {
namespace {

// Skia's exact integer form of round(v * a / 255).
int premultiply(int v, int a) {
  const int t = v * a + 128;
  return (t + (t >> 8)) >> 8;
}

unsigned char chromium_round_trip(int v, int a) {
  const int p = premultiply(v, a);
  const float r = static_cast<float>(p) * (1.0f / 255.0f);
  const float s = 1.0f / (static_cast<float>(a) * (1.0f / 255.0f));
  const float x = (r * s) * 255.0f;
  // Round half to even, as the float-to-int conversion in Skia does.
  return static_cast<unsigned char>(std::min(255.0f, std::nearbyint(x)));
}

unsigned char node_decode_round_trip(int v, int a) {
  const int p = premultiply(v, a);
  const float x = static_cast<float>(p) * static_cast<float>(255.0 / a);
  return static_cast<unsigned char>(std::min(255.0f, std::trunc(x)));
}

unsigned char node_put_get(int v, int a) {
  const float p = std::trunc(static_cast<float>(v) * static_cast<float>(a / 255.0));
  const float x = p * static_cast<float>(255.0 / a);
  return static_cast<unsigned char>(std::min(255.0f, std::trunc(x)));
}

using Table = std::array<unsigned char, 256 * 256>;  // [alpha][value]

template <unsigned char (*F)(int, int)>
const Table& table() {
  static const Table t = [] {
    Table out{};
    for (int a = 0; a < 256; ++a) {
      for (int v = 0; v < 256; ++v) {
        out[static_cast<std::size_t>(a * 256 + v)] = a == 0     ? 0
                                                     : a == 255 ? static_cast<unsigned char>(v)
                                                                : F(v, a);
      }
    }
    return out;
  }();
  return t;
}

void apply_table(RgbaImage& rgba, const Table& t) {
  unsigned char* px = rgba.data();
  for (std::size_t i = 0, n = rgba.view().bytes(); i < n; i += 4) {
    const std::size_t row = std::size_t{px[i + 3]} * 256;
    for (std::size_t c = 0; c < 3; ++c) px[i + c] = t[row + px[i + c]];
  }
}

}  // namespace

CanvasAlpha parse_canvas_alpha(std::string_view name) {
  if (name == "none") return CanvasAlpha::kNone;
  if (name == "chromium" || name == "browser") return CanvasAlpha::kChromium;
  if (name == "node-canvas" || name == "node") return CanvasAlpha::kNodeCanvas;
  throw std::invalid_argument("unknown canvas alpha model '" + std::string(name) +
                              "' (expected none, chromium or node-canvas)");
}

void apply_canvas_decode(RgbaImage& rgba, CanvasAlpha model) {
  if (model == CanvasAlpha::kChromium) apply_table(rgba, table<chromium_round_trip>());
  if (model == CanvasAlpha::kNodeCanvas) apply_table(rgba, table<node_decode_round_trip>());
}

void apply_canvas_put_get(RgbaImage& rgba, CanvasAlpha model) {
  if (model == CanvasAlpha::kNodeCanvas) apply_table(rgba, table<node_put_get>());
}

}  // namespace aosuite
