// The library behind include/aosuite/aosuite.hpp: a thin layer over the one comparison
// (compare/comparison.hpp), which `aosuite compare`, folder mode and suites use too.
#include "aosuite/aosuite.hpp"

#include <fmt/format.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "common/file_io.hpp"
#include "compare/comparison.hpp"
#include "image/exr_file.hpp"
#include "image/image_file.hpp"
#include "image/image_io.hpp"

namespace aosuite {
namespace {

namespace fs = std::filesystem;

Picture picture_of(const Image& image, const std::string& name) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() != std::size_t(image.width) * std::size_t(image.height) * 4) {
    throw std::invalid_argument(name + ": an Image needs width * height * 4 bytes of RGBA");
  }
  Picture p;
  p.name = name, p.format = "image";
  p.rgba = RgbaImage(image.width, image.height);
  std::memcpy(p.rgba.data(), image.rgba.data(), image.rgba.size());
  return p;
}

Picture picture_of(const FloatFrame& image, const std::string& name) {
  if (image.width <= 0 || image.height <= 0 || (image.channels != 1 && image.channels != 3) ||
      image.samples.size() !=
          std::size_t(image.width) * std::size_t(image.height) * std::size_t(image.channels)) {
    throw std::invalid_argument(
        name + ": a FloatFrame needs 1 or 3 channels and width * height * channels samples");
  }
  Picture p;
  p.name = name, p.format = "float", p.is_float = true;
  p.floats.width = image.width, p.floats.height = image.height;
  p.floats.channels = image.channels, p.floats.data = image.samples;
  return p;
}

comparison::Tolerance tolerance_of(const Tolerance& t) {
  comparison::Tolerance out;
  out.resemble = t.resemble;
  out.mode = resemble::parse_mode(t.mode);
  out.max_mismatch_percent = t.max_mismatch_percent;
  out.max_channel_delta = t.max_channel_delta;
  out.max_mean_shift = t.max_mean_shift;
  out.max_mean_delta = t.max_mean_delta;
  out.shift_radius = t.shift_radius;
  out.allow_kind_change = t.allow_kind_change;
  for (const std::string& spec : t.gates) metric::add_gate_spec(out.gates, spec);
  for (const std::string& spec : t.float_gates) metric::add_gate_spec(out.float_gates, spec);
  return out;
}

// The public defaults are the comparison's: one rule (tests/api_test.cpp checks it too).
const bool kSameDefaults = [] {
  const comparison::Tolerance mine = tolerance_of({}), rule;
  return mine.mode == rule.mode && mine.max_mismatch_percent == rule.max_mismatch_percent &&
         mine.max_channel_delta == rule.max_channel_delta &&
         mine.max_mean_shift == rule.max_mean_shift && mine.max_mean_delta == rule.max_mean_delta &&
         mine.shift_radius == rule.shift_radius &&
         mine.allow_kind_change == rule.allow_kind_change && mine.resemble == rule.resemble;
}();

Verdict verdict_of(const comparison::Comparison& c) {
  Verdict v;
  v.status = c.same() ? Verdict::Status::kPass : Verdict::Status::kFail;
  v.mismatch_percent = c.mismatch_percent, v.max_channel_delta = c.max_channel_delta;
  v.mean_shift = c.mean_shift, v.mean_delta = c.mean_delta;
  if (!c.same()) v.message = c.message();
  return v;
}

// The one comparison of an in-memory image against an expected one (in memory, or a golden
// file's bytes, so that its own bit depth and layout are judged).
template <class Img>
Verdict compare_with(const Img& actual, const comparison::Input& expected, const Tolerance& t,
                     comparison::Comparison* kept = nullptr) {
  try {
    if (!kSameDefaults) throw std::logic_error("the API's defaults differ from the comparison's");
    const Picture a = picture_of(actual, "the actual image");
    comparison::Options o;
    o.want_diff = kept != nullptr;
    comparison::Comparison c =
        comparison::run(comparison::Input::image(a), expected, tolerance_of(t), o);
    Verdict v = verdict_of(c);
    if (kept) *kept = std::move(c);
    return v;
  } catch (const std::exception& ex) {
    Verdict v;
    v.message = ex.what();
    return v;
  }
}

template <class Img>
Verdict compare_pictures(const Img& actual, const Img& expected, const Tolerance& t) {
  try {
    const Picture e = picture_of(expected, "the expected image");
    return compare_with(actual, comparison::Input::image(e), t);
  } catch (const std::exception& ex) {
    Verdict v;
    v.message = ex.what();
    return v;
  }
}

bool is_exr_name(const fs::path& p) { return p.extension() == ".exr"; }

void write_image(const fs::path& file, const Image& image) { write_png(file.string(), image); }
void write_image(const fs::path& file, const FloatFrame& image) {
  if (!is_exr_name(file)) {
    throw std::invalid_argument(file.string() + ": a FloatFrame's golden is an .exr file");
  }
  write_exr(file.string(), image);
}

// The failure images under $AOSUITE_FAILURES/<test>/: the actual image in the golden's format
// and Resemble's diff (8-bit images); their paths go into the verdict and its message.
template <class Img>
void write_failure(const Img& image, const fs::path& golden, const std::string& test,
                   const comparison::Comparison& c, Verdict& v) {
  const char* root = std::getenv("AOSUITE_FAILURES");
  const fs::path dir = fs::path(root && *root ? root : "aosuite-failures") /
                       (test.empty() ? golden.stem().string() : test);
  fs::create_directories(dir);
  const fs::path actual = dir / ("actual_" + golden.filename().string());
  write_image(actual, image);
  v.actual_file = fs::absolute(actual).string();
  v.message += "\n  actual: " + v.actual_file;
  if (!c.diff.empty()) {
    const fs::path diff = dir / ("diff_" + golden.stem().string() + ".png");
    write_png_rgba8(diff, c.diff);
    v.diff_file = fs::absolute(diff).string();
    v.message += "\n  diff:   " + v.diff_file;
  }
  v.message += "\n  golden: " + fs::absolute(golden).string() +
               "\n  accept it: AOSUITE_UPDATE_GOLDENS=1 (rerun the test)";
}

bool update_requested() {
  const char* update = std::getenv("AOSUITE_UPDATE_GOLDENS");
  return update && std::strcmp(update, "1") == 0;
}

template <class Img>
Verdict golden_verdict(const Img& image, const std::string& golden, const Tolerance& t,
                       const std::string& test) {
  std::error_code ec;
  const bool exists = fs::exists(golden, ec);
  Verdict v;
  comparison::Comparison c;
  if (!exists) {
    v.status = Verdict::Status::kNew;
    v.message = "no golden yet at " + fs::absolute(golden).string() +
                " (AOSUITE_UPDATE_GOLDENS=1 writes it)";
  } else {
    try {
      const std::vector<unsigned char> bytes = read_file(golden, kMaxFileBytes);
      v = compare_with(image, comparison::Input::file(golden, bytes), t, &c);
    } catch (const std::exception& e) {
      v.status = Verdict::Status::kError, v.message = e.what();
    }
  }
  if (v.status != Verdict::Status::kPass && v.status != Verdict::Status::kError &&
      update_requested()) {
    try {
      if (!fs::path(golden).parent_path().empty())
        fs::create_directories(fs::path(golden).parent_path());
      write_image(golden, image);
      v.status = Verdict::Status::kPass;
      v.message = "wrote the golden " + golden + " (AOSUITE_UPDATE_GOLDENS=1)";
    } catch (const std::exception& e) {
      v.status = Verdict::Status::kError, v.message = e.what();
    }
    return v;
  }
  if (v.status == Verdict::Status::kFail) {
    try {
      write_failure(image, golden, test, c, v);
    } catch (const std::exception& e) {
      v.message += "\n  (the failure images could not be written: " + std::string(e.what()) + ")";
    }
  }
  return v;
}

}  // namespace

std::ostream& operator<<(std::ostream& out, const Verdict& v) {
  static constexpr const char* kNames[] = {"PASS", "FAIL", "NEW", "ERROR"};
  out << kNames[static_cast<int>(v.status)];
  return v.message.empty() ? out : out << ": " << v.message;
}

Image read_image(const std::string& file) {
  const RgbaImage rgba = decode_rgba8(read_file(file, kMaxFileBytes), file);
  Image out{rgba.width(), rgba.height(), {}};
  out.rgba.assign(rgba.data(), rgba.data() + rgba.view().bytes());
  return out;
}

FloatFrame read_float_image(const std::string& file) {
  const Picture p = read_picture(file, kMaxFileBytes);
  if (!p.is_float) throw FileError(file + ": an 8-bit image, not float samples (read_image)");
  return {p.floats.width, p.floats.height, p.floats.channels, p.floats.data};
}

void write_png(const std::string& file, const Image& image) {
  write_png_rgba8(file, picture_of(image, file).rgba);
}

void write_exr(const std::string& file, const FloatFrame& image) {
  const Picture p = picture_of(image, file);
  aosuite::write_exr(file, image.width, image.height, p.floats.data.data(), image.channels);
}

Verdict compare(const Image& actual, const Image& expected, const Tolerance& tolerance) {
  return compare_pictures(actual, expected, tolerance);
}

Verdict compare(const FloatFrame& actual, const FloatFrame& expected, const Tolerance& tolerance) {
  return compare_pictures(actual, expected, tolerance);
}

Verdict matches_golden(const Image& image, const std::string& golden, const Tolerance& tolerance,
                       const std::string& test_name) {
  return golden_verdict(image, golden, tolerance, test_name);
}

Verdict matches_golden(const FloatFrame& image, const std::string& golden,
                       const Tolerance& tolerance, const std::string& test_name) {
  return golden_verdict(image, golden, tolerance, test_name);
}

}  // namespace aosuite
