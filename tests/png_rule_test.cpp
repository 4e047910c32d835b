// One PNG validity rule (image/png_layout.hpp): the fast decoder, libspng's path, the
// check without pixels and the band reader accept and refuse the same files, and agree on
// the pixels of those they accept. Every colour type, bit depth and interlace, each with
// the corruptions found in the wild and a few harmless oddities.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <random>

#include "compare/band_compare.hpp"
#include "image/image_io.hpp"
#include "image/png_fast.hpp"
#include "png_fixture.hpp"

namespace aosuite {
namespace {

using test::Bytes;

struct Kind {
  int colour, depth;
};

int channels(int colour) { return colour == 2 ? 3 : colour == 4 ? 2 : colour == 6 ? 4 : 1; }

// Samples packed into a row of bytes (big-endian for 16 bits, high bits first below 8).
Bytes pack_row(const std::vector<int>& samples, int depth) {
  Bytes out;
  if (depth == 16) {
    for (int s : samples)
      out.push_back(static_cast<unsigned char>(s >> 8)),
          out.push_back(static_cast<unsigned char>(s & 255));
    return out;
  }
  if (depth == 8) return Bytes(samples.begin(), samples.end());
  int acc = 0, bits = 0;
  for (int s : samples) {
    acc = acc << depth | s, bits += depth;
    if (bits == 8) out.push_back(static_cast<unsigned char>(acc)), acc = 0, bits = 0;
  }
  if (bits) out.push_back(static_cast<unsigned char>(acc << (8 - bits)));
  return out;
}

// The filtered rows (filter byte first) of a w x h image of random samples, plain or in
// Adam7's seven passes, with `extra` more bytes after the last row.
Bytes raw_image(std::mt19937& rng, std::uint32_t w, std::uint32_t h, Kind k, bool interlace,
                std::size_t extra = 0) {
  const int ch = channels(k.colour);
  const int max = k.colour == 3 ? std::min(3, (1 << k.depth) - 1) : (1 << k.depth) - 1;
  std::uniform_int_distribution<int> sample(0, max);
  std::vector<std::vector<int>> px(h, std::vector<int>(std::size_t(w) * ch));
  for (auto& row : px)
    for (auto& s : row) s = sample(rng);
  const int bpp = std::max(1, ch * k.depth / 8);
  Bytes raw;
  auto emit = [&](const std::vector<std::vector<int>>& rows) {
    Bytes prev;
    for (std::size_t y = 0; y < rows.size(); ++y) {
      const Bytes packed = pack_row(rows[y], k.depth);
      const int filter = static_cast<int>(y % 5);
      raw.push_back(static_cast<unsigned char>(filter));
      const Bytes f = test::filter_row(filter, packed, prev, bpp);
      raw.insert(raw.end(), f.begin(), f.end());
      prev = packed;
    }
  };
  if (!interlace) {
    emit(px);
  } else {
    const int x0[7] = {0, 4, 0, 2, 0, 1, 0}, y0[7] = {0, 0, 4, 0, 2, 0, 1};
    const int dx[7] = {8, 8, 4, 4, 2, 2, 1}, dy[7] = {8, 8, 8, 4, 4, 2, 2};
    for (int p = 0; p < 7; ++p) {
      std::vector<std::vector<int>> rows;
      for (std::uint32_t y = y0[p]; y < h; y += dy[p]) {
        std::vector<int> row;
        for (std::uint32_t x = x0[p]; x < w; x += dx[p]) {
          for (int c = 0; c < ch; ++c) row.push_back(px[y][std::size_t(x) * ch + c]);
        }
        if (!row.empty()) rows.push_back(row);
      }
      emit(rows);
    }
  }
  for (std::size_t i = 0; i < extra; ++i) raw.push_back(0);
  return raw;
}

// A PNG from its parts: chunks are listed as (type, data) and written with valid CRCs.
struct Chunk {
  std::string type;
  Bytes data;
};

Bytes assemble(const std::vector<Chunk>& chunks) {
  Bytes out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  for (const Chunk& c : chunks) test::put_chunk(out, c.type.c_str(), c.data);
  return out;
}

Bytes ihdr(std::uint32_t w, std::uint32_t h, Kind k, bool interlace, int method = 0,
           int filter_method = 0) {
  Bytes d;
  test::put_u32(d, w);
  test::put_u32(d, h);
  d.insert(d.end(), {static_cast<unsigned char>(k.depth), static_cast<unsigned char>(k.colour),
                     static_cast<unsigned char>(method), static_cast<unsigned char>(filter_method),
                     static_cast<unsigned char>(interlace)});
  return d;
}

// The chunks of a valid file: IHDR, PLTE for palette images, the stream in three IDATs, IEND.
std::vector<Chunk> chunks_of(std::uint32_t w, std::uint32_t h, Kind k, bool interlace,
                             const Bytes& z) {
  std::vector<Chunk> c = {{"IHDR", ihdr(w, h, k, interlace)}};
  if (k.colour == 3) {  // 2 entries for 1-bit images, 4 for the rest (samples are 0..3)
    Bytes plte = {10, 20, 30, 40, 50, 60, 70, 80, 90, 100, 110, 120};
    plte.resize(k.depth == 1 ? 6 : 12);
    c.push_back({"PLTE", plte});
  }
  const std::size_t a = z.size() / 3, b = 2 * z.size() / 3;
  c.push_back({"IDAT", Bytes(z.begin(), z.begin() + long(a))});
  c.push_back({"IDAT", Bytes(z.begin() + long(a), z.begin() + long(b))});
  c.push_back({"IDAT", Bytes(z.begin() + long(b), z.end())});
  c.push_back({"IEND", {}});
  return c;
}

std::size_t index_of(const std::vector<Chunk>& c, const char* type, bool last = false) {
  std::size_t found = c.size();
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (c[i].type == type) {
      found = i;
      if (!last) break;
    }
  }
  return found;
}

struct Variant {
  std::string what;
  Bytes png;
  bool valid;
};

std::vector<Variant> variants(std::mt19937& rng, std::uint32_t w, std::uint32_t h, Kind k,
                              bool interlace) {
  const Bytes raw = raw_image(rng, w, h, k, interlace);
  const Bytes z = test::zlib_compress(raw);
  const std::vector<Chunk> base = chunks_of(w, h, k, interlace, z);
  const Bytes good = assemble(base);
  std::vector<Variant> out = {{"valid", good, true}};
  auto with = [&](const std::string& what, bool valid,
                  const std::function<void(std::vector<Chunk>&)>& f) {
    std::vector<Chunk> c = base;
    f(c);
    out.push_back({what, assemble(c), valid});
  };
  const std::size_t first_idat = index_of(base, "IDAT"), last_idat = index_of(base, "IDAT", true);
  // Harmless: ancillary chunks anywhere (unknown ones, bad CRCs are not checked), bytes
  // after IEND, an empty IDAT.
  with("text before the data", true, [&](auto& c) {
    c.insert(c.begin() + long(first_idat), {"tEXt", {'a', 0, 'b'}});
  });
  with("ancillary after the data", true, [&](auto& c) {
    c.insert(c.end() - 1, {"zzZz", {1, 2, 3}});
  });
  with("empty IDAT", true, [&](auto& c) { c.insert(c.begin() + long(last_idat), {"IDAT", {}}); });
  {
    Bytes v = good;
    v.insert(v.end(), {1, 2, 3, 4, 5});
    out.push_back({"bytes after IEND", v, true});
  }
  // Truncations.
  for (const std::size_t cut : {1, 4, 8, 12, 13, 16, 20, 30}) {
    if (cut < good.size() - 40) {
      out.push_back({"last " + std::to_string(cut) + " bytes cut",
                     Bytes(good.begin(), good.end() - long(cut)), false});
    }
  }
  for (const std::size_t keep : {std::size_t{33}, std::size_t{40}, good.size() / 2}) {
    out.push_back({"cut to " + std::to_string(keep) + " bytes",
                   Bytes(good.begin(), good.begin() + long(keep)), false});
  }
  with("no IEND", false, [&](auto& c) { c.pop_back(); });
  {
    Bytes v = good;
    v[v.size() - 12 - 1] ^= 0x40;  // the last IDAT's CRC
    out.push_back({"bad CRC on the last IDAT", v, false});
  }
  with("compression method 1", false, [&](auto& c) { c[0].data[10] = 1; });
  with("filter method 1", false, [&](auto& c) { c[0].data[11] = 1; });
  with("second IHDR", false, [&](auto& c) { c.insert(c.begin() + long(first_idat), c[0]); });
  with("unknown critical chunk before the data", false, [&](auto& c) {
    c.insert(c.begin() + long(first_idat), {"ABCD", {1, 2}});
  });
  with("unknown critical chunk after the data", false, [&](auto& c) {
    c.insert(c.end() - 1, {"ABCD", {1, 2}});
  });
  with("IDATs not consecutive", false, [&](auto& c) {
    c.insert(c.begin() + long(first_idat) + 1, {"tEXt", {'a', 0, 'b'}});
  });
  with("IEND not empty", false, [&](auto& c) { c.back().data = {0}; });
  with("no IDAT", false, [&](auto& c) { c.erase(c.begin() + long(first_idat), c.end() - 1); });
  auto with_stream = [&](const std::string& what, const Bytes& stream) {
    std::vector<Chunk> c = chunks_of(w, h, k, interlace, stream);
    out.push_back({what, assemble(c), false});
  };
  std::mt19937 same = rng;  // the same pixels again, with more bytes after the last row
  with_stream("data after the last row",
              test::zlib_compress(raw_image(same, w, h, k, interlace, 7)));
  with_stream("last row short", test::zlib_compress(Bytes(raw.begin(), raw.end() - 1)));
  with_stream("stream never ends", test::zlib_compress(raw, Z_SYNC_FLUSH));
  Bytes bad_adler = z;
  bad_adler.back() ^= 1;
  with_stream("bad Adler-32", bad_adler);
  return out;
}

enum class Verdict { kOk, kError };

template <typename F>
Verdict verdict(F f, std::string& message) {
  try {
    f();
    return Verdict::kOk;
  } catch (const FileError& e) {
    message = e.what();
    return Verdict::kError;
  }
}

TEST(PngRule, BothDecodersAcceptAndRefuseTheSameFiles) {
  std::mt19937 rng(3);
  const std::vector<Kind> kinds = {{0, 1}, {0, 2}, {0, 4}, {0, 8}, {0, 16}, {2, 8}, {2, 16}, {3, 1},
                                   {3, 2}, {3, 4}, {3, 8}, {4, 8}, {4, 16}, {6, 8}, {6, 16}};
  int checked = 0;
  for (const Kind k : kinds) {
    for (const bool interlace : {false, true}) {
      const std::uint32_t w = 13, h = 11;
      for (const Variant& v : variants(rng, w, h, k, interlace)) {
        const std::string what = "colour " + std::to_string(k.colour) + ", depth " +
                                 std::to_string(k.depth) + (interlace ? ", interlaced" : "") +
                                 ": " + v.what;
        std::string m_fast, m_general, m_check;
        RgbaImage fast, general;
        const Verdict by_fast = verdict([&] { fast = decode_png(v.png, "v.png"); }, m_fast);
        const Verdict by_general =
            verdict([&] { general = decode_png_general(v.png, "v.png"); }, m_general);
        const Verdict by_check = verdict([&] { check_png(v.png, "v.png"); }, m_check);
        EXPECT_EQ(by_fast, v.valid ? Verdict::kOk : Verdict::kError) << what << ": " << m_fast;
        EXPECT_EQ(by_general, by_fast) << what << ": " << m_general;
        EXPECT_EQ(by_check, by_fast) << what << ": " << m_check;
        for (const std::string* m : {&m_fast, &m_general, &m_check}) {
          if (m->empty()) continue;
          EXPECT_NE(m->find("v.png"), std::string::npos) << what << ": " << *m;
          EXPECT_EQ(m->find('\n'), std::string::npos) << what << ": " << *m;
        }
        if (by_fast == Verdict::kOk && by_general == Verdict::kOk) {
          ASSERT_EQ(fast.width(), general.width()) << what;
          ASSERT_EQ(fast.height(), general.height()) << what;
          EXPECT_EQ(std::memcmp(fast.data(), general.data(), fast.view().bytes()), 0) << what;
        }
        // The band reader takes 8-bit RGB and RGBA; the same verdict when it reads the file.
        if (k.depth == 8 && (k.colour == 2 || k.colour == 6) && !interlace) {
          std::string m_bands;
          const Verdict by_bands = verdict(
              [&] { compare_png_bands(v.png, "v.png", v.png, "v.png", resemble::Options{}); },
              m_bands);
          EXPECT_EQ(by_bands, by_fast) << what << " (bands): " << m_bands;
        }
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 800);
}

// A small file whose header claims a huge image is refused from its size alone, before any
// pixel memory: it cannot inflate to that many bytes.
TEST(PngRule, TooLittleDataForTheImageIsRefusedBeforeDecoding) {
  const Bytes raw(100, 0);
  for (const Kind k : {Kind{6, 8}, Kind{0, 8}, Kind{2, 16}}) {
    const Bytes png =
        test::png_with_idat(16384, 16384, k.depth, k.colour, test::zlib_compress(raw));
    for (const bool general : {false, true}) {
      try {
        if (general) {
          decode_png_general(png, "claims.png");
        } else {
          decode_png(png, "claims.png");
        }
        ADD_FAILURE() << "accepted";
      } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find("cannot fill 16384x16384"), std::string::npos)
            << e.what();
      }
    }
  }
}

}  // namespace
}  // namespace aosuite
