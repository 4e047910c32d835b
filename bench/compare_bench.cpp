// Comparator kernels per mode at 1080p and 4K, PNG decode, two PNG files compared whole or
// in bands, and the floors they are measured against: one read of both images (memory
// bandwidth) for the kernel, both files inflated and unfiltered for the band comparison.
//
// `--pair=A.png,B.png` (repeatable) also runs the band comparison and its floors on those
// files, e.g. peers-bench's pairs, so a whole `aosuite compare` can be held to the floor.
#include <benchmark/benchmark.h>
#include <isa-l/igzip_lib.h>
#include <sys/mman.h>

#include <atomic>
#include <cstring>
#include <opencv2/core/utility.hpp>
#include <string_view>

#include "common/thread_beside.hpp"
#include "compare/band_compare.hpp"
#include "compare/count_kernel.hpp"
#include "compare/opencv.hpp"
#include "compare/parallel_rows.hpp"
#include "image/inflate.hpp"
#include "image/png_fast.hpp"
#include "image/png_layout.hpp"
#include "image/png_unfilter.hpp"

namespace {

using aosuite::resemble::Mode;

// An AO-like pair: smooth shading plus noise; the second is 1.5 % darker with a few blobs,
// so every pixel differs a little (the hard case for a tolerance), as peers-bench's `ao` pair.
std::pair<cv::Mat, cv::Mat> make_pair(int w, int h) {
  cv::Mat a(h, w, CV_8UC4), noise(h, w, CV_8UC4);
  cv::randu(noise, 0, 8);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const auto v = static_cast<uchar>(60 + 150 * x / w + 30 * y / h);
      a.at<cv::Vec4b>(y, x) =
          cv::Vec4b(v, static_cast<uchar>(v * 0.9), static_cast<uchar>(v * 0.8), 255);
    }
  }
  a += noise;
  a.forEach<cv::Vec4b>([](cv::Vec4b& p, const int*) { p[3] = 255; });
  cv::Mat b = a * 0.985;
  b.forEach<cv::Vec4b>([](cv::Vec4b& p, const int*) { p[3] = 255; });
  for (int k = 0; k < 200; ++k) {
    cv::Mat roi = b(cv::Rect((k * 7919) % (w - 20), (k * 104729) % (h - 20), 12, 12));
    roi.setTo(cv::Scalar(255, 0, 0, 255));
  }
  return {a, b};
}

const std::pair<cv::Mat, cv::Mat>& pair_for(int height) {
  static const auto p1080 = make_pair(1920, 1080);
  static const auto p2160 = make_pair(3840, 2160);
  return height == 1080 ? p1080 : p2160;
}

void set_pixels(benchmark::State& state, const cv::Mat& m) {
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * m.rows * m.cols);
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * m.rows * m.cols * 8);
}

void BM_Compare(benchmark::State& state, Mode mode, bool diff) {
  const auto& [a, b] = pair_for(static_cast<int>(state.range(0)));
  aosuite::resemble::Options o;
  o.modes = {mode};
  o.produce_diff = diff;
  for (auto _ : state) benchmark::DoNotOptimize(aosuite::resemble::compare(a, b, o));
  set_pixels(state, a);
}

// The floor: read both images once with the same threads the comparator uses, doing the
// least work that still touches every byte (an XOR folded into one word per stripe).
void BM_ReadBothBaseline(benchmark::State& state) {
  const auto& [a, b] = pair_for(static_cast<int>(state.range(0)));
  const auto* pa = reinterpret_cast<const std::uint64_t*>(a.data);
  const auto* pb = reinterpret_cast<const std::uint64_t*>(b.data);
  const int rows = a.rows;
  const std::size_t row_words = std::size_t(a.cols) / 2;
  for (auto _ : state) {
    std::atomic<std::uint64_t> total{0};
    aosuite::parallel_rows(a.cols, rows, [&](int y0, int y1) {
      std::uint64_t acc = 0;
      for (std::size_t i = std::size_t(y0) * row_words; i < std::size_t(y1) * row_words; ++i)
        acc |= pa[i] ^ pb[i];
      total |= acc;
    });
    benchmark::DoNotOptimize(total.load());
  }
  set_pixels(state, a);
}

void BM_CountScalarReference(benchmark::State& state) {
  const auto& [a, b] = pair_for(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        aosuite::count_mismatches_scalar(a.data, b.data, a.cols, a.rows, {16, 16, 16, 16}));
  }
  set_pixels(state, a);
}

using PngPair = std::array<std::vector<unsigned char>, 2>;

const PngPair& png_pair_for(int height) {
  static const auto encode = [](int h) {
    const auto& [a, b] = pair_for(h);
    return PngPair{aosuite::encode_png_rgba8(a, 6), aosuite::encode_png_rgba8(b, 6)};
  };
  static const PngPair p1080 = encode(1080), p2160 = encode(2160);
  return height == 1080 ? p1080 : p2160;
}

void BM_DecodePng(benchmark::State& state) {
  const auto& a = pair_for(static_cast<int>(state.range(0))).first;
  const std::vector<unsigned char> png = aosuite::encode_png_rgba8(a, 6);
  for (auto _ : state) benchmark::DoNotOptimize(aosuite::decode_png_rgba8(png, "bench"));
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * a.rows * a.cols);
}

// `aosuite compare A B` without its process: both PNGs decoded whole (on two threads) and
// compared, against compare_png_bands counting them a band at a time. The whole path also
// pays the kernel's zeroing of 2 x 33 MB of fresh pages at 4K every iteration, as a process
// does once.
void BM_ComparePngFiles(benchmark::State& state, bool bands) {
  const auto& pngs = png_pair_for(static_cast<int>(state.range(0)));
  const auto& pa = pngs[0];  // named references: clang 14 cannot capture a binding
  const auto& pb = pngs[1];
  aosuite::resemble::Options o;
  o.modes = {Mode::kLess};
  for (auto _ : state) {
    if (bands) {
      benchmark::DoNotOptimize(aosuite::compare_png_bands(pa, "a", pb, "b", o));
    } else {
      aosuite::RgbaImage img_a, img_b;
      aosuite::side_by_side([&] { img_b = aosuite::decode_png(pb, "b"); },
                            [&] { img_a = aosuite::decode_png(pa, "a"); });
      benchmark::DoNotOptimize(aosuite::resemble::compare(img_a, img_b, o));
    }
  }
  const auto& a = pair_for(static_cast<int>(state.range(0))).first;
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * a.rows * a.cols);
}

// One file inflated and unfiltered a band at a time into `band`, as compare_png_bands
// reads it (chunk checks, inflate, Adler-32, row filters), its rows thrown away.
void inflate_and_unfilter(const std::vector<unsigned char>& png, unsigned char* band) {
  std::optional<aosuite::PngRows> rows = aosuite::PngRows::open(png, "floor");
  if (!rows) throw std::invalid_argument("not an 8-bit RGB(A) PNG: the band reader's kind");
  const std::uint32_t h = rows->height(), band_rows = aosuite::band_rows_for(rows->width());
  for (std::uint32_t y = 0; y < h; y += band_rows) rows->read(band, std::min(band_rows, h - y));
}

// The floor of comparing two PNG files: each inflated and unfiltered on a thread of its own
// (started every iteration, as compare_png_bands starts one), and nothing else: no shared
// ring of bands, no counting, no process. Buffers are allocated once, outside the timing.
void two_inflate_floor(benchmark::State& state, const PngPair& files) {
  const aosuite::PixelBuffer bands(std::size_t{2} << 20);
  for (auto _ : state) {
    const aosuite::ThreadBeside other(
        [&] { inflate_and_unfilter(files[1], bands.data() + (1 << 20)); });
    inflate_and_unfilter(files[0], bands.data());
  }
}

void BM_TwoInflateFloor(benchmark::State& state) {
  two_inflate_floor(state, png_pair_for(static_cast<int>(state.range(0))));
}

// The floor under the floor: the first file's zlib stream inflated in one call on one thread,
// no CRCs, no unfiltering: by the project's inflater (InflateOnly) and by ISA-L's
// (IsalInflateOnly), the one it replaced. What a whole comparison of the pair cannot beat on
// two cores without a faster inflate.
std::vector<unsigned char> zlib_stream(const std::vector<unsigned char>& png,
                                       std::size_t& out_bytes) {
  const aosuite::PngLayout layout = aosuite::walk_png(png, "inflate", false);
  std::vector<unsigned char> stream;
  for (const auto& chunk : layout.idat) stream.insert(stream.end(), chunk.begin(), chunk.end());
  out_bytes = layout.filtered_bytes();
  return stream;
}

void inflate_only(benchmark::State& state, const PngPair& files) {
  std::size_t n = 0;
  const std::vector<unsigned char> stream = zlib_stream(files[0], n);
  std::vector<unsigned char> out(n + 1);
  for (auto _ : state) {
    bool given = false;
    aosuite::Inflater inflater([&] {
      const auto piece = given ? std::span<const unsigned char>{} : std::span(stream);
      given = true;
      return piece;
    });
    if (inflater.inflate(out.data(), out.size()) != n || !inflater.ended()) {
      throw std::runtime_error("inflate failed");
    }
    benchmark::DoNotOptimize(out.data());
  }
}

void isal_inflate_only(benchmark::State& state, const PngPair& files) {
  std::size_t n = 0;
  std::vector<unsigned char> stream = zlib_stream(files[0], n), out(n);
  for (auto _ : state) {
    inflate_state s;
    isal_inflate_init(&s);
    s.crc_flag = ISAL_ZLIB;
    s.next_in = stream.data();
    s.avail_in = static_cast<std::uint32_t>(stream.size());
    s.next_out = out.data();
    s.avail_out = static_cast<std::uint32_t>(out.size());
    if (isal_inflate_stateless(&s) != ISAL_DECOMP_OK) throw std::runtime_error("inflate failed");
    benchmark::DoNotOptimize(out.data());
  }
}

// The same two on the synthetic AO-like image at each size (no --pair needed).
void BM_Inflate(benchmark::State& state, bool isal) {
  const PngPair& files = png_pair_for(static_cast<int>(state.range(0)));
  (isal ? isal_inflate_only : inflate_only)(state, files);
}

void compare_png_bands_on(benchmark::State& state, const PngPair& files) {
  aosuite::resemble::Options o;
  o.modes = {Mode::kLess};
  for (auto _ : state) {
    benchmark::DoNotOptimize(aosuite::compare_png_bands(files[0], "a", files[1], "b", o));
  }
}

// What a process pays to fault in 2 MB of fresh memory as 4 KB pages or as one huge page
// (PixelBuffer's choice): on the project's VMs each 4 KB fault costs about 10 us.
void BM_FaultIn2MB(benchmark::State& state, bool huge) {
  constexpr std::size_t kBytes = std::size_t{2} << 20;
  for (auto _ : state) {
    if (huge) {
      aosuite::PixelBuffer buffer(kBytes);  // pre-faulted, huge pages from 2 MB up
      benchmark::DoNotOptimize(buffer.data());
    } else {
      void* p = ::mmap(nullptr, kBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
      ::madvise(p, kBytes, MADV_NOHUGEPAGE);
      auto* bytes = static_cast<volatile unsigned char*>(p);
      for (std::size_t i = 0; i < kBytes; i += 4096) bytes[i] = 1;
      ::munmap(p, kBytes);
    }
  }
}

// Unfiltering a 4K RGBA band of 64 rows (filtered bytes random, so no branch is predictable)
// with every row's filter `type`, or with 5 the filter cycling through all of them; the
// widest kernels against the SSE4.1 ones. Not in place, so every iteration has the same input.
void BM_Unfilter(benchmark::State& state, aosuite::UnfilterKernels kernels) {
  constexpr std::size_t kWidth = 3840, kLen = kWidth * 4;
  constexpr std::uint32_t kRows = 64;
  const auto type = static_cast<int>(state.range(0));
  std::vector<unsigned char> raw(kRows * (kLen + 1)), out(kRows * kLen), above(kLen);
  cv::RNG rng(3);
  for (auto& v : raw) v = static_cast<unsigned char>(rng.uniform(0, 256));
  for (std::uint32_t y = 0; y < kRows; ++y) {
    raw[y * (kLen + 1)] = static_cast<unsigned char>(type == 5 ? y % 5 : type);
  }
  for (auto _ : state) {
    aosuite::unfilter_rows(raw.data(), out.data(), above.data(), kLen, 4, kRows, kernels);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * kRows * kWidth);
}

void BM_EncodeDiffPng(benchmark::State& state) {
  const auto& a = pair_for(static_cast<int>(state.range(0))).first;
  for (auto _ : state) benchmark::DoNotOptimize(aosuite::encode_png_rgba8(a, 3));
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * a.rows * a.cols);
}

#define SIZES Arg(1080)->Arg(2160)->Unit(benchmark::kMillisecond)->UseRealTime()
BENCHMARK(BM_ReadBothBaseline)->SIZES;
BENCHMARK_CAPTURE(BM_Compare, less, Mode::kLess, false)->SIZES;
BENCHMARK_CAPTURE(BM_Compare, nothing, Mode::kNothing, false)->SIZES;
BENCHMARK_CAPTURE(BM_Compare, alpha, Mode::kAlpha, false)->SIZES;
BENCHMARK_CAPTURE(BM_Compare, colors, Mode::kColors, false)->SIZES;
BENCHMARK_CAPTURE(BM_Compare, antialiasing, Mode::kAntialiasing, false)->SIZES;
BENCHMARK_CAPTURE(BM_Compare, less_with_diff, Mode::kLess, true)->SIZES;
BENCHMARK(BM_CountScalarReference)->SIZES;
BENCHMARK(BM_DecodePng)->SIZES;
BENCHMARK_CAPTURE(BM_ComparePngFiles, whole, false)->SIZES;
BENCHMARK_CAPTURE(BM_ComparePngFiles, bands, true)->SIZES;
BENCHMARK(BM_TwoInflateFloor)->SIZES;
BENCHMARK_CAPTURE(BM_Inflate, ours, false)->SIZES;
BENCHMARK_CAPTURE(BM_Inflate, isal, true)->SIZES;
BENCHMARK(BM_EncodeDiffPng)->SIZES;
BENCHMARK_CAPTURE(BM_Unfilter, best, aosuite::UnfilterKernels::kBest)->DenseRange(1, 5);
BENCHMARK_CAPTURE(BM_Unfilter, sse41, aosuite::UnfilterKernels::kSse41)->DenseRange(1, 5);
BENCHMARK_CAPTURE(BM_FaultIn2MB, small_pages, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_FaultIn2MB, huge_page, true)->Unit(benchmark::kMillisecond);

// Registers the floor and the band comparison for each --pair=A,B, and removes those flags.
void register_file_pairs(int& argc, char** argv) {
  static std::vector<PngPair> pairs;  // registered benchmarks keep references into it
  static constexpr std::string_view kFlag = "--pair=";
  std::vector<std::string> names;
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    const std::size_t comma = arg.find(',');
    if (!arg.starts_with(kFlag) || comma == std::string_view::npos) {
      argv[kept++] = argv[i];
      continue;
    }
    const std::string a(arg.substr(kFlag.size(), comma - kFlag.size())), b(arg.substr(comma + 1));
    pairs.push_back({aosuite::read_file(a), aosuite::read_file(b)});
    names.push_back(a + "," + b);
  }
  argc = kept;
  pairs.shrink_to_fit();
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const std::string first = names[i].substr(0, names[i].find(','));
    for (const auto& [what, f] : {std::pair{"InflateOnly/", &inflate_only},
                                  std::pair{"IsalInflateOnly/", &isal_inflate_only},
                                  std::pair{"TwoInflateFloor/", &two_inflate_floor},
                                  std::pair{"ComparePngBands/", &compare_png_bands_on}}) {
      const bool one_file = f == &inflate_only || f == &isal_inflate_only;
      const std::string name = what + (one_file ? first : names[i]);
      benchmark::RegisterBenchmark(name.c_str(), f, std::cref(pairs[i]))
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_file_pairs(argc, argv);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
