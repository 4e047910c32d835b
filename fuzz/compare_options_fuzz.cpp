// The option objects of `compare --batch` lines (compare/resemble_json.hpp) and the comparison
// they configure (compare/resemble.hpp), on small images made from the input: an image never
// differs from itself, and the result line is JSON.
// Input: a JSON line, a newline, then the images: canvas model, width and height of A and of
// B (each 1 + byte % 16), and pixel bytes (repeated as needed; A's first, then B's).
#include <nlohmann/json.hpp>
#include <string_view>

#include "compare/resemble.hpp"
#include "compare/resemble_json.hpp"
#include "fuzz/fuzz_util.hpp"
#include "image/image_io.hpp"

namespace {

namespace rs = aosuite::resemble;
namespace fuzz = aosuite::fuzz;

// A w x h image of the pixel bytes from `at` on, wrapping around.
aosuite::RgbaImage image(std::string_view pixels, std::size_t at, int w, int h) {
  aosuite::RgbaImage out(w, h);
  for (std::size_t i = 0; i < out.view().bytes(); ++i) {
    out.data()[i] =
        pixels.empty() ? 0 : static_cast<unsigned char>(pixels[(at + i) % pixels.size()]);
  }
  return out;
}

void check(const rs::Result& r) {
  if (!nlohmann::json::accept(rs::result_json(r))) fuzz::fail("the result line is not JSON");
  if (r.raw_mismatch_percentage < 0 || r.raw_mismatch_percentage > 100) {
    fuzz::fail("a mismatch percentage outside 0..100");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input = fuzz::as_text(data, size);
  const std::size_t newline = std::min(input.find('\n'), input.size());
  std::string_view rest = input.substr(std::min(newline + 1, input.size()));
  rs::Options options;
  try {
    rs::apply_json_options(nlohmann::json::parse(input.substr(0, newline)), options);
  } catch (const nlohmann::json::exception&) {
    return 0;
  } catch (const std::invalid_argument& e) {
    fuzz::expect_printable(e.what());
    return 0;
  }
  if (rest.size() < 5) return 0;
  constexpr aosuite::CanvasAlpha kModels[] = {aosuite::CanvasAlpha::kNone,
                                              aosuite::CanvasAlpha::kChromium,
                                              aosuite::CanvasAlpha::kNodeCanvas};
  options.canvas_alpha = kModels[static_cast<unsigned char>(rest[0]) % 3];
  auto side = [&](int i) { return 1 + static_cast<unsigned char>(rest[1 + i]) % 16; };
  const int wa = side(0), ha = side(1), wb = side(2), hb = side(3);
  rest.remove_prefix(5);
  const aosuite::RgbaImage a = image(rest, 0, wa, ha);
  const aosuite::RgbaImage b = image(rest, a.view().bytes(), wb, hb);

  for (const bool diff : {false, true}) {
    options.produce_diff = diff;
    const rs::Result same = rs::compare(a, a, options);
    check(same);
    if (same.mismatch_count != 0) fuzz::fail("an image differs from itself");
    check(rs::compare(a, b, options));
  }
  return 0;
}
