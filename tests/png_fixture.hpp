// Hand-built PNG files for decoder tests: any colour type and bit depth, a lying header, a
// truncated stream. Written with zlib directly so the fixtures do not depend on our encoder.
#pragma once

#include <zlib.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace aosuite::test {

using Bytes = std::vector<unsigned char>;

inline void put_u32(Bytes& out, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<unsigned char>(v >> s));
}

inline void put_chunk(Bytes& out, const char* type, const Bytes& data) {
  put_u32(out, static_cast<std::uint32_t>(data.size()));
  Bytes body(type, type + 4);
  body.insert(body.end(), data.begin(), data.end());
  out.insert(out.end(), body.begin(), body.end());
  put_u32(out, static_cast<std::uint32_t>(crc32(0, body.data(), static_cast<uInt>(body.size()))));
}

inline int paeth_predictor(int a, int b, int c) {
  const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  return (pa <= pb && pa <= pc) ? a : (pb <= pc ? b : c);
}

// Applies PNG filter `type` (0-4) to `row` given the previous unfiltered row (or zeros).
inline Bytes filter_row(int type, const Bytes& row, const Bytes& prev, int bpp) {
  Bytes out(row.size());
  for (std::size_t i = 0; i < row.size(); ++i) {
    const int a = i >= std::size_t(bpp) ? row[i - bpp] : 0, b = prev.empty() ? 0 : prev[i];
    const int c = i >= std::size_t(bpp) && !prev.empty() ? prev[i - bpp] : 0;
    const int pred = type == 1   ? a
                     : type == 2 ? b
                     : type == 3 ? (a + b) / 2
                     : type == 4 ? paeth_predictor(a, b, c)
                                 : 0;
    out[i] = static_cast<unsigned char>(row[i] - pred);
  }
  return out;
}

inline std::uint32_t be32(const unsigned char* p) {
  return std::uint32_t{p[0]} << 24 | std::uint32_t{p[1]} << 16 | std::uint32_t{p[2]} << 8 | p[3];
}

// A zlib stream of `raw`; with flush = Z_SYNC_FLUSH it is left unfinished (no final block,
// no Adler-32), as a writer that stopped early leaves it.
inline Bytes zlib_compress(const Bytes& raw, int flush = Z_FINISH) {
  z_stream zs{};
  deflateInit(&zs, Z_DEFAULT_COMPRESSION);
  Bytes z(deflateBound(&zs, static_cast<uLong>(raw.size())) + 16);
  zs.next_in = const_cast<unsigned char*>(raw.data());
  zs.avail_in = static_cast<uInt>(raw.size());
  zs.next_out = z.data();
  zs.avail_out = static_cast<uInt>(z.size());
  deflate(&zs, flush);
  z.resize(zs.total_out);
  deflateEnd(&zs);
  return z;
}

// A PNG of the given header whose IDAT holds `z` as is (none when empty), under valid CRCs.
inline Bytes png_with_idat(std::uint32_t w, std::uint32_t h, int bit_depth, int color_type,
                           const Bytes& z, const Bytes& plte = {}, const Bytes& trns = {}) {
  Bytes out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  Bytes ihdr;
  put_u32(ihdr, w);
  put_u32(ihdr, h);
  ihdr.insert(ihdr.end(), {static_cast<unsigned char>(bit_depth),
                           static_cast<unsigned char>(color_type), 0, 0, 0});
  put_chunk(out, "IHDR", ihdr);
  if (!plte.empty()) put_chunk(out, "PLTE", plte);
  if (!trns.empty()) put_chunk(out, "tRNS", trns);
  if (!z.empty()) put_chunk(out, "IDAT", z);
  put_chunk(out, "IEND", {});
  return out;
}

// `rows` holds the raw samples of each row (no filter byte). Row y is written with filter
// `filters[y % filters.size()]` (bpp = bytes per pixel, for the filters that need it).
inline Bytes make_png(std::uint32_t w, std::uint32_t h, int bit_depth, int color_type,
                      const std::vector<Bytes>& rows, const Bytes& plte = {},
                      const Bytes& trns = {}, const std::vector<int>& filters = {0}, int bpp = 1) {
  Bytes raw;
  for (std::size_t y = 0; y < rows.size(); ++y) {
    const int f = filters[y % filters.size()];
    raw.push_back(static_cast<unsigned char>(f));
    const Bytes filtered = filter_row(f, rows[y], y ? rows[y - 1] : Bytes{}, bpp);
    raw.insert(raw.end(), filtered.begin(), filtered.end());
  }
  return png_with_idat(w, h, bit_depth, color_type, rows.empty() ? Bytes{} : zlib_compress(raw),
                       plte, trns);
}

inline void write_bytes(const std::filesystem::path& p, const Bytes& b) {
  std::ofstream(p, std::ios::binary)
      .write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

// A fresh empty directory under the system temp dir, removed at scope exit.
class TempDir {
 public:
  TempDir() {
    std::string tmpl = (std::filesystem::temp_directory_path() / "aosuite-test-XXXXXX").string();
    path_ = mkdtemp(tmpl.data());
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

}  // namespace aosuite::test
