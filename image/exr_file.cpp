#include "image/exr_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <system_error>

#include "common/printable.hpp"
#include "common/sibling_library.hpp"
#include "image/exr_library.hpp"
#include "image/image_io.hpp"

namespace aosuite {
namespace {

// The library is opened at run time (sibling_symbol), never linked: only the types are used.
using ReadExr = decltype(aosuite_read_exr);
using WriteExr = decltype(aosuite_write_exr);

template <class Fn>
struct Entry {
  Fn* fn = nullptr;
  std::string error;
};

template <class Fn>
Fn* exr_entry(const char* symbol, const std::string& name, const char* doing) {
  // One lookup per symbol and process; dlopen shares the library between them.
  static const Entry<Fn> entry = [symbol] {
    Entry<Fn> e;
    e.fn = sibling_symbol<Fn>("libaosuite_exr.so", symbol, e.error);
    return e;
  }();
  if (!entry.fn) throw FileError(fmt::format("{}: cannot {} EXR: {}", name, doing, entry.error));
  return entry.fn;
}

// OpenEXR's messages may span lines, and they and the header walk's quote names from the
// file: one line, escaped.
std::string one_line(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return printable(text);
}

struct Allocation {
  FloatImage* image;
  std::uint64_t max_bytes;
  std::string refused;
};

float* allocate(void* user, int width, int height, int channels) {
  auto& a = *static_cast<Allocation*>(user);
  const std::uint64_t pixels =
      std::uint64_t(std::max(width, 0)) * std::uint64_t(std::max(height, 0));
  if (width <= 0 || height <= 0) {
    a.refused = fmt::format("EXR has an empty data window ({}x{})", width, height);
    return nullptr;
  }
  if (std::string why = decode_budget_problem(width, height, channels, sizeof(float), a.max_bytes);
      !why.empty()) {
    a.refused = std::move(why);
    return nullptr;
  }
  a.image->width = width, a.image->height = height, a.image->channels = channels;
  a.image->data.assign(pixels * std::uint64_t(channels), 0.0f);
  return a.image->data.data();
}

}  // namespace

FloatImage decode_exr(std::span<const unsigned char> bytes, const std::string& name,
                      std::uint64_t max_bytes) {
  ReadExr* read = exr_entry<ReadExr>("aosuite_read_exr", name, "read");
  FloatImage image;
  Allocation a{&image, max_bytes, {}};
  char err[512] = {};
  if (read(bytes.data(), bytes.size(), &allocate, &a, err, sizeof err) != 0) {
    throw FileError(fmt::format("{}: {}", name, a.refused.empty() ? one_line(err) : a.refused));
  }
  return image;
}

void write_exr(const std::filesystem::path& path, int width, int height, const float* pixels,
               int channels) {
  WriteExr* write = exr_entry<WriteExr>("aosuite_write_exr", path.string(), "write");
  const std::filesystem::path tmp =
      path.parent_path() / fmt::format(".{}.tmp.exr", path.filename().string());
  char err[512] = {};
  if (write(tmp.c_str(), width, height, channels, pixels, err, sizeof err) != 0) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw FileError(fmt::format("{}: cannot write EXR: {}", path.string(), one_line(err)));
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace aosuite
