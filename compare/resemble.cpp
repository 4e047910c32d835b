#include "compare/resemble.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string>

#include "common/printable.hpp"
#include "compare/count_kernel.hpp"
#include "compare/js_number.hpp"
#include "compare/parallel_rows.hpp"
#include "compare/resemble_pixel.hpp"

namespace aosuite::resemble {

Mode parse_mode(std::string_view name) {
  for (Mode mode : {Mode::kDefault, Mode::kNothing, Mode::kLess, Mode::kColors, Mode::kAntialiasing,
                    Mode::kAlpha}) {
    if (mode_name(mode) == name) return mode;
  }
  throw std::invalid_argument("unknown mode '" + printable(name) +
                              "' (expected nothing, less, colors, antialiasing or alpha)");
}

std::string_view mode_name(Mode mode) {
  switch (mode) {
    case Mode::kDefault:
      return "default";
    case Mode::kNothing:
      return "nothing";
    case Mode::kLess:
      return "less";
    case Mode::kColors:
      return "colors";
    case Mode::kAntialiasing:
      return "antialiasing";
    case Mode::kAlpha:
      return "alpha";
  }
  return "default";
}

ErrorType parse_error_type(std::string_view name) {
  if (name == "movement") return ErrorType::kMovement;
  if (name == "flatDifferenceIntensity") return ErrorType::kFlatDifferenceIntensity;
  if (name == "movementDifferenceIntensity") return ErrorType::kMovementDifferenceIntensity;
  if (name == "diffOnly") return ErrorType::kDiffOnly;
  return ErrorType::kFlat;
}

Settings resolve(const Options& options) {
  Settings s;
  Tolerance& t = s.tolerance;
  for (Mode mode : options.modes) {
    // Resemble's ignoreX() setters (resemble.js 867-943); colors keeps the RGB tolerances.
    switch (mode) {
      case Mode::kDefault:
        continue;  // not a Resemble mode: sets nothing, applies no custom tolerance
      case Mode::kNothing:
        t = {0, 0, 0, 0, 0, 255};
        break;
      case Mode::kLess:
        t = {16, 16, 16, 16, 16, 240};
        break;
      case Mode::kAntialiasing:
        t = {32, 32, 32, 32, 64, 96};
        break;
      case Mode::kAlpha:
        t = {16, 16, 16, 255, 16, 240};
        break;
      case Mode::kColors:
        t.alpha = 16;
        t.min_brightness = 16;
        t.max_brightness = 240;
        break;
    }
    s.ignore_antialiasing = mode == Mode::kAntialiasing;
    s.ignore_colors = mode == Mode::kColors;
    // setupCustomTolerance() runs after every applied mode.
    const ToleranceOverride& o = options.tolerance;
    t.red = o.red.value_or(t.red);
    t.green = o.green.value_or(t.green);
    t.blue = o.blue.value_or(t.blue);
    t.alpha = o.alpha.value_or(t.alpha);
    t.min_brightness = o.min_brightness.value_or(t.min_brightness);
    t.max_brightness = o.max_brightness.value_or(t.max_brightness);
  }
  return s;
}

namespace {

using namespace pixel;  // NOLINT: the predicates read as Resemble's own names

// JavaScript's `v || fallback` for a number.
double or_default(double v, double fallback) { return (v == 0 || std::isnan(v)) ? fallback : v; }

class PixelJudge {
 public:
  PixelJudge(RgbaView d1, RgbaView d2, const Options& o, const Settings& s)
      : d1_(d1.data), d2_(d2.data), w_(d1.width), h_(d1.height), o_(o), s_(s) {}

  // Resemble's per-pixel body (resemble.js 598-654). Paints into diff when it is non-null;
  // returns true for a mismatch.
  bool judge(int x, int y, unsigned char* diff) const {
    const std::size_t off = (std::size_t(y) * w_ + x) * 4;
    const Px p1 = load(d1_ + off), p2 = load(d2_ + off);
    const bool area = in_area(x, y, p2);
    unsigned char* out = diff ? diff + off : nullptr;
    if (s_.ignore_colors) {
      if (brightness_similar(p1, p2) || !area) return ok(out, p2, true);
      return error(out, p1, p2);
    }
    if (rgb_similar(p1, p2) || !area) return ok(out, p1, false);
    if (s_.ignore_antialiasing && (antialiased(d1_, p1, x, y) || antialiased(d2_, p2, x, y))) {
      if (brightness_similar(p1, p2)) return ok(out, p2, true);
    }
    return error(out, p1, p2);
  }

 private:
  bool rgb_similar(const Px& p1, const Px& p2) const {
    const Tolerance& t = s_.tolerance;
    return similar(p1.r, p2.r, t.red) && similar(p1.g, p2.g, t.green) &&
           similar(p1.b, p2.b, t.blue) && similar(p1.a, p2.a, t.alpha);
  }

  bool brightness_similar(const Px& p1, const Px& p2) const {
    return similar(p1.a, p2.a, s_.tolerance.alpha) &&
           similar(brightness(p1), brightness(p2), s_.tolerance.min_brightness);
  }

  bool within(int x, int y, const Box& b) const {
    return x > or_default(b.left, 0) && x < or_default(b.right, w_) && y > or_default(b.top, 0) &&
           y < or_default(b.bottom, h_);
  }

  bool in_area(int x, int y, const Px& p2) const {
    if (o_.ignore_areas_colored_with) {
      const Color& c = *o_.ignore_areas_colored_with;
      return colors_distance(p2, c.r, c.g, c.b) != 0;
    }
    auto inside = [&](const Box& b) { return within(x, y, b); };
    if (o_.bounding_boxes &&
        std::none_of(o_.bounding_boxes->begin(), o_.bounding_boxes->end(), inside)) {
      return false;
    }
    return !(o_.ignored_boxes &&
             std::any_of(o_.ignored_boxes->begin(), o_.ignored_boxes->end(), inside));
  }

  bool antialiased(const unsigned char* img, const Px& p, int x, int y) const {
    return pixel::antialiased(img, w_, h_, p, x, y, s_.tolerance.max_brightness);
  }

  bool ok(unsigned char* out, const Px& p, bool grey) const {
    if (!out || o_.error_type == ErrorType::kDiffOnly) return false;
    if (grey) {
      out[0] = out[1] = out[2] = u8clamp(brightness(p));
    } else {
      out[0] = static_cast<unsigned char>(p.r);
      out[1] = static_cast<unsigned char>(p.g);
      out[2] = static_cast<unsigned char>(p.b);
    }
    out[3] = u8clamp(p.a * o_.transparency);
    return false;
  }

  bool error(unsigned char* out, const Px& p1, const Px& p2) const {
    if (!out) return true;
    const Color& e = o_.error_color;
    double v[4] = {e.r, e.g, e.b, e.a};
    switch (o_.error_type) {
      case ErrorType::kFlat:
        break;
      case ErrorType::kMovement:
        v[0] = (p2.r * (e.r / 255) + e.r) / 2;
        v[1] = (p2.g * (e.g / 255) + e.g) / 2;
        v[2] = (p2.b * (e.b / 255) + e.b) / 2;
        v[3] = p2.a;
        break;
      case ErrorType::kFlatDifferenceIntensity:
        v[3] = colors_distance(p1, p2.r, p2.g, p2.b);
        break;
      case ErrorType::kMovementDifferenceIntensity: {
        const double k = (colors_distance(p1, p2.r, p2.g, p2.b) / 255) * 0.8;
        v[0] = (1 - k) * (p2.r * (e.r / 255)) + k * e.r;
        v[1] = (1 - k) * (p2.g * (e.g / 255)) + k * e.g;
        v[2] = (1 - k) * (p2.b * (e.b / 255)) + k * e.b;
        v[3] = p2.a;
        break;
      }
      case ErrorType::kDiffOnly:
        v[0] = p2.r, v[1] = p2.g, v[2] = p2.b, v[3] = p2.a;
        break;
    }
    for (int c = 0; c < 4; ++c) out[c] = u8clamp(v[c]);
    return true;
  }

  const unsigned char* d1_;
  const unsigned char* d2_;
  int w_, h_;
  const Options& o_;
  const Settings& s_;
};

// Resemble skips every sixth row and column of large images, in antialiasing mode only.
bool skipped(int x, int y, bool skip) { return skip && (x % 6 == 0 || y % 6 == 0); }

// An image as Resemble's canvas sees it: the caller's pixels, or a modified copy.
struct Seen {
  RgbaImage copy;
  RgbaView view;
};

Seen as_seen(RgbaView img, int w, int h, CanvasAlpha model) {
  Seen out{{}, img};
  if (model != CanvasAlpha::kNone) {
    out.copy = copy_of(img);
    apply_canvas_decode(out.copy, model);
    out.view = out.copy.view();
  }
  if (img.width == w && img.height == h) return out;
  // The smaller image is padded right and bottom with transparent black (normalise()).
  RgbaImage padded(w, h);
  for (int y = 0; y < img.height; ++y) {
    std::copy_n(out.view.row(y), std::size_t(img.width) * 4,
                padded.data() + std::size_t(y) * std::size_t(w) * 4);
  }
  apply_canvas_put_get(padded, model);
  return {padded, padded.view()};
}

// When Resemble returns early it stops after the first pixel, in its column-major order,
// at which the running percentage exceeds the threshold. Our pass is row-major and
// complete, so replay that order over the mismatch mask.
MismatchTally truncate_early(const std::vector<unsigned char>& mask, int w, int h, bool skip,
                             double threshold) {
  const double pixels = double(h) * double(w);
  auto above = [&](std::uint64_t n) { return (double(n) / pixels) * 100 > threshold; };
  auto at = [&](int x, int y) { return mask[std::size_t(y) * std::size_t(w) + std::size_t(x)]; };
  std::vector<std::uint32_t> column(static_cast<std::size_t>(w), 0);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) column[std::size_t(x)] += at(x, y);
  }
  std::uint64_t seen = 0;
  int stop_x = w, stop_y = h;
  for (int x = 0; x < w && stop_x == w; ++x) {
    if (!above(seen + column[x]) && !above(seen)) {
      seen += column[x];
      continue;
    }
    for (int y = 0; y < h; ++y) {
      if (skipped(x, y, skip)) continue;
      seen += at(x, y);
      if (above(seen)) {
        stop_x = x, stop_y = y;
        break;
      }
    }
  }
  MismatchTally t;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < std::min(w, stop_x + 1); ++x) {
      if (at(x, y) && (x < stop_x || y <= stop_y)) t.add(y, 1, x, x);
    }
  }
  return t;
}

}  // namespace

Result result_from_tally(const MismatchTally& tally, ImageSize a, ImageSize b,
                         std::chrono::steady_clock::time_point start) {
  Result r;
  const int w = std::max(a.width, b.width), h = std::max(a.height, b.height);
  r.mismatch_count = tally.count;
  r.raw_mismatch_percentage = (double(tally.count) / (double(h) * double(w))) * 100;
  r.mismatch_percentage = js_to_fixed2(r.raw_mismatch_percentage);
  r.same_dimensions = a.width == b.width && a.height == b.height;
  r.width_difference = a.width - b.width;
  r.height_difference = a.height - b.height;
  r.diff_bounds =
      tally.count ? Bounds{tally.top, tally.left, tally.bottom, tally.right} : Bounds{h, w, 0, 0};
  r.analysis_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return r;
}

std::optional<std::array<int, 4>> count_only_thresholds(const Options& options) {
  const Settings s = resolve(options);
  const double early = options.return_early_threshold;
  const bool compare_only = early != 0 && !std::isnan(early);
  const bool has_area =
      options.bounding_boxes || options.ignored_boxes || options.ignore_areas_colored_with;
  if (s.ignore_colors || s.ignore_antialiasing || has_area || compare_only ||
      options.produce_diff) {
    return std::nullopt;
  }
  const Tolerance& t = s.tolerance;
  std::array<int, 4> min_delta{};
  const double tol[4] = {t.red, t.green, t.blue, t.alpha};
  for (int c = 0; c < 4; ++c) {
    int d = 1;
    while (d < 256 && similar(0, d, tol[c])) ++d;
    min_delta[c] = d;
  }
  return min_delta;
}

Result compare_identical(ImageSize size) {
  return result_from_tally({}, size, size, std::chrono::steady_clock::now());
}

std::uint64_t working_bytes(ImageSize a, ImageSize b, const Options& options) {
  auto px = [](std::uint64_t w, std::uint64_t h) { return w * h; };
  const std::uint64_t w = std::uint64_t(std::max(a.width, b.width));
  const std::uint64_t h = std::uint64_t(std::max(a.height, b.height));
  std::uint64_t bytes = 0;
  for (const ImageSize& s : {a, b}) {  // as_seen: a canvas model's copy, padding to w x h
    if (options.canvas_alpha != CanvasAlpha::kNone) bytes += 4 * px(s.width, s.height);
    if (std::uint64_t(s.width) != w || std::uint64_t(s.height) != h) bytes += 4 * px(w, h);
  }
  const double early = options.return_early_threshold;
  const bool compare_only = early != 0 && !std::isnan(early);
  if (!count_only_thresholds(options)) {
    if (options.produce_diff && !compare_only) bytes += 4 * px(w, h);        // the diff image
    if (compare_only && !resolve(options).ignore_colors) bytes += px(w, h);  // the mask
  }
  return bytes;
}

Result compare(RgbaView a, RgbaView b, const Options& options) {
  const auto start = std::chrono::steady_clock::now();
  const Settings s = resolve(options);
  const int w = std::max(a.width, b.width), h = std::max(a.height, b.height);
  const Seen seen1 = as_seen(a, w, h, options.canvas_alpha);
  const Seen seen2 = as_seen(b, w, h, options.canvas_alpha);
  const RgbaView d1 = seen1.view, d2 = seen2.view;

  const double thr = options.large_image_threshold;
  const bool skip = thr != 0 && !std::isnan(thr) && s.ignore_antialiasing && (w > thr || h > thr);
  const double early = options.return_early_threshold;
  const bool compare_only = early != 0 && !std::isnan(early);
  const bool stops_early = compare_only && !s.ignore_colors;

  RgbaImage diff_image;
  MismatchTally tally;
  if (const auto min_delta = count_only_thresholds(options)) {
    tally = count_mismatches(d1.data, d2.data, w, h, *min_delta);
  } else {
    if (options.produce_diff && !compare_only) diff_image = RgbaImage(w, h);
    std::vector<unsigned char> mask(stops_early ? std::size_t(w) * std::size_t(h) : 0);
    const PixelJudge judge(d1, d2, options, s);
    unsigned char* diff = diff_image.empty() ? nullptr : diff_image.data();
    std::mutex m;
    parallel_rows(w, h, [&](int y0, int y1) {
      MismatchTally local;
      for (int y = y0; y < y1; ++y) {
        for (int x = 0; x < w; ++x) {
          if (skipped(x, y, skip) || !judge.judge(x, y, diff)) continue;
          local.add(y, 1, x, x);
          if (stops_early) mask[std::size_t(y) * std::size_t(w) + std::size_t(x)] = 1;
        }
      }
      std::lock_guard lock(m);
      tally.merge(local);
    });
    if (stops_early) tally = truncate_early(mask, w, h, skip, early);
  }

  Result r = result_from_tally(tally, {a.width, a.height}, {b.width, b.height}, start);
  r.diff = std::move(diff_image);
  return r;
}

}  // namespace aosuite::resemble
