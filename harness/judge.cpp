#include "harness/judge.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>
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
    case Status::kWarn:
      return "WARN";
  }
  return "ERROR";
}

int severity(Status s) {
  switch (s) {
    case Status::kError:
      return 5;
    case Status::kFail:
      return 4;
    case Status::kNew:
      return 3;
    case Status::kFlaky:
      return 2;
    case Status::kWarn:
      return 1;
    case Status::kPass:
      return 0;
  }
  return 5;
}

Status worst(Status a, Status b) { return severity(a) >= severity(b) ? a : b; }

bool awaits_approval(Status s) {
  return s == Status::kFail || s == Status::kNew || s == Status::kWarn;
}

Status parse_status(std::string_view name) {
  for (Status s : {Status::kPass, Status::kFail, Status::kNew, Status::kError, Status::kFlaky,
                   Status::kWarn}) {
    if (status_name(s) == name) return s;
  }
  throw std::invalid_argument("unknown status '" + std::string(name) + "'");
}

std::string LargestDifference::text() const {
  return x < 0 ? std::string() : fmt::format("{:.4g} @ ({}, {})", value, x, y);
}

std::vector<std::uint8_t> ignored_pixels(const Tolerance& t, int width, int height) {
  if (t.ignore.empty() && t.mask.empty()) return {};
  const std::size_t w = std::size_t(width);
  std::vector<std::uint8_t> out(w * std::size_t(height), 0);
  for (const resemble::Box& b : t.ignore) {
    const auto clip = [](int v, int size) { return std::clamp(v, 0, size); };
    const int x0 = clip(static_cast<int>(b.left), width);
    const int x1 = clip(static_cast<int>(b.right) + 1, width);
    const int y0 = clip(static_cast<int>(b.top), height);
    const int y1 = clip(static_cast<int>(b.bottom) + 1, height);
    for (int y = y0; y < y1; ++y)
      std::fill_n(out.begin() + std::ptrdiff_t(std::size_t(y) * w + std::size_t(x0)), x1 - x0, 1);
  }
  if (!t.mask.empty()) {
    const RgbaImage mask = read_png(t.mask);
    if (mask.width() != width || mask.height() != height) {
      throw std::runtime_error(fmt::format("mask {} is {}x{}, the images are {}x{}",
                                           t.mask.string(), mask.width(), mask.height(), width,
                                           height));
    }
    for (std::size_t i = 0; i < out.size(); ++i) {
      const unsigned char* m = mask.data() + 4 * i;
      out[i] |= m[0] != 0 || m[1] != 0 || m[2] != 0;
    }
  }
  return out;
}

std::string golden_hash(std::span<const unsigned char> bytes) {
  return ContentHash().add(bytes).hex();
}

namespace {

// Pixel i (row-major) of `from` copied into `to`, both packed RGBA8 of one size.
void copy_pixel(const RgbaImage& from, RgbaImage& to, std::size_t i) {
  std::copy_n(from.data() + 4 * i, 4, to.data() + 4 * i);
}

// The tolerance's ignored pixels at the render's size, read on first need (an identical image
// needs none) and then shared by every golden, the diff and the report's overlay: a mask file
// is read once per image.
class Ignored {
 public:
  Ignored(const Tolerance& t, const RgbaImage& render) : t_(t), render_(render) {}
  const std::vector<std::uint8_t>& get() {  // throws as ignored_pixels does
    if (!pixels_) pixels_ = ignored_pixels(t_, render_.width(), render_.height());
    return *pixels_;
  }

 private:
  const Tolerance& t_;
  const RgbaImage& render_;
  std::optional<std::vector<std::uint8_t>> pixels_;
};

// The render with ignored pixels taken from the golden, so neither Resemble nor the channel
// delta sees a difference there.
RgbaImage without_ignored(const RgbaImage& render, const RgbaImage& golden, Ignored& ignored_px,
                          const Counted* counted) {
  const std::vector<std::uint8_t>& ignored = ignored_px.get();
  if (ignored.empty() && !counted) return render;
  RgbaImage out = copy_of(render);
  for (std::size_t i = 0; i < ignored.size(); ++i)
    if (ignored[i]) copy_pixel(golden, out, i);
  if (counted) {  // background: the golden's pixels, so nothing differs there
    for (std::size_t i = 0; i < counted->size(); ++i)
      if (!(*counted)[i]) copy_pixel(golden, out, i);
  }
  return out;
}

// The largest |a - b| of any R, G, B or A sample and where it is, and the pixels where any
// differs.
void channel_differences(const RgbaImage& a, const RgbaImage& b, ImageVerdict& v) {
  const std::size_t n = a.view().bytes();
  int hi = 0;
  std::size_t at = 0;
  long long pixels = 0;
  for (std::size_t i = 0; i < n; i += 4) {
    int pixel = 0;
    for (std::size_t c = i; c < i + 4; ++c)
      pixel = std::max(pixel, std::abs(int(a.data()[c]) - int(b.data()[c])));
    if (pixel > hi) hi = pixel, at = i / 4;
    pixels += pixel > 0;
  }
  v.max_channel_delta = hi, v.differing_pixels = pixels;
  const std::size_t w = std::size_t(a.width());
  if (hi > 0) v.largest = {double(hi), int(at % w), int(at / w)};
}

// The largest finite |a - b| of any sample of two float images of one size (a grey one against
// each of the other's channels) and where it is, over the counted pixels.
LargestDifference float_difference(const FloatImage& a, const FloatImage& b,
                                   const Counted* counted) {
  LargestDifference out;
  const std::size_t pixels = std::size_t(a.width) * std::size_t(a.height);
  const std::size_t ca = std::size_t(a.channels), cb = std::size_t(b.channels);
  const std::size_t channels = std::max(ca, cb);
  for (std::size_t i = 0; i < pixels; ++i) {
    if (counted && !(*counted)[i]) continue;
    for (std::size_t c = 0; c < channels; ++c) {
      const double d = std::abs(double(a.data[i * ca + std::min(c, ca - 1)]) -
                                double(b.data[i * cb + std::min(c, cb - 1)]));
      if (std::isfinite(d) && d > out.value) {
        out = {d, int(i % std::size_t(a.width)), int(i / std::size_t(a.width))};
      }
    }
  }
  return out;
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

// The tolerance's metric gates and, with no limit, each metric only its warning tier gates:
// measured once, judged by each tier.
std::vector<metric::Gates> measured_gates(const Tolerance& t) {
  std::vector<metric::Gates> out = t.gates;
  for (const metric::Gates& g : t.warn.gates) metric::gates_for(out, *g.metric);
  return out;
}

// The warning tier on a passing image: the one verdict rule under the tier's limits, over the
// figures and whole-image measurements the failing tier's judgement already made.
verdict::Verdict warned(const ImageVerdict& v, const WarnLimits& w, bool resemble) {
  std::vector<metric::Outcome> outcomes;
  for (const metric::Gates& g : w.gates) {
    for (const metric::Measurement& m : v.measured) {
      if (m.metric != g.metric->name) continue;
      for (metric::Outcome& o : metric::judge(g, m)) outcomes.push_back(std::move(o));
    }
  }
  const verdict::ResembleFigures found = figures(v);
  return verdict::decide(resemble && w.resemble() ? &found : nullptr,
                         {.max_mismatch_percent = w.max_mismatch_percent,
                          .max_channel_delta = w.max_channel_delta,
                          .max_differing_pixels = w.max_differing_pixels},
                         outcomes);
}

// The tolerance's metric gates, over the counted pixels; with regions, each region's gates
// over its painted pixels and the tolerance's over the unpainted ones.
void measure_gates(const Picture& golden, const Picture& render, const Tolerance& t,
                   const fs::path& golden_file, std::string_view image, bool want_map,
                   const Counted* counted, ImageVerdict& v) {
  const std::vector<metric::Gates> whole = measured_gates(t);
  if (t.regions.empty()) {
    measure_set(whole, "", golden, render, want_map, counted, v);
    return;
  }
  const std::vector<std::uint8_t> classes =
      region_classes(region_map(golden_file, image), t, golden.size());
  for (std::size_t k = 0; k <= t.regions.size(); ++k) {
    Counted mask(classes.size());
    for (std::size_t i = 0; i < mask.size(); ++i)
      mask[i] = classes[i] == k && (!counted || (*counted)[i]);
    measure_set(k == 0 ? whole : t.regions[k - 1].gates, k == 0 ? "" : t.regions[k - 1].name,
                golden, render, want_map, &mask, v);
  }
}

// Resemble's figures on an 8-bit image, into `v`. With `counted`, the mismatch is a percentage
// of the counted pixels, not of the frame.
void resemble_figures(const RgbaImage& golden, const RgbaImage& render, const Tolerance& t,
                      Ignored& ignored, const Counted* counted, ImageVerdict& v) {
  const RgbaImage judged = without_ignored(render, golden, ignored, counted);
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
                     Ignored& ignored, bool want_map, const Counted* counted) {
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
      resemble_figures(golden, render, t, ignored, counted, v);
      if (!t.gates.empty() || !t.warn.gates.empty()) {
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
      v.largest = float_difference(golden.floats, rendered.floats, counted);
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
      const verdict::Verdict w = warned(v, t.warn, !is_float);
      if (!w.pass) v.status = Status::kWarn, v.message = "warning: " + w.message();
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

// Resemble's diff image of a failing or warning 8-bit image of the golden's size, when asked.
// A golden or mask that cannot be read here (an identical image's two-sided budget reads neither
// before) makes the verdict kError, naming it.
void add_diff(ImageVerdict& v, const RgbaImage& render, const Tolerance& t, Ignored& ignored,
              bool want_diff, const Counted* counted) {
  if (!want_diff || v.mismatch_percent >= 100 || render.empty()) return;
  if (v.status != Status::kFail && v.status != Status::kWarn) return;
  try {
    const std::vector<unsigned char> bytes = read_file(v.golden, kMaxFileBytes);
    const RgbaImage golden = decode_rgba8(bytes, v.golden.string(), kMaxFileBytes);
    v.diff = resemble::compare(golden, without_ignored(render, golden, ignored, counted),
                               resemble_options(t, true))
                 .diff;
    v.ignored = ignored.get();
  } catch (const std::exception& e) {
    v.status = Status::kError, v.message = e.what(), v.diff = {};
  }
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
  Ignored ignored(tolerance, render);
  for (const fs::path& g : goldens)
    tried.push_back(
        against(image, render_bytes, render, g, tolerance, ignored, want_diff, counted));
  for (const ImageVerdict& v : tried) {
    if (v.status == Status::kError) return v;
  }
  for (ImageVerdict& v : tried) {
    if (v.status == Status::kPass) {
      v.heatmap = {};  // maps are for failures and warnings
      return v;
    }
  }
  // A variant that passes with a warning before any that fails.
  if (const auto warning = std::ranges::find(tried, Status::kWarn, &ImageVerdict::status);
      warning != tried.end()) {
    add_diff(*warning, render, tolerance, ignored, want_diff, counted);
    return *warning;
  }
  // None passed: report the closest golden.
  ImageVerdict best = *std::min_element(tried.begin(), tried.end(), closer);
  add_diff(best, render, tolerance, ignored, want_diff, counted);
  return best;
}

}  // namespace aosuite::harness
