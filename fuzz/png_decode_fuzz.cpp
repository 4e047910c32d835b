// PNG decoding (image/image_io.hpp) on any bytes, held to the one validity rule
// (image/png_layout.hpp): the fast decoder and libspng accept the same files and decode them
// to the same pixels, and check_png accepts exactly what decode_png does, at the same size.
#include <cstring>
#include <optional>

#include "fuzz/fuzz_util.hpp"
#include "image/image_io.hpp"
#include "image/png_fast.hpp"

namespace {

using aosuite::FileError;
using aosuite::RgbaImage;
namespace fuzz = aosuite::fuzz;

const std::string kName = "input.png";

// `decode`'s image, or nullopt for a refused file (whose message must be escaped).
template <typename Decode>
auto accepted(Decode decode) -> std::optional<decltype(decode())> {
  try {
    return decode();
  } catch (const FileError& e) {
    fuzz::expect_printable(e.what());
    return std::nullopt;
  }
}

bool same_pixels(const RgbaImage& a, const RgbaImage& b) {
  return a.width() == b.width() && a.height() == b.height() &&
         std::memcmp(a.data(), b.data(), a.view().bytes()) == 0;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const unsigned char> png(data, size);
  const auto image = accepted([&] { return aosuite::decode_png(png, kName); });
  const auto checked = accepted([&] { return aosuite::check_png(png, kName); });
  if (image.has_value() != checked.has_value()) fuzz::fail("check_png and decode_png disagree");
  if (image && (checked->width != image->width() || checked->height != image->height())) {
    fuzz::fail("check_png and decode_png disagree on the size");
  }
  // decode_png_fast: nullopt for a kind it leaves to libspng, a throw for a refused file.
  const auto fast = accepted([&] { return aosuite::decode_png_fast(png, kName); });
  if (fast && !*fast) return 0;
  const auto general = accepted([&] { return aosuite::decode_png_general(png, kName); });
  if (fast.has_value() != general.has_value()) {
    fuzz::fail(fast ? "libspng refuses what the fast decoder accepts"
                    : "the fast decoder refuses what libspng accepts");
  }
  if (fast && !same_pixels(**fast, *general)) fuzz::fail("the decoders' pixels differ");
  return 0;
}
