#include <gtest/gtest.h>
#include <unistd.h>

#include "compare/opencv.hpp"
#include "image/png_fast.hpp"
#include "png_fixture.hpp"

namespace aosuite {
namespace {

using test::Bytes;
using test::make_png;

cv::Vec4b decode_1px(const Bytes& png) {
  const cv::Mat m = decode_png_rgba8(png, "fixture.png");
  EXPECT_EQ(m.cols, 1);
  EXPECT_EQ(m.rows, 1);
  return m.at<cv::Vec4b>(0, 0);
}

TEST(DecodePng, GreyGreyAlphaPaletteAndSixteenBit) {
  EXPECT_EQ(decode_1px(make_png(1, 1, 8, 0, {{77}})), cv::Vec4b(77, 77, 77, 255));
  EXPECT_EQ(decode_1px(make_png(1, 1, 8, 4, {{77, 9}})), cv::Vec4b(77, 77, 77, 9));
  EXPECT_EQ(decode_1px(make_png(1, 1, 8, 3, {{1}}, {10, 20, 30, 40, 50, 60}, {255, 99})),
            cv::Vec4b(40, 50, 60, 99));  // palette entry 1 with its tRNS alpha
  // 16-bit samples 0xABAB, 0x1212, 0x0000 are exactly 171, 18, 0 in 8 bits
  EXPECT_EQ(decode_1px(make_png(1, 1, 16, 2, {{0xAB, 0xAB, 0x12, 0x12, 0, 0}})),
            cv::Vec4b(171, 18, 0, 255));
  EXPECT_EQ(decode_1px(make_png(1, 1, 16, 0, {{0x12, 0x12}})), cv::Vec4b(18, 18, 18, 255));
}

TEST(DecodePng, EveryRowFilterForRgbAndRgba) {
  // Rows cycle through None, Sub, Up, Average and Paeth, repeat each filter (a row
  // filtered against one filtered the same way), then go through every ordered pair of
  // Sub, Average and Paeth (unfiltered two rows at once); random samples exercise every
  // predictor branch, values 0-3 the ties between predictors, the widths every loop tail.
  // RGBA and RGB 8-bit take the fast path (image/png_fast.hpp).
  cv::RNG rng(5);
  // Ties that change Paeth's choice need a + 2b = 3c, which a small contiguous range hits.
  const std::vector<int> filters{0, 1, 2, 3, 4, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4, 2, 1,
                                 1, 1, 3, 1, 4, 3, 1, 3, 3, 3, 4, 4, 1, 4, 3, 4, 4};
  for (int channels : {3, 4}) {
    for (int w : {1, 2, 3, 4, 5, 37, 74}) {
      const int h = static_cast<int>(filters.size());
      const bool ties = w == 74;
      std::vector<Bytes> rows(h, Bytes(std::size_t(w) * channels));
      for (auto& r : rows)
        for (auto& v : r)
          v = static_cast<unsigned char>(ties ? rng.uniform(0, 4) : rng.uniform(0, 256));
      const Bytes png = make_png(w, h, 8, channels == 4 ? 6 : 2, rows, {}, {}, filters, channels);
      const cv::Mat m = decode_png_rgba8(png, "filters.png");
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
          const unsigned char* src = &rows[y][std::size_t(x) * channels];
          const cv::Vec4b want(src[0], src[1], src[2], channels == 4 ? src[3] : 255);
          ASSERT_EQ(m.at<cv::Vec4b>(y, x), want)
              << channels << " channels, width " << w << ", row " << y << ", x " << x;
        }
      }
    }
  }
}

// Reading a PNG a few rows at a time gives the rows decode_png gives, whatever the band
// size, with the zlib stream split over several IDAT chunks or in one.
TEST(PngRows, AnyBandSizeGivesTheWholeImage) {
  cv::RNG rng(9);
  const std::vector<int> filters{0, 1, 2, 3, 4, 4, 1, 3, 2};
  for (int channels : {3, 4}) {
    const int w = 37, h = 23;
    std::vector<Bytes> rows(h, Bytes(std::size_t(w) * channels));
    for (auto& r : rows)
      for (auto& v : r) v = static_cast<unsigned char>(rng.uniform(0, 256));
    const int type = channels == 4 ? 6 : 2;
    const Bytes one_idat = make_png(w, h, 8, type, rows, {}, {}, filters, channels);
    const RgbaImage want = decode_png(one_idat, "one.png");
    // The same stream in IDAT chunks of 1, 2 and the rest of its bytes.
    const std::size_t at = 8 + 25, len = test::be32(&one_idat[at]);
    const Bytes z(one_idat.begin() + at + 8, one_idat.begin() + at + 8 + long(len));
    Bytes split(one_idat.begin(), one_idat.begin() + long(at));
    test::put_chunk(split, "IDAT", Bytes(z.begin(), z.begin() + 1));
    test::put_chunk(split, "IDAT", Bytes(z.begin() + 1, z.begin() + 3));
    test::put_chunk(split, "IDAT", Bytes(z.begin() + 3, z.end()));
    test::put_chunk(split, "IEND", {});
    for (const Bytes* png : {&one_idat, static_cast<const Bytes*>(&split)}) {
      for (std::uint32_t band : {1u, 2u, 5u, 23u}) {
        std::optional<PngRows> reader = PngRows::open(*png, "rows.png");
        ASSERT_TRUE(reader);
        Bytes buf(reader->band_bytes(band));
        for (std::uint32_t y = 0; y < std::uint32_t(h); y += band) {
          const std::uint32_t n = std::min(band, std::uint32_t(h) - y);
          reader->read(buf.data(), n);
          ASSERT_EQ(std::memcmp(buf.data(), want.view().row(int(y)), std::size_t(n) * w * 4), 0)
              << channels << " channels, band " << band << ", rows from " << y;
        }
      }
    }
  }
}

// Image data larger than the fast reader's input slices, in one chunk, in libpng's 8 KB
// chunks (joined a slice at a time) and in a mix: every layout decodes as libspng decodes
// it, and a bad CRC anywhere in the image data is reported as such, even behind a zlib
// error that inflate meets first.
TEST(PngRows, ImageDataInChunksOfAnySizeHasEveryCrcChecked) {
  cv::RNG rng(13);
  const std::uint32_t w = 300, h = 400;  // noise: about 480 KB compressed
  std::vector<Bytes> rows(h, Bytes(std::size_t{w} * 4));
  for (auto& r : rows)
    for (auto& v : r) v = static_cast<unsigned char>(rng.uniform(0, 256));
  const Bytes one = make_png(w, h, 8, 6, rows, {}, {}, {0, 1, 2, 3, 4}, 4);
  const std::size_t at = 8 + 25, len = test::be32(&one[at]);
  const Bytes z(one.begin() + at + 8, one.begin() + at + 8 + long(len));
  const RgbaImage want = decode_png_general(one, "one.png");
  // The stream cut at `cuts`; where each chunk's data begins in the file, and its length.
  struct Split {
    Bytes png;
    std::vector<std::pair<std::size_t, std::size_t>> chunks;
  };
  auto split = [&](const std::vector<std::size_t>& cuts) {
    Split out{Bytes(one.begin(), one.begin() + long(at)), {}};
    std::size_t from = 0;
    for (std::size_t i = 0; i <= cuts.size(); ++i) {
      const std::size_t to = i < cuts.size() ? cuts[i] : z.size();
      out.chunks.emplace_back(out.png.size() + 8, to - from);
      test::put_chunk(out.png, "IDAT", Bytes(z.begin() + long(from), z.begin() + long(to)));
      from = to;
    }
    test::put_chunk(out.png, "IEND", {});
    return out;
  };
  std::vector<std::size_t> small, mixed = {8192, 16384, 216384};
  for (std::size_t c = 8192; c < z.size(); c += 8192) small.push_back(c);
  for (std::size_t c = 224576; c < z.size(); c += 8192) mixed.push_back(c);
  for (const auto& cuts : {std::vector<std::size_t>{}, small, mixed}) {
    const Split s = split(cuts);
    const std::string what = std::to_string(s.chunks.size()) + " chunks";
    const RgbaImage got = decode_png(s.png, "split.png");
    ASSERT_EQ(std::memcmp(got.data(), want.data(), want.view().bytes()), 0) << what;
    EXPECT_EQ(check_png(s.png, "split.png").width, int(w)) << what;
    Bytes bad_crc = s.png, behind_zlib_error = s.png;
    bad_crc[s.chunks[s.chunks.size() / 2].first + 100] ^= 1;
    // A reserved block type in the first chunk, under a good CRC; a bad CRC in the last.
    const auto [first, first_len] = s.chunks.front();
    behind_zlib_error[first + 2] |= 6;
    const auto crc = static_cast<std::uint32_t>(
        crc32(0, &behind_zlib_error[first - 4], static_cast<uInt>(first_len + 4)));
    for (int i = 0; i < 4; ++i) {
      behind_zlib_error[first + first_len + std::size_t(i)] =
          static_cast<unsigned char>(crc >> (24 - 8 * i));
    }
    behind_zlib_error[s.chunks.back().first + 100] ^= 1;
    for (const Bytes* bad : {&bad_crc, &behind_zlib_error}) {
      for (const bool full : {true, false}) {
        try {
          if (full) {
            decode_png(*bad, "bad.png");
          } else {
            check_png(*bad, "bad.png");
          }
          ADD_FAILURE() << what << ": no error";
        } catch (const FileError& e) {
          EXPECT_NE(std::string(e.what()).find("IDAT chunk CRC mismatch"), std::string::npos)
              << what << ": " << e.what();
        }
      }
    }
  }
}

TEST(DecodePng, CorruptImageDataInTheFastPathIsAnError) {
  const Bytes good = make_png(8, 8, 8, 6, std::vector<Bytes>(8, Bytes(32, 200)));
  Bytes bad_crc = good;
  bad_crc[40] ^= 0x55;  // inside IDAT: its CRC no longer matches
  EXPECT_THROW(decode_png_rgba8(bad_crc, "x.png"), FileError);
  // a row with filter type 9
  std::vector<Bytes> rows(2, Bytes(8, 1));
  EXPECT_THROW(decode_png_rgba8(make_png(2, 2, 8, 6, rows, {}, {}, {9}, 4), "x.png"), FileError);
}

// Both decode_png and check_png must refuse it with the same kind of message.
void expect_error(const Bytes& png, const std::string& fragment) {
  for (const bool full : {true, false}) {
    try {
      if (full) {
        decode_png(png, "bad.png");
      } else {
        check_png(png, "bad.png");
      }
      ADD_FAILURE() << "no error for " << fragment << (full ? " (decode)" : " (check)");
    } catch (const FileError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("bad.png"), std::string::npos) << what;
      EXPECT_NE(what.find(fragment), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << "one line: " << what;
    }
  }
}

TEST(DecodePng, RejectsBadInputWithOneLineNamingTheFile) {
  expect_error({'h', 'e', 'l', 'l', 'o'}, "not a PNG");
  expect_error({}, "not a PNG");
  const Bytes good = make_png(4, 4, 8, 2, std::vector<Bytes>(4, Bytes(12, 7)));
  expect_error(Bytes(good.begin(), good.begin() + static_cast<long>(good.size()) / 2), "corrupt");
  expect_error(Bytes(good.begin(), good.begin() + 20), "header");
  // a header claiming 100000 x 100000 pixels, refused before any allocation
  expect_error(make_png(100000, 100000, 8, 6, {}), "larger than");
  expect_error(make_png(20000, 20000, 8, 6, {}), "larger than");
  // a valid header whose data is missing
  expect_error(make_png(4, 4, 8, 2, {}), "corrupt");
  // the fast path's own checks: CRC, zlib stream, row filter
  Bytes bad_crc = make_png(8, 8, 8, 6, std::vector<Bytes>(8, Bytes(32, 200)));
  bad_crc[40] ^= 0x55;
  expect_error(bad_crc, "CRC");
  expect_error(make_png(2, 2, 8, 6, std::vector<Bytes>(2, Bytes(8, 1)), {}, {}, {9}, 4), "filter");
}

// A corrupt file's chunk type may be any four bytes, a terminal's escape sequence too: messages
// quote it escaped (found by fuzz/png_decode_fuzz.cpp).
TEST(DecodePng, ChunkTypesAreQuotedEscaped) {
  const Bytes good = make_png(1, 1, 8, 6, {Bytes(4, 9)});
  Bytes odd(good.begin(), good.end() - 12);  // IEND is the last 12 bytes
  test::put_chunk(odd, "\x1b[2J", {});       // critical: bit 5 of its first byte is clear
  test::put_chunk(odd, "IEND", {});
  expect_error(odd, "unknown critical chunk '\\x1b[2J'");
  Bytes bad_crc = odd;
  bad_crc[bad_crc.size() - 13] ^= 1;  // the last byte of the odd chunk's CRC
  expect_error(bad_crc, "\\x1b[2J chunk CRC mismatch");
}

// An 8x8 RGBA PNG whose IDAT holds `z` under a valid CRC, so only the zlib layer is wrong.
Bytes rgba8x8_with_idat(const Bytes& z) { return test::png_with_idat(8, 8, 8, 6, z); }

TEST(DecodePng, ZlibStreamErrorsBehindValidCrcs) {
  const Bytes raw(8 * (1 + 8 * 4), 0);  // 8 rows: filter byte 0 and 32 zero samples
  EXPECT_EQ(decode_png(rgba8x8_with_idat(test::zlib_compress(raw)), "ok.png").width(), 8);
  Bytes bad_adler = test::zlib_compress(raw);
  bad_adler.back() ^= 1;
  expect_error(rgba8x8_with_idat(bad_adler), "corrupt");
  expect_error(rgba8x8_with_idat(test::zlib_compress(Bytes(raw.begin(), raw.end() - 33))),
               "corrupt");
  Bytes longer = raw;
  longer.resize(raw.size() + 33, 0);
  expect_error(rgba8x8_with_idat(test::zlib_compress(longer)), "corrupt");
  Bytes bad_header = test::zlib_compress(raw);
  bad_header[0] = 0x79;  // compression method 9
  expect_error(rgba8x8_with_idat(bad_header), "corrupt");
  Bytes big_window = test::zlib_compress(raw);
  big_window[0] = 0x88, big_window[1] = 0x1c;  // CINFO 8 (a 64 KB window), FCHECK still valid
  expect_error(rgba8x8_with_idat(big_window), "corrupt");
  // every row there but the stream never ends: flushed, no final block, no checksum
  expect_error(rgba8x8_with_idat(test::zlib_compress(raw, Z_SYNC_FLUSH)), "corrupt");
}

TEST(DecodePng, CheckGivesTheSizeOfWhatDecodes) {
  const std::vector<Bytes> pngs = {
      make_png(5, 3, 8, 6, std::vector<Bytes>(3, Bytes(20, 9)), {}, {}, {0, 1, 2, 3, 4}, 4),
      make_png(7, 2, 8, 2, std::vector<Bytes>(2, Bytes(21, 9))),
      make_png(1, 1, 8, 0, {{77}}),  // libspng's path
      make_png(1, 1, 8, 3, {{1}}, {10, 20, 30, 40, 50, 60}, {255, 99}),
  };
  for (const Bytes& png : pngs) {
    const RgbaImage img = decode_png(png, "x.png");
    const ImageSize size = check_png(png, "x.png");
    EXPECT_EQ(size.width, img.width());
    EXPECT_EQ(size.height, img.height());
  }
}

TEST(FileIo, MissingFilesAndDirectoriesAreClearErrors) {
  test::TempDir dir;
  EXPECT_THROW(read_png_rgba8(dir / "missing.png"), FileError);
  try {
    read_png_rgba8(dir.path());
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("is a directory"), std::string::npos);
  }
}

TEST(FileIo, PngRoundTripsAndWritesAtomically) {
  test::TempDir dir;
  cv::Mat img(3, 5, CV_8UC4);
  cv::randu(img, 0, 256);
  write_png_rgba8(dir / "x.png", img);
  const cv::Mat back = read_png_rgba8(dir / "x.png");
  EXPECT_EQ(cv::norm(img, back, cv::NORM_INF), 0);
  // only the final file remains: no temporary beside it
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 1);
  EXPECT_THROW(write_png_rgba8(dir / "no" / "such" / "dir.png", img), FileError);
  EXPECT_FALSE(std::filesystem::exists(dir / "no"));
}

TEST(FileIo, FailedWriteKeepsTheOldFile) {
  test::TempDir dir;
  test::write_bytes(dir / "keep.png", {1, 2, 3});
  std::filesystem::permissions(
      dir.path(), std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
  cv::Mat img(2, 2, CV_8UC4, cv::Scalar::all(9));
  if (::geteuid() != 0) {  // root ignores directory permissions
    EXPECT_THROW(write_png_rgba8(dir / "keep.png", img), FileError);
  }
  std::filesystem::permissions(dir.path(), std::filesystem::perms::owner_all);
  EXPECT_EQ(read_file(dir / "keep.png"), (Bytes{1, 2, 3}));
}

}  // namespace
}  // namespace aosuite
