// The library behind include/aosuite/aosuite.hpp: a thin layer over the harness's verdict
// (harness/judge.hpp), which `aosuite check` and folder mode use too.
#include "aosuite/aosuite.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "common/file_io.hpp"
#include "compare/metric.hpp"
#include "harness/goldens.hpp"
#include "harness/judge.hpp"
#include "image/image_file.hpp"
#include "image/image_io.hpp"

namespace aosuite {
namespace {

namespace fs = std::filesystem;

RgbaImage pixels_of(const Image& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() != std::size_t(image.width) * std::size_t(image.height) * 4) {
    throw std::invalid_argument("an Image needs width * height * 4 bytes of RGBA");
  }
  RgbaImage out(image.width, image.height);
  std::memcpy(out.data(), image.rgba.data(), image.rgba.size());
  return out;
}

harness::Tolerance tolerance_of(const Tolerance& t) {
  harness::Tolerance out;
  out.mode = resemble::parse_mode(t.mode);
  out.max_mismatch_percent = t.max_mismatch_percent;
  out.max_channel_delta = t.max_channel_delta;
  for (const std::string& spec : t.gates) metric::add_gate_spec(out.gates, spec);
  out.resemble = t.resemble || out.gates.empty();
  return out;
}

Verdict verdict_of(const harness::ImageVerdict& v) {
  Verdict out;
  out.status = v.status == harness::Status::kPass   ? Verdict::Status::kPass
               : v.status == harness::Status::kFail ? Verdict::Status::kFail
               : v.status == harness::Status::kNew  ? Verdict::Status::kNew
                                                    : Verdict::Status::kError;
  out.mismatch_percent = v.mismatch_percent;
  out.max_channel_delta = v.max_channel_delta;
  out.message = v.status == harness::Status::kPass ? "" : v.message;
  return out;
}

// The verdict on `image` against the goldens given (none: NEW).
Verdict judge(const Image& image, const std::vector<fs::path>& goldens, const Tolerance& t) {
  try {
    const RgbaImage rgba = pixels_of(image);
    const std::vector<unsigned char> png = encode_png_rgba8(rgba, 1);
    return verdict_of(harness::judge("image", png, rgba, goldens, tolerance_of(t), false));
  } catch (const std::exception& e) {
    Verdict v;
    v.message = e.what();
    return v;
  }
}

}  // namespace

std::ostream& operator<<(std::ostream& out, const Verdict& v) {
  static constexpr const char* kNames[] = {"PASS", "FAIL", "NEW", "ERROR"};
  out << kNames[static_cast<int>(v.status)] << " (mismatch " << v.mismatch_percent
      << " %, max channel delta " << v.max_channel_delta << ")";
  return v.message.empty() ? out : out << ": " << v.message;
}

Image read_image(const std::string& file) {
  const RgbaImage rgba = decode_rgba8(read_file(file, kMaxFileBytes), file);
  Image out{rgba.width(), rgba.height(), {}};
  out.rgba.assign(rgba.data(), rgba.data() + rgba.view().bytes());
  return out;
}

void write_png(const std::string& file, const Image& image) {
  write_png_rgba8(file, pixels_of(image));
}

Verdict compare(const Image& actual, const Image& expected, const Tolerance& tolerance) {
  // The expected image is judged as a golden file, exactly as `aosuite check` would.
  std::string pattern = (fs::temp_directory_path() / "aosuite-compare-XXXXXX").string();
  if (!mkdtemp(pattern.data())) {
    Verdict v;
    v.message = "cannot make a temporary folder: " + std::string(std::strerror(errno));
    return v;
  }
  const fs::path dir = pattern;
  const fs::path golden = dir / "expected.png";
  Verdict v;
  try {
    write_png(golden.string(), expected);
    v = judge(actual, {golden}, tolerance);
  } catch (const std::exception& e) {
    v.message = e.what();
  }
  std::error_code ec;
  fs::remove_all(dir, ec);
  return v;
}

Verdict matches_golden(const Image& image, const std::string& golden, const Tolerance& tolerance) {
  std::error_code ec;
  const bool exists = fs::exists(golden, ec);
  Verdict v =
      judge(image, exists ? std::vector<fs::path>{golden} : std::vector<fs::path>{}, tolerance);
  const char* update = std::getenv("AOSUITE_UPDATE_GOLDENS");
  if (v.status != Verdict::Status::kPass && update && std::strcmp(update, "1") == 0) {
    try {
      if (!fs::path(golden).parent_path().empty())
        fs::create_directories(fs::path(golden).parent_path());
      write_png(golden, image);
      v.status = Verdict::Status::kPass;
      v.message = "wrote the golden " + golden + " (AOSUITE_UPDATE_GOLDENS=1)";
    } catch (const std::exception& e) {
      v.status = Verdict::Status::kError;
      v.message = e.what();
    }
  }
  return v;
}

}  // namespace aosuite
