#include "harness/judge.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include "common/content_hash.hpp"
#include "compare/verdict.hpp"
#include "image/image_file.hpp"
#include "image/image_io.hpp"
#include "image/png_layout.hpp"

namespace aosuite::harness {

namespace fs = std::filesystem;

std::string_view status_name(Status s) {
  switch (s) {
    case Status::kPass:
      return "PASS";
    case Status::kFail:
      return "FAIL";
    case Status::kNew:
      return "NEW";
    case Status::kError:
      return "ERROR";
    case Status::kFlaky:
      return "FLAKY";
  }
  return "ERROR";
}

int severity(Status s) {
  switch (s) {
    case Status::kError:
      return 4;
    case Status::kFail:
      return 3;
    case Status::kNew:
      return 2;
    case Status::kFlaky:
      return 1;
    case Status::kPass:
      return 0;
  }
  return 4;
}

Status worst(Status a, Status b) { return severity(a) >= severity(b) ? a : b; }

Status parse_status(std::string_view name) {
  for (Status s : {Status::kPass, Status::kFail, Status::kNew, Status::kError, Status::kFlaky}) {
    if (status_name(s) == name) return s;
  }
  throw std::invalid_argument("unknown status '" + std::string(name) + "'");
}

std::string golden_hash(std::span<const unsigned char> bytes) {
  return ContentHash().add(bytes).hex();
}

namespace {

// Pixel i (row-major) of `from` copied into `to`, both packed RGBA8 of one size.
void copy_pixel(const RgbaImage& from, RgbaImage& to, std::size_t i) {
  std::copy_n(from.data() + 4 * i, 4, to.data() + 4 * i);
}

// The render with ignored regions taken from the golden, so neither Resemble nor the channel
// delta sees a difference there.
RgbaImage without_ignored(const RgbaImage& render, const RgbaImage& golden, const Tolerance& t,
                          const Counted* counted) {
  if (t.ignore.empty() && t.mask.empty() && !counted) return render;
  RgbaImage out = copy_of(render);
  const std::size_t w = std::size_t(render.width()), pixels = w * std::size_t(render.height());
  if (counted) {  // background: the golden's pixels, so nothing differs there
    for (std::size_t i = 0; i < pixels; ++i)
      if (!(*counted)[i]) copy_pixel(golden, out, i);
  }
  for (const resemble::Box& b : t.ignore) {
    // Inclusive corners, clipped to the frame.
    const auto clip = [](int v, int size) { return std::clamp(v, 0, size); };
    const int x0 = clip(static_cast<int>(b.left), render.width());
    const int x1 = clip(static_cast<int>(b.right) + 1, render.width());
    const int y0 = clip(static_cast<int>(b.top), render.height());
    const int y1 = clip(static_cast<int>(b.bottom) + 1, render.height());
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) copy_pixel(golden, out, std::size_t(y) * w + std::size_t(x));
  }
  if (!t.mask.empty()) {
    const RgbaImage mask = read_png(t.mask);
    if (mask.width() != render.width() || mask.height() != render.height()) {
      throw std::runtime_error(fmt::format("mask {} is {}x{}, the images are {}x{}",
                                           t.mask.string(), mask.width(), mask.height(),
                                           render.width(), render.height()));
    }
    for (std::size_t i = 0; i < pixels; ++i) {
      const unsigned char* m = mask.data() + 4 * i;
      if (m[0] != 0 || m[1] != 0 || m[2] != 0) copy_pixel(golden, out, i);
    }
  }
  return out;
}

// The largest |a - b| of any R, G, B or A sample, and the pixels where any differs.
void channel_differences(const RgbaImage& a, const RgbaImage& b, ImageVerdict& v) {
  const std::size_t n = a.view().bytes();
  int hi = 0;
  long long pixels = 0;
  for (std::size_t i = 0; i < n; i += 4) {
    int pixel = 0;
    for (std::size_t c = i; c < i + 4; ++c)
      pixel = std::max(pixel, std::abs(int(a.data()[c]) - int(b.data()[c])));
    hi = std::max(hi, pixel), pixels += pixel > 0;
  }
  v.max_channel_delta = hi, v.differing_pixels = pixels;
}

verdict::ResembleAllowance allowance(const Tolerance& t) {
  return {.max_mismatch_percent = t.max_mismatch_percent,
          .max_channel_delta = t.max_channel_delta,
          .min_channel_delta = t.min_channel_delta,
          .min_differing_pixels = t.min_differing_pixels,
          .max_differing_pixels = t.max_differing_pixels};
}

verdict::ResembleFigures figures(const ImageVerdict& v) {
  return {.mismatch_percent = v.mismatch_percent,
          .mismatch_text = v.mismatch_text,
          .max_channel_delta = v.max_channel_delta,
          .differing_pixels = v.differing_pixels};
}

resemble::Options resemble_options(const Tolerance& t, bool diff) {
  resemble::Options o;
  o.modes = {t.mode};
  o.produce_diff = diff;
  return o;
}

// The metric gates of one golden against the render: every measurement and outcome.
// One set of gates over the counted pixels (all: null); `region` names them in the outcomes.
// Only the whole image's (or the unpainted pixels') measurements are kept as the image's
// values; a region's show in its outcomes.
void measure_set(const std::vector<metric::Gates>& gates, const std::string& region,
                 const Picture& golden, const Picture& render, bool want_map,
                 const Counted* counted, ImageVerdict& v) {
  for (const metric::Gates& g : gates) {
    const bool map = want_map && v.heatmap.empty() && g.metric->heatmap;
    metric::Measurement m =
        metric::measure(*g.metric, golden, render, {.want_map = map, .counted = counted});
    for (metric::Outcome& o : metric::judge(g, m)) {
      o.region = region;
      v.outcomes.push_back(std::move(o));
    }
    if (map) v.heatmap = std::move(m.map);
    m.map = {};
    if (region.empty()) v.measured.push_back(std::move(m));
  }
}

// Each pixel's class in the region map beside the golden: 0 unpainted, i + 1 for regions[i].
// Throws std::runtime_error naming the map when it is missing, of another size, or holds a
// colour no region has.
std::vector<std::uint8_t> region_classes(const fs::path& file, const Tolerance& t, ImageSize size) {
  if (!fs::is_regular_file(file)) {
    throw std::runtime_error(fmt::format(
        "{}: no region map (the tolerance has regions; `bless` writes an empty one to paint)",
        file.string()));
  }
  const RgbaImage map = read_png(file);
  if (map.width() != size.width || map.height() != size.height) {
    throw std::runtime_error(fmt::format("{}: the region map is {}x{}, the image {}x{}",
                                         file.string(), map.width(), map.height(), size.width,
                                         size.height));
  }
  std::vector<std::uint8_t> out(std::size_t(map.width()) * std::size_t(map.height()), 0);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const unsigned char* p = map.data() + 4 * i;
    if (p[0] == 0 && p[1] == 0 && p[2] == 0) continue;
    for (std::size_t k = 0; k < t.regions.size() && !out[i]; ++k) {
      const auto& c = t.regions[k].color;
      if (p[0] == c[0] && p[1] == c[1] && p[2] == c[2]) out[i] = std::uint8_t(k + 1);
    }
    if (!out[i]) {
      throw std::runtime_error(fmt::format("{}: pixel ({}, {}) is ({}, {}, {}), no region's colour",
                                           file.string(), i % std::size_t(map.width()),
                                           i / std::size_t(map.width()), p[0], p[1], p[2]));
    }
  }
  return out;
}

// The tolerance's metric gates, over the counted pixels; with regions, each region's gates
// over its painted pixels and the tolerance's over the unpainted ones.
void measure_gates(const Picture& golden, const Picture& render, const Tolerance& t,
                   const fs::path& golden_file, std::string_view image, bool want_map,
                   const Counted* counted, ImageVerdict& v) {
  if (t.regions.empty()) {
    measure_set(t.gates, "", golden, render, want_map, counted, v);
    return;
  }
  const std::vector<std::uint8_t> classes =
      region_classes(region_map(golden_file, image), t, golden.size());
  for (std::size_t k = 0; k <= t.regions.size(); ++k) {
    Counted mask(classes.size());
    for (std::size_t i = 0; i < mask.size(); ++i)
      mask[i] = classes[i] == k && (!counted || (*counted)[i]);
    measure_set(k == 0 ? t.gates : t.regions[k - 1].gates, k == 0 ? "" : t.regions[k - 1].name,
                golden, render, want_map, &mask, v);
  }
}

// Resemble's figures on an 8-bit image, into `v`. With `counted`, the mismatch is a percentage
// of the counted pixels, not of the frame.
void resemble_figures(const RgbaImage& golden, const RgbaImage& render, const Tolerance& t,
                      const Counted* counted, ImageVerdict& v) {
  const RgbaImage judged = without_ignored(render, golden, t, counted);
  const resemble::Result r = resemble::compare(golden, judged, resemble_options(t, false));
  v.mismatch_percent = r.raw_mismatch_percentage;
  v.mismatch_text = r.mismatch_percentage;
  if (counted) {
    const auto n = std::ranges::count_if(*counted, [](std::uint8_t f) { return f != 0; });
    v.mismatch_percent = n ? 100.0 * double(r.mismatch_count) / double(n) : 0.0;
    v.mismatch_text = fmt::format("{:.2f}", v.mismatch_percent);
  }
  channel_differences(golden, judged, v);
}

// The metrics' view of a PNG: its own pixels, a 16-bit one at 16 bits; an 8-bit one already
// decoded for Resemble is copied, not decoded again.
Picture metric_picture(std::span<const unsigned char> file, const RgbaImage& decoded,
                       const std::string& name) {
  if (!is_png(file) || peek_png_header(file, name).bit_depth == 16) {
    return decode_picture(file, name, kMaxFileBytes);  // 16-bit samples at full precision
  }
  Picture p;
  p.name = name, p.rgba = decoded;
  return p;
}

// One golden against the render; kError when the golden cannot be read.
ImageVerdict against(std::string_view image, std::span<const unsigned char> render_bytes,
                     const RgbaImage& render, const fs::path& golden_file, const Tolerance& t,
                     bool want_map, const Counted* counted) {
  ImageVerdict v;
  v.image = std::string(image), v.golden = golden_file;
  try {
    const std::vector<unsigned char> bytes = read_file(golden_file, kMaxFileBytes);
    v.golden_hash = golden_hash(bytes);
    if (std::equal(bytes.begin(), bytes.end(), render_bytes.begin(), render_bytes.end())) {
      // Nothing to measure, but a two-sided budget's minimum still judges "no difference".
      v.identical = true, v.mismatch_text = "0.00", v.comparable = true;
      const verdict::ResembleFigures none = figures(v);
      const verdict::Verdict d = verdict::decide(t.resemble ? &none : nullptr, allowance(t), {});
      v.status = d.pass ? Status::kPass : Status::kFail, v.message = d.message();
      return v;
    }
    const bool is_float = render.empty();
    if (is_float && t.gates.empty()) {
      v.status = Status::kFail, v.mismatch_percent = 100, v.mismatch_text = "100.00";
      v.message =
          "the EXR files differ (without a metric gate, EXR images are compared byte for byte)";
      return v;
    }
    if (!is_float) {
      const RgbaImage golden = decode_rgba8(bytes, golden_file.string(), kMaxFileBytes);
      if (golden.width() != render.width() || golden.height() != render.height()) {
        v.status = Status::kFail, v.mismatch_percent = 100, v.mismatch_text = "100.00";
        v.message = fmt::format("golden is {}x{}, render is {}x{}", golden.width(), golden.height(),
                                render.width(), render.height());
        return v;
      }
      resemble_figures(golden, render, t, counted, v);
      if (!t.gates.empty()) {
        try {
          measure_gates(metric_picture(bytes, golden, golden_file.string()),
                        metric_picture(render_bytes, render, "the render"), t, golden_file, image,
                        want_map, counted, v);
        } catch (const std::invalid_argument& e) {  // a golden of another kind (16 vs 8 bits)
          v.status = Status::kFail, v.message = e.what();
          return v;
        }
      }
    } else {
      const Picture golden = decode_picture(bytes, golden_file.string(), kMaxFileBytes);
      const Picture rendered = decode_picture(render_bytes, "the render", kMaxFileBytes);
      const ImageSize gs = golden.size(), rs = rendered.size();
      if (gs.width != rs.width || gs.height != rs.height || !same_kind(golden, rendered)) {
        v.status = Status::kFail, v.mismatch_percent = 100, v.mismatch_text = "100.00";
        v.message = fmt::format("golden is {}x{} {}, render is {}x{} {}", gs.width, gs.height,
                                golden.kind(), rs.width, rs.height, rendered.kind());
        return v;
      }
      measure_gates(golden, rendered, t, golden_file, image, want_map, counted, v);
    }
    const verdict::ResembleFigures found = figures(v);
    const verdict::Verdict d =
        verdict::decide(!is_float && t.resemble ? &found : nullptr, allowance(t), v.outcomes);
    v.message = d.message();
    v.status = d.pass ? Status::kPass : Status::kFail;
    v.comparable = true;
    if (d.pass) {
      v.stale = verdict::stale_budgets(!is_float && t.resemble ? &found : nullptr, allowance(t),
                                       v.outcomes);
    }
  } catch (const std::exception& e) {
    v.status = Status::kError;
    v.message = e.what();
  }
  return v;
}

// How far from passing: gates failed first, then Resemble's mismatch.
bool closer(const ImageVerdict& a, const ImageVerdict& b) {
  const auto failed = [](const ImageVerdict& v) {
    return std::ranges::count_if(v.outcomes, [](const metric::Outcome& o) { return !o.pass; });
  };
  if (failed(a) != failed(b)) return failed(a) < failed(b);
  return a.mismatch_percent < b.mismatch_percent;
}

}  // namespace

ImageVerdict judge(std::string_view image, std::span<const unsigned char> render_bytes,
                   const RgbaImage& render, const std::vector<fs::path>& goldens,
                   const Tolerance& tolerance, bool want_diff, const Counted* counted) {
  if (goldens.empty()) {
    ImageVerdict v;
    v.image = std::string(image), v.status = Status::kNew, v.message = "no golden yet";
    return v;
  }
  // Every accepted golden is read, even after one passes: a damaged golden or variant is an
  // error to repair, not something another variant may hide.
  std::vector<ImageVerdict> tried;
  for (const fs::path& g : goldens)
    tried.push_back(against(image, render_bytes, render, g, tolerance, want_diff, counted));
  for (const ImageVerdict& v : tried) {
    if (v.status == Status::kError) return v;
  }
  for (ImageVerdict& v : tried) {
    if (v.status == Status::kPass) {
      v.heatmap = {};  // maps are for failures
      return v;
    }
  }
  // None passed: report the closest golden.
  ImageVerdict best = *std::min_element(tried.begin(), tried.end(), closer);
  if (want_diff && best.status == Status::kFail && best.mismatch_percent < 100 && !render.empty()) {
    const std::vector<unsigned char> bytes = read_file(best.golden, kMaxFileBytes);
    const RgbaImage golden = decode_rgba8(bytes, best.golden.string(), kMaxFileBytes);
    best.diff = resemble::compare(golden, without_ignored(render, golden, tolerance, counted),
                                  resemble_options(tolerance, true))
                    .diff;
  }
  return best;
}

}  // namespace aosuite::harness
