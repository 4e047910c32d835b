#include "compare/comparison.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>

#include "common/thread_beside.hpp"
#include "compare/band_compare.hpp"
#include "compare/channel_stats.hpp"
#include "compare/verdict.hpp"
#include "image/image_file.hpp"
#include "image/image_io.hpp"
#include "image/png_layout.hpp"

namespace aosuite::comparison {

namespace fs = std::filesystem;

std::string LargestDifference::text() const {
  return x < 0 ? std::string() : fmt::format("{:.4g} @ ({}, {})", value, x, y);
}

std::string Comparison::message() const {
  const auto joined = [](const std::vector<std::string>& v) {
    std::string out;
    for (const std::string& s : v) out += (out.empty() ? "" : "; ") + s;
    return out;
  };
  if (!failed.empty()) return joined(failed);
  return warned.empty() ? std::string() : "warning: " + joined(warned);
}

std::vector<metric::Gates> Tolerance::gates_for(bool is_float) const {
  std::vector<metric::Gates> out = gates;
  if (is_float) out.insert(out.end(), float_gates.begin(), float_gates.end());
  return out;
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

namespace {

// What kind of samples an input holds: "8-bit" (as a canvas holds it, whatever its channels),
// or "16-bit" / "float" with "grey" or "colour". A PNG's header says it without decoding.
std::string layout(int channels) { return channels == 1 ? "grey" : "colour"; }
std::string kind_of(const Picture& p) {
  if (!p.is_float) return "8-bit";
  return fmt::format("{} {}", p.floats.srgb ? "16-bit" : "float", layout(p.floats.channels));
}

// One side of the comparison, decoded on first need.
class Side {
 public:
  Side(const Input& in, std::uint64_t max_bytes) : in_(in), max_bytes_(max_bytes) {}
  const std::string& name() const { return in_.name; }
  std::span<const unsigned char> bytes() const { return in_.bytes; }
  bool png() const { return !in_.picture && is_png(in_.bytes); }
  const Picture& picture() {
    if (in_.picture) return *in_.picture;
    if (!decoded_) decoded_ = decode_picture(in_.bytes, in_.name, max_bytes_);
    return *decoded_;
  }
  std::string kind() {
    if (png()) {
      const PngHeader h = peek_png_header(in_.bytes, in_.name);
      if (h.bit_depth != 16) return "8-bit";
      return "16-bit " + layout(h.colour_type == 0 || h.colour_type == 4 ? 1 : 3);
    }
    return kind_of(picture());
  }
  // Decodes it whole, so a file cut or corrupt past its header is an error (FileError) before
  // a verdict read from its header alone ("another size or kind") could hide it.
  void check() { png() ? static_cast<void>(rgba8()) : static_cast<void>(picture()); }
  bool is_float() {
    if (png()) return false;  // a 16-bit PNG is compared as a canvas holds it, and by metrics
    return picture().is_float && !picture().floats.srgb;
  }
  // As a canvas holds it (Resemble's view): 8-bit as it is, 16-bit by the high byte.
  const RgbaImage& rgba8() {
    if (!rgba_) {
      rgba_ = png() ? decode_png(in_.bytes, in_.name)
                    : (picture().is_float ? canvas_rgba8(picture()) : copy_of(picture().rgba));
    }
    return *rgba_;
  }
  // The metrics' view: every sample at its full precision (a 16-bit PNG at 16 bits).
  const Picture& full() {
    if (!png()) return picture();
    if (peek_png_header(in_.bytes, in_.name).bit_depth == 16) return picture();
    if (!full_) {
      full_.emplace();
      full_->name = in_.name, full_->format = "PNG", full_->rgba = copy_of(rgba8());
    }
    return *full_;
  }

 private:
  const Input& in_;
  std::uint64_t max_bytes_;
  std::optional<Picture> decoded_, full_;
  std::optional<RgbaImage> rgba_;
};

resemble::Options resemble_options(const Tolerance& t, const Options& o, bool diff) {
  resemble::Options r = o.resemble_options ? *o.resemble_options : resemble::Options{};
  if (!o.resemble_options) r.modes = {t.mode};
  r.produce_diff = diff;
  return r;
}

verdict::ResembleAllowance allowance(const Tolerance& t) {
  return {.max_mismatch_percent = t.max_mismatch_percent,
          .max_channel_delta = t.max_channel_delta,
          .min_channel_delta = t.min_channel_delta,
          .min_differing_pixels = t.min_differing_pixels,
          .max_differing_pixels = t.max_differing_pixels,
          .max_mean_shift = t.max_mean_shift,
          .max_mean_delta = t.max_mean_delta};
}

verdict::ResembleFigures figures(const Comparison& c) {
  return {.mismatch_percent = c.mismatch_percent,
          .mismatch_text = c.mismatch_text,
          .max_channel_delta = c.max_channel_delta,
          .differing_pixels = c.differing_pixels,
          .mean_shift = c.mean_shift,
          .mean_delta = c.mean_delta};
}

void copy_pixel(const RgbaImage& from, RgbaImage& to, std::size_t i) {
  std::copy_n(from.data() + 4 * i, 4, to.data() + 4 * i);
}

// A differing actual pixel within `radius` of an expected pixel it matches (every channel
// within `limit`) is taken as that expected one at its own place: rasterisation jitter.
void forgive_shifts(const RgbaImage& expected, RgbaImage& actual, int radius, int limit) {
  const int w = expected.width(), h = expected.height();
  const RgbaImage original = copy_of(actual);
  const auto close = [&](const unsigned char* a, const unsigned char* e) {
    for (int c = 0; c < 4; ++c)
      if (std::abs(int(a[c]) - int(e[c])) > limit) return false;
    return true;
  };
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(y) * std::size_t(w) + std::size_t(x);
      const unsigned char* a = original.data() + 4 * i;
      if (std::equal(a, a + 4, expected.data() + 4 * i)) continue;
      bool found = false;
      for (int dy = -radius; dy <= radius && !found; ++dy) {
        for (int dx = -radius; dx <= radius && !found; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx < 0 || yy < 0 || xx >= w || yy >= h) continue;
          found =
              close(a, expected.data() + 4 * (std::size_t(yy) * std::size_t(w) + std::size_t(xx)));
        }
      }
      if (found) copy_pixel(expected, actual, i);
    }
  }
}

// The actual image as judged: ignored and uncounted pixels taken from the expected one (so
// nothing differs there), and shifts within the radius forgiven.
RgbaImage judged_pixels(const RgbaImage& expected, const RgbaImage& actual, const Tolerance& t,
                        const std::vector<std::uint8_t>& ignored, const Counted* counted) {
  RgbaImage out = copy_of(actual);
  for (std::size_t i = 0; i < ignored.size(); ++i)
    if (ignored[i]) copy_pixel(expected, out, i);
  if (counted) {
    for (std::size_t i = 0; i < counted->size(); ++i)
      if (!(*counted)[i]) copy_pixel(expected, out, i);
  }
  if (t.shift_radius > 0)
    forgive_shifts(expected, out, t.shift_radius, std::min(t.max_channel_delta, 16));
  return out;
}

void take_stats(const ChannelStats& s, int width, Comparison& c) {
  c.max_channel_delta = s.max_delta;
  c.differing_pixels = static_cast<long long>(s.differing);
  c.mean_shift = s.mean_shift(), c.mean_delta = s.mean_delta();
  if (s.at >= 0) {
    c.largest = {double(s.max_delta), int(s.at % width), int(s.at / width)};
  }
}

// The metric gates of one set of pixels; `region` names them in the outcomes. Only the whole
// image's (or the unpainted pixels') measurements are kept as the comparison's values.
void measure_set(const std::vector<metric::Gates>& gates, const std::string& region,
                 const Picture& expected, const Picture& actual, const Options& o,
                 const Counted* counted, Comparison& c) {
  for (const metric::Gates& g : gates) {
    const bool map = o.want_heatmap && c.heatmap.empty() && g.metric->heatmap;
    metric::Measurement m =
        metric::measure(*g.metric, expected, actual,
                        {.want_map = map, .counted = counted, .tool_pooling = o.tool_pooling});
    for (metric::Outcome& outcome : metric::judge(g, m)) {
      outcome.region = region;
      c.outcomes.push_back(std::move(outcome));
    }
    if (map) c.heatmap = std::move(m.map);
    m.map = {};
    if (region.empty()) c.measured.push_back(std::move(m));
  }
}

// Each pixel's class in the region map: 0 unpainted, i + 1 for regions[i].
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
      const auto& col = t.regions[k].color;
      if (p[0] == col[0] && p[1] == col[1] && p[2] == col[2]) out[i] = std::uint8_t(k + 1);
    }
    if (!out[i]) {
      throw std::runtime_error(fmt::format("{}: pixel ({}, {}) is ({}, {}, {}), no region's colour",
                                           file.string(), i % std::size_t(map.width()),
                                           i / std::size_t(map.width()), p[0], p[1], p[2]));
    }
  }
  return out;
}

// The tolerance's metric gates (and each metric only the warning tier gates, measured once
// and judged by each tier), over the counted pixels; with regions, each region's gates over
// its painted pixels and the tolerance's over the unpainted ones.
void measure_gates(const Picture& expected, const Picture& actual, const Tolerance& t,
                   const Options& o, bool is_float, Comparison& c) {
  std::vector<metric::Gates> whole = t.gates_for(is_float);
  for (const metric::Gates& g : t.warn.gates) metric::gates_for(whole, *g.metric);
  if (whole.empty() && t.regions.empty()) return;
  if (t.regions.empty()) {
    measure_set(whole, "", expected, actual, o, o.counted, c);
    return;
  }
  const std::vector<std::uint8_t> classes = region_classes(o.region_map, t, expected.size());
  for (std::size_t k = 0; k <= t.regions.size(); ++k) {
    Counted mask(classes.size());
    for (std::size_t i = 0; i < mask.size(); ++i)
      mask[i] = classes[i] == k && (!o.counted || (*o.counted)[i]);
    measure_set(k == 0 ? whole : t.regions[k - 1].gates, k == 0 ? "" : t.regions[k - 1].name,
                expected, actual, o, &mask, c);
  }
}

// The warning tier on a passing comparison, over the figures and measurements already made.
verdict::Verdict warned(const Comparison& c, const WarnLimits& w, bool resemble) {
  std::vector<metric::Outcome> outcomes;
  for (const metric::Gates& g : w.gates) {
    for (const metric::Measurement& m : c.measured) {
      if (m.metric != g.metric->name) continue;
      for (metric::Outcome& o : metric::judge(g, m)) outcomes.push_back(std::move(o));
    }
  }
  const verdict::ResembleFigures found = figures(c);
  return verdict::decide(resemble && w.resemble() ? &found : nullptr,
                         {.max_mismatch_percent = w.max_mismatch_percent,
                          .max_channel_delta = w.max_channel_delta,
                          .max_differing_pixels = w.max_differing_pixels},
                         outcomes);
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
    for (std::size_t ch = 0; ch < channels; ++ch) {
      const double d = std::abs(double(a.data[i * ca + std::min(ch, ca - 1)]) -
                                double(b.data[i * cb + std::min(ch, cb - 1)]));
      if (std::isfinite(d) && d > out.value) {
        out = {d, int(i % std::size_t(a.width)), int(i / std::size_t(a.width))};
      }
    }
  }
  return out;
}

// Resemble's figures and the channel statistics of two 8-bit images of one size. Straight
// from the two PNG files, a band at a time, where nothing needs the whole images (no diff,
// nothing ignored or uncounted, no shift radius, Resemble's thresholds alone decide).
// `aosuite compare --diff` keeps the diff image of this comparison, whatever the verdict.
// Returns the ignored pixels it read (a mask is read once per comparison; add_diff reuses them).
std::vector<std::uint8_t> resemble_figures(Side& expected, Side& actual, const Tolerance& t,
                                           const Options& o, Comparison& c) {
  const bool keep_diff = o.want_diff && o.resemble_options;
  const resemble::Options ro = resemble_options(t, o, keep_diff);
  const bool whole =
      keep_diff || o.counted || !t.ignore.empty() || !t.mask.empty() || t.shift_radius > 0;
  if (!whole && expected.png() && actual.png()) {
    ChannelStats stats;
    if (auto r = compare_png_bands(expected.bytes(), expected.name(), actual.bytes(), actual.name(),
                                   ro, &stats)) {
      c.mismatch_percent = r->raw_mismatch_percentage, c.mismatch_text = r->mismatch_percentage;
      take_stats(stats, int(peek_png_header(expected.bytes(), expected.name()).width), c);
      c.resemble = std::move(*r);
      return {};  // no ignore box or mask: nothing is ignored
    }
  }
  const RgbaImage& e = expected.rgba8();
  std::vector<std::uint8_t> ignored = ignored_pixels(t, e.width(), e.height());
  const RgbaImage judged = judged_pixels(e, actual.rgba8(), t, ignored, o.counted);
  resemble::Result r = resemble::compare(e, judged, ro);
  c.mismatch_percent = r.raw_mismatch_percentage, c.mismatch_text = r.mismatch_percentage;
  if (o.counted) {
    const auto n = std::ranges::count_if(*o.counted, [](std::uint8_t f) { return f != 0; });
    c.mismatch_percent = n ? 100.0 * double(r.mismatch_count) / double(n) : 0.0;
    c.mismatch_text = fmt::format("{:.2f}", c.mismatch_percent);
  }
  ChannelStats stats;
  stats.add(e.data(), judged.data(), std::uint64_t(e.width()) * std::uint64_t(e.height()), 0);
  if (o.counted) {  // means over the counted pixels only (the others agree by construction)
    stats.pixels = std::uint64_t(std::ranges::count_if(*o.counted, [](auto f) { return f != 0; }));
  }
  take_stats(stats, e.width(), c);
  if (keep_diff) c.diff = std::move(r.diff), c.ignored = ignored;
  c.resemble = std::move(r);
  return ignored;
}

void decide(const Tolerance& t, bool resemble_gate, Comparison& c) {
  const verdict::ResembleFigures found = figures(c);
  const verdict::Verdict d =
      verdict::decide(resemble_gate ? &found : nullptr, allowance(t), c.outcomes);
  c.failed = d.failed;
  c.verdict = d.pass ? Verdict::kSame : Verdict::kDifferent;
  if (!d.pass) return;
  if (!c.identical)
    c.stale = verdict::stale_budgets(resemble_gate ? &found : nullptr, allowance(t), c.outcomes);
  const verdict::Verdict w = warned(c, t.warn, resemble_gate);
  if (!w.pass) c.verdict = Verdict::kWarn, c.warned = w.failed;
}

void different_shape(Comparison& c, std::string why) {
  c.verdict = Verdict::kDifferent, c.mismatch_percent = 100, c.mismatch_text = "100.00";
  c.failed = {std::move(why)};
}

// Resemble's diff image and the ignored pixels, for a comparison that is not the same.
void add_diff(Side& expected, Side& actual, const Tolerance& t, const Options& o,
              std::vector<std::uint8_t> ignored, Comparison& c) {
  if (!o.want_diff || !c.diff.empty() || c.verdict == Verdict::kSame || !c.comparable) return;
  const RgbaImage& e = expected.rgba8();
  if (ignored.empty()) ignored = ignored_pixels(t, e.width(), e.height());  // no Resemble gate ran
  c.diff = resemble::compare(e, judged_pixels(e, actual.rgba8(), t, ignored, o.counted),
                             resemble_options(t, o, true))
               .diff;
  c.ignored = std::move(ignored);
}

}  // namespace

Comparison run(const Input& actual_in, const Input& expected_in, const Tolerance& t,
               const Options& o) {
  Comparison c;
  Side expected(expected_in, o.max_bytes), actual(actual_in, o.max_bytes);
  if (!expected_in.bytes.empty() && std::ranges::equal(expected_in.bytes, actual_in.bytes)) {
    // Nothing to measure, but a two-sided budget's minimum still judges "no difference".
    c.identical = true, c.comparable = true, c.mismatch_text = "0.00";
    c.expected_kind = c.actual_kind = expected.kind();
    if (!t.mask.empty() && expected.png()) {  // a mask that cannot fit is an error here too
      const PngHeader h = peek_png_header(expected.bytes(), expected.name());
      ignored_pixels(t, int(h.width), int(h.height));
    }
    decide(t, t.resemble && !expected.is_float(), c);
    const bool is_float = expected.is_float();
    if (o.resemble_options) {  // `aosuite compare` prints the metrics and Resemble's result
      const std::vector<metric::Gates> gates = t.gates_for(is_float);
      if (!gates.empty()) measure_set(gates, "", expected.full(), expected.full(), o, nullptr, c);
      if (!is_float) {
        c.resemble = expected.png()
                         ? resemble::compare_identical(check_png(expected.bytes(), expected.name()))
                         : resemble::compare(expected.rgba8(), expected.rgba8(),
                                             resemble_options(t, o, false));
      }
    }
    if (o.want_diff && o.resemble_options && !is_float) {
      c.diff =
          resemble::compare(expected.rgba8(), expected.rgba8(), resemble_options(t, o, true)).diff;
    }
    return c;
  }
  c.expected_kind = expected.kind(), c.actual_kind = actual.kind();
  const bool is_float = expected.is_float() || actual.is_float();
  if (c.expected_kind != c.actual_kind && !t.allow_kind_change) {
    expected.check(), actual.check();
    different_shape(c, fmt::format("expected is {}, actual is {} (allow_kind_change = true "
                                   "accepts another bit depth or layout)",
                                   c.expected_kind, c.actual_kind));
    return c;
  }
  if (is_float) {
    const Picture &e = expected.picture(), &a = actual.picture();
    const ImageSize es = e.size(), as = a.size();
    if (es.width != as.width || es.height != as.height || !same_kind(e, a)) {
      different_shape(c, fmt::format("expected is {}x{} {}, actual is {}x{} {}", es.width,
                                     es.height, e.kind(), as.width, as.height, a.kind()));
      return c;
    }
    measure_gates(e, a, t, o, true, c);
    c.largest = float_difference(e.floats, a.floats, o.counted);
    const std::vector<metric::Gates> gates = t.gates_for(true);
    if (std::ranges::none_of(gates, [](const metric::Gates& g) { return !g.limits.empty(); })) {
      // Nothing allows a difference: float images with no limit must hold the same samples,
      // bit for bit, whatever their files' compression or metadata (a lossless re-encode
      // passes, as it does for 8-bit images), files and images in memory alike.
      if (std::ranges::equal(e.floats.data, a.floats.data, [](float x, float y) {
            return std::bit_cast<std::uint32_t>(x) == std::bit_cast<std::uint32_t>(y);
          })) {
        c.comparable = true;
        decide(t, false, c);
        return c;
      }
      c.verdict = Verdict::kDifferent;
      c.failed = {
          "the float images differ (with no metric gate, float images must hold the same "
          "samples, bit for bit: give one, e.g. flip.max_mean=0.02)"};
      return c;
    }
    c.comparable = true;
    decide(t, false, c);
    return c;
  }
  // 8-bit (and 16-bit as a canvas holds it): sizes from the headers where they are PNGs.
  const auto size_of = [](Side& s) {
    if (s.png()) {
      const PngHeader h = peek_png_header(s.bytes(), s.name());
      return ImageSize{int(h.width), int(h.height)};
    }
    return s.picture().size();
  };
  const ImageSize es = size_of(expected), as = size_of(actual);
  if (es.width != as.width || es.height != as.height) {
    expected.check(), actual.check();
    different_shape(c, fmt::format("expected is {}x{}, actual is {}x{}", es.width, es.height,
                                   as.width, as.height));
    if (o.resemble_options)
      c.resemble =
          resemble::compare(expected.rgba8(), actual.rgba8(), resemble_options(t, o, o.want_diff));
    if (c.resemble) c.diff = std::move(c.resemble->diff);
    return c;
  }
  std::vector<std::uint8_t> ignored;
  if (t.resemble) ignored = resemble_figures(expected, actual, t, o, c);
  measure_gates(expected.full(), actual.full(), t, o, false, c);
  c.comparable = true;
  decide(t, t.resemble, c);
  // A failure says what kind of change it saw (only then: it needs both images decoded).
  if (!c.same())
    c.changes = changed_regions(expected.rgba8(), actual.rgba8(), ignored, 8, o.max_bytes);
  add_diff(expected, actual, t, o, std::move(ignored), c);
  if (o.want_difference_views && !c.same())
    c.views = difference_views(expected.rgba8(), actual.rgba8());
  return c;
}

}  // namespace aosuite::comparison
