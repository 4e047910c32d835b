// The banded comparison straight from two PNG files (compare/band_compare.hpp): whatever it
// accepts, decoding both files whole accepts too and counts the same mismatches; whatever it
// refuses, one of the files is refused by decode_png.
// Input: one byte choosing the mode, two bytes (big-endian) giving the first file's length,
// the first file, the second file.
#include <optional>

#include "compare/band_compare.hpp"
#include "fuzz/fuzz_util.hpp"
#include "image/image_io.hpp"

namespace {

namespace rs = aosuite::resemble;
namespace fuzz = aosuite::fuzz;

// Both files decoded whole, or nullopt when either is refused.
std::optional<std::pair<aosuite::RgbaImage, aosuite::RgbaImage>> decode_both(
    std::span<const unsigned char> a, std::span<const unsigned char> b) {
  try {
    return std::pair{aosuite::decode_png(a, "a.png"), aosuite::decode_png(b, "b.png")};
  } catch (const aosuite::FileError&) {
    return std::nullopt;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 3) return 0;
  // The modes that keep the count-only path (no colours or antialiasing mode).
  constexpr rs::Mode kModes[] = {rs::Mode::kDefault, rs::Mode::kNothing, rs::Mode::kLess,
                                 rs::Mode::kAlpha};
  rs::Options options;
  options.modes = {kModes[data[0] % 4]};
  const std::size_t len_a = std::min<std::size_t>(size - 3, std::size_t{data[1]} << 8 | data[2]);
  const std::span<const unsigned char> a(data + 3, len_a), b(data + 3 + len_a, size - 3 - len_a);

  std::optional<rs::Result> banded;
  try {
    banded = aosuite::compare_png_bands(a, "a.png", b, "b.png", options);
  } catch (const aosuite::FileError& e) {
    fuzz::expect_printable(e.what());
    if (decode_both(a, b)) fuzz::fail("compare_png_bands refuses files decode_png accepts");
    return 0;
  }
  if (!banded) return 0;  // not both of the fast kind and one size: decoded whole instead
  const auto images = decode_both(a, b);
  if (!images) fuzz::fail("compare_png_bands accepts a file decode_png refuses");
  const rs::Result whole = rs::compare(images->first, images->second, options);
  if (whole.mismatch_count != banded->mismatch_count ||
      whole.raw_mismatch_percentage != banded->raw_mismatch_percentage ||
      !(whole.diff_bounds == banded->diff_bounds)) {
    fuzz::fail("the banded and the whole comparison differ");
  }
  return 0;
}
