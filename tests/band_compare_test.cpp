// compare_png_bands against decoding both files whole and calling resemble::compare: the
// same result for every option it takes, at sizes that wrap its ring of bands; nullopt for
// everything it leaves to the whole-image path; errors that name the file.
#include "compare/band_compare.hpp"

#include <gtest/gtest.h>

#include <random>

#include "image/image_io.hpp"
#include "png_fixture.hpp"

namespace aosuite {
namespace {

using test::Bytes;
namespace rs = resemble;

struct Pair {
  Bytes a, b;
};

// Random RGB or RGBA pixels, and a copy that differs a little or a lot in places; every
// row filter, so unfiltering across band edges is exercised.
Pair random_pair(std::mt19937& rng, int w, int h, int channels) {
  std::uniform_int_distribution<int> byte(0, 255), coin(0, 99), delta(-40, 40);
  std::vector<Bytes> a(std::size_t(h), Bytes(std::size_t(w) * channels)), b;
  for (auto& row : a)
    for (auto& v : row) v = static_cast<unsigned char>(byte(rng));
  b = a;
  const int edit_percent = coin(rng) % 20;
  for (auto& row : b) {
    for (auto& v : row) {
      if (coin(rng) < edit_percent)
        v = static_cast<unsigned char>(std::clamp(v + delta(rng), 0, 255));
    }
  }
  const int type = channels == 4 ? 6 : 2;
  const std::vector<int> filters{0, 1, 2, 3, 4};
  return {test::make_png(w, h, 8, type, a, {}, {}, filters, channels),
          test::make_png(w, h, 8, type, b, {}, {}, filters, channels)};
}

rs::Result whole(const Pair& p, const rs::Options& o) {
  return rs::compare(decode_png(p.a, "a.png"), decode_png(p.b, "b.png"), o);
}

void expect_same(const rs::Result& got, const rs::Result& want, const std::string& what) {
  EXPECT_EQ(got.mismatch_count, want.mismatch_count) << what;
  EXPECT_EQ(got.raw_mismatch_percentage, want.raw_mismatch_percentage) << what;
  EXPECT_EQ(got.mismatch_percentage, want.mismatch_percentage) << what;
  EXPECT_EQ(got.diff_bounds, want.diff_bounds) << what;
  EXPECT_TRUE(got.same_dimensions) << what;
  EXPECT_TRUE(got.diff.empty()) << what;
}

std::vector<rs::Options> threshold_options() {
  std::vector<rs::Options> out(5);
  out[1].modes = {rs::Mode::kLess};
  out[2].modes = {rs::Mode::kNothing};
  out[3].modes = {rs::Mode::kAlpha};
  out[4].modes = {rs::Mode::kLess};
  out[4].tolerance.red = 3, out[4].tolerance.alpha = 30;
  return out;
}

TEST(BandCompare, SameResultAsWholeImagesAcrossBandsAndRingWraps) {
  std::mt19937 rng(11);
  // Widths give bands of 8 to 108 rows, or a single row (40000 px: wider than a band);
  // heights end mid-band and wrap the ring of four bands several times.
  const std::vector<std::pair<int, int>> sizes = {{1, 1},      {37, 23},   {300, 250},
                                                  {2000, 150}, {4000, 37}, {40000, 6}};
  for (const auto& [w, h] : sizes) {
    for (int channels : {3, 4}) {
      const Pair p = random_pair(rng, w, h, channels);
      for (const rs::Options& o : threshold_options()) {
        const std::string what =
            std::to_string(w) + "x" + std::to_string(h) + "x" + std::to_string(channels) +
            " mode " + (o.modes.empty() ? "default" : std::string(rs::mode_name(o.modes[0])));
        const auto got = compare_png_bands(p.a, "a.png", p.b, "b.png", o);
        ASSERT_TRUE(got) << what;
        expect_same(*got, whole(p, o), what);
      }
    }
  }
}

TEST(BandCompare, IdenticalPixelsAndEdgeMismatches) {
  // One mismatching pixel in each corner: the bounds come from the first and last band.
  const int w = 2000, h = 150;
  std::vector<Bytes> a(h, Bytes(std::size_t(w) * 4, 90)), b = a;
  for (auto [x, y] : {std::pair{0, 0}, {w - 1, 0}, {0, h - 1}, {w - 1, h - 1}}) b[y][4 * x] = 200;
  const Bytes pa = test::make_png(w, h, 8, 6, a), pb = test::make_png(w, h, 8, 6, b);
  const auto got = compare_png_bands(pa, "a.png", pb, "b.png", {});
  ASSERT_TRUE(got);
  EXPECT_EQ(got->mismatch_count, 4u);
  EXPECT_EQ(got->diff_bounds, (rs::Bounds{0, 0, h - 1, w - 1}));
  const auto same = compare_png_bands(pa, "a.png", test::make_png(w, h, 8, 6, a), "c.png", {});
  ASSERT_TRUE(same);
  EXPECT_EQ(same->mismatch_count, 0u);
  EXPECT_EQ(same->diff_bounds, (rs::Bounds{h, w, 0, 0}));
}

TEST(BandCompare, LeavesEverythingElseToTheWholeImagePath) {
  std::mt19937 rng(3);
  const Pair p = random_pair(rng, 16, 8, 4);
  auto banded = [&](const rs::Options& o) { return compare_png_bands(p.a, "a", p.b, "b", o); };
  rs::Options o;
  EXPECT_TRUE(banded(o));
  for (rs::Mode m : {rs::Mode::kAntialiasing, rs::Mode::kColors}) {
    o = {};
    o.modes = {m};
    EXPECT_FALSE(banded(o)) << rs::mode_name(m);
  }
  o = {};
  o.produce_diff = true;
  EXPECT_FALSE(banded(o));
  o = {};
  o.return_early_threshold = 5;
  EXPECT_FALSE(banded(o));
  o = {};
  o.ignored_boxes = std::vector<rs::Box>{{0, 0, 4, 4}};
  EXPECT_FALSE(banded(o));
  o = {};
  o.canvas_alpha = CanvasAlpha::kChromium;
  EXPECT_FALSE(banded(o));
  // different sizes, a grey PNG (libspng's kind), not a PNG at all
  const Pair other = random_pair(rng, 16, 9, 4);
  EXPECT_FALSE(compare_png_bands(p.a, "a", other.b, "b", {}));
  const Bytes grey = test::make_png(16, 8, 8, 0, std::vector<Bytes>(8, Bytes(16, 7)));
  EXPECT_FALSE(compare_png_bands(p.a, "a", grey, "b", {}));
  EXPECT_FALSE(compare_png_bands(Bytes{'h', 'i'}, "a", p.b, "b", {}));
}

TEST(BandCompare, CorruptFileIsAnErrorNamingIt) {
  const int w = 2000, h = 150;
  const std::vector<Bytes> rows(h, Bytes(std::size_t(w) * 4, 50));
  const Bytes good = test::make_png(w, h, 8, 6, rows);
  // The same rows with the stream cut short, its last row filter 7, or its checksum wrong:
  // each found only when the decoder reaches the end, after many bands were compared.
  Bytes raw;
  for (const Bytes& r : rows) {
    raw.push_back(0);
    raw.insert(raw.end(), r.begin(), r.end());
  }
  Bytes bad_filter = raw;
  bad_filter[raw.size() - (std::size_t(w) * 4 + 1)] = 7;
  Bytes short_z = test::zlib_compress(raw);
  // erase, not resize: resize's unreachable growth path makes GCC 12 under -fsanitize=address
  // warn of a memset of 2^64 - 30 bytes (-Wstringop-overflow).
  short_z.erase(short_z.end() - 30, short_z.end());
  Bytes bad_adler = test::zlib_compress(raw);
  bad_adler.back() ^= 1;
  for (const Bytes& z : {test::zlib_compress(bad_filter), short_z, bad_adler}) {
    const Bytes bad = test::png_with_idat(w, h, 8, 6, z);
    for (const bool bad_second : {false, true}) {
      try {
        if (bad_second) {
          compare_png_bands(good, "good.png", bad, "bad.png", {});
        } else {
          compare_png_bands(bad, "bad.png", good, "good.png", {});
        }
        ADD_FAILURE() << "no error";
      } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find("bad.png"), std::string::npos) << e.what();
      }
    }
  }
}

}  // namespace
}  // namespace aosuite
