// FLIP as a metric (compare/flip.hpp has the kernel): LDR-FLIP for 8-bit and 16-bit PNGs,
// HDR-FLIP for EXR, as NVlabs/flip's tool chooses by file type; grey images as R = G = B.

#include "compare/flip.hpp"
#include "compare/metric.hpp"
#include "compare/srgb.hpp"

namespace aosuite::metric {
namespace {

constexpr std::string_view kStats[] = {"mean", "weighted_median", "q1", "q3", "min", "max"};

// Three linear channels per pixel.
std::vector<float> linear_rgb(const FloatImage& f) {
  const std::size_t pixels = std::size_t(f.width) * std::size_t(f.height);
  std::vector<float> out(pixels * 3);
  for (std::size_t i = 0; i < pixels; ++i) {
    for (std::size_t c = 0; c < 3; ++c) {
      const float v = f.data[i * std::size_t(f.channels) + (f.channels == 3 ? c : 0)];
      out[i * 3 + c] = f.srgb ? srgb_to_linear(v) : v;
    }
  }
  return out;
}

Measurement measure_flip(const Picture& reference, const Picture& test, const Request& request) {
  flip::FlipResult f;
  RgbaImage map;
  const bool hdr = reference.is_float && !reference.floats.srgb;
  flip::Options o;
  o.tool_arithmetic = request.tool_pooling;
  if (!reference.is_float) {
    f = flip::compare_ldr(reference.rgba, test.rgba, o);
  } else {
    const std::vector<float> a = linear_rgb(reference.floats), b = linear_rgb(test.floats);
    const int w = reference.floats.width, h = reference.floats.height;
    const flip::RgbFloatView va{a.data(), w, h, std::size_t(w) * 3};
    const flip::RgbFloatView vb{b.data(), w, h, std::size_t(w) * 3};
    f = hdr ? flip::compare_hdr(va, vb, o) : flip::compare_ldr_linear(va, vb, o);
  }
  if (request.want_map) map = flip::error_map_image(f);
  if (request.counted) {
    std::size_t kept = 0;
    for (std::size_t i = 0; i < f.error_map.size(); ++i)
      if ((*request.counted)[i]) f.error_map[kept++] = f.error_map[i];
    f.error_map.resize(kept);
    flip::pool(f, request.tool_pooling);
  }
  Measurement m;
  m.metric = "flip";
  if (request.tool_pooling) m.tool_decimals = 6;  // FLIP's tool prints "%.6f"
  m.map = std::move(map);
  m.values = {{"mean", f.mean},
              {"weighted_median", f.weighted_median},
              {"q1", f.first_weighted_quartile},
              {"q3", f.third_weighted_quartile},
              {"min", f.min},
              {"max", f.max}};
  if (hdr) m.facts = {{"start_exposure", f.start_exposure}, {"stop_exposure", f.stop_exposure}};
  return m;
}

}  // namespace

extern const Metric kFlip{
    .name = "flip",
    .summary = "NVlabs FLIP v1.6 error (0 = same); LDR for PNG, HDR for EXR; map: magma",
    .stats = kStats,
    .primary = "mean",
    .measure = measure_flip,
    .raw_floats = true,  // the tool's own reading: NaN as 0, Inf as the largest float
    .heatmap = true,
};

}  // namespace aosuite::metric
