#include "compare/band_compare.hpp"

#include <array>
#include <condition_variable>
#include <exception>
#include <mutex>

#include "common/thread_beside.hpp"
#include "compare/count_kernel.hpp"
#include "image/png_fast.hpp"

namespace aosuite {
namespace {

// A band's pixels per image: large enough that the inflater's per-call cost (its 32 KB window
// kept) is a few per cent, small enough that a band read is still in L2 when counted.
constexpr std::size_t kBandBytes = 128 << 10;
// Bands in flight per image: a decoder may run this many bands ahead of the counting, and of
// the other file's decoder, so that bands one file decodes slower than the other even out.
// With 4 the 4K `blobs` peers-bench pair took 65.5 ms against its 54.0 ms two-inflate floor,
// with 6 54.4 ms (compare_bench ComparePngBands); a 1080p ring stays under 2 MB (rgba_image.cpp).
constexpr std::uint32_t kSlots = 6;

// Two decoders meet here. Band i goes into slot i % kSlots of both images; once both have
// it, it is counted by whichever decoder next finds its own next slot still taken (or its
// file done), and its slot is freed for band i + kSlots. So the decoder ahead does the
// counting while the one behind keeps decoding, and the run ends when the slower file does.
class Rendezvous {
 public:
  explicit Rendezvous(std::uint32_t bands) : bands_(bands) {
    for (std::uint32_t s = 0; s < kSlots; ++s) free_for_[s] = s;
  }
  // Waits until band's slot is free, counting meanwhile; false when the other decoder failed.
  template <class Count>
  bool wait_for_slot(std::uint32_t band, Count& count) {
    std::unique_lock lock(m_);
    while (!failed_ && free_for_[band % kSlots] != band) {
      if (!count_one(lock, count)) cv_.wait(lock);
    }
    return !failed_;
  }
  // The decoder has band i in its slot. Bands reach both decoders in order.
  void arrive(std::uint32_t band) {
    {
      std::lock_guard lock(m_);
      if (++arrived_[band % kSlots] == 2) ++both_have_;
    }
    cv_.notify_all();
  }
  // After the decoder's last band: counts until every band is counted.
  template <class Count>
  void finish(Count& count) {
    std::unique_lock lock(m_);
    while (!failed_ && counted_ < bands_) {
      if (!count_one(lock, count)) cv_.wait(lock);
    }
  }
  void fail(std::exception_ptr e) {
    {
      std::lock_guard lock(m_);
      if (!error_) error_ = std::move(e);
      failed_ = true;
    }
    cv_.notify_all();
  }
  void rethrow() const {
    if (error_) std::rethrow_exception(error_);
  }

 private:
  // Counts the next band both decoders have, if any (unlocked meanwhile), and frees its slot.
  template <class Count>
  bool count_one(std::unique_lock<std::mutex>& lock, Count& count) {
    if (taken_ == both_have_) return false;
    const std::uint32_t band = taken_++;
    lock.unlock();
    count(band);
    lock.lock();
    arrived_[band % kSlots] = 0;
    free_for_[band % kSlots] = band + kSlots;
    ++counted_;
    cv_.notify_all();
    return true;
  }

  std::mutex m_;
  std::condition_variable cv_;
  const std::uint32_t bands_;
  std::array<std::uint32_t, kSlots> free_for_{};
  std::array<int, kSlots> arrived_{};
  // Bands both decoders have, taken for counting, and counted: each a prefix of all bands.
  std::uint32_t both_have_ = 0, taken_ = 0, counted_ = 0;
  bool failed_ = false;
  std::exception_ptr error_;
};

}  // namespace

std::uint32_t band_rows_for(std::uint32_t width) {
  return std::max<std::uint32_t>(1,
                                 static_cast<std::uint32_t>(kBandBytes / (std::size_t{width} * 4)));
}

std::optional<resemble::Result> compare_png_bands(
    std::span<const unsigned char> a, const std::string& name_a, std::span<const unsigned char> b,
    const std::string& name_b, const resemble::Options& options, comparison::ChannelStats* stats) {
  const auto start = std::chrono::steady_clock::now();
  // The files' pixels are what is compared only without a canvas model.
  const std::optional<std::array<int, 4>> min_delta = resemble::count_only_thresholds(options);
  if (!min_delta || options.canvas_alpha != CanvasAlpha::kNone) return std::nullopt;
  // Opening reads only the chunk headers (the image data's CRCs are checked as it is read).
  std::array<std::optional<PngRows>, 2> png = {PngRows::open(a, name_a), PngRows::open(b, name_b)};
  if (!png[0] || !png[1] || png[0]->width() != png[1]->width() ||
      png[0]->height() != png[1]->height()) {
    return std::nullopt;
  }
  const std::uint32_t w = png[0]->width(), h = png[0]->height();
  const std::uint32_t band_rows = band_rows_for(w);
  const std::uint32_t bands = (h + band_rows - 1) / band_rows;
  // Each decoder populates its own ring on its own thread: the two populations (0.7 ms
  // together at 1080p) run side by side, and overlap the second thread's start.
  // 1080p `blobs`, whole process: 21.5 -> 19.9 ms (bench/README.md).
  const std::array<std::size_t, 2> slot_bytes = {png[0]->band_bytes(band_rows),
                                                 png[1]->band_bytes(band_rows)};
  std::array<PixelBuffer, 2> rings;
  auto slot = [&](int i, std::uint32_t band) {
    return rings[std::size_t(i)].data() + (band % kSlots) * slot_bytes[std::size_t(i)];
  };

  Rendezvous meet(bands);
  std::array<MismatchTally, 2> tally;
  std::array<comparison::ChannelStats, 2> channel_stats;
  auto decode = [&](int i) {
    auto count = [&](std::uint32_t band) {
      const std::uint32_t y0 = band * band_rows, rows = std::min(band_rows, h - y0);
      tally[i].merge(count_band(slot(0, band), slot(1, band), static_cast<int>(w),
                                static_cast<int>(rows), static_cast<int>(y0), *min_delta));
      if (stats) {
        channel_stats[std::size_t(i)].add(slot(0, band), slot(1, band), std::uint64_t(w) * rows,
                                          std::uint64_t(w) * y0);
      }
    };
    try {
      rings[std::size_t(i)] = PixelBuffer(slot_bytes[std::size_t(i)] * kSlots);
      for (std::uint32_t band = 0; band < bands; ++band) {
        if (!meet.wait_for_slot(band, count)) return;
        png[i]->read(slot(i, band), std::min(band_rows, h - band * band_rows));
        meet.arrive(band);
      }
      meet.finish(count);
    } catch (...) {
      meet.fail(std::current_exception());
    }
  };
  {
    // Never on this thread's CPU: taking turns there left the decoders waiting 5.8 ms in all
    // (median, 1080p `blobs`); 1080p `ao` whole process 21.7 -> 17.4 ms (bench/README.md).
    ThreadBeside other([&] { decode(1); });
    decode(0);
  }
  meet.rethrow();
  tally[0].merge(tally[1]);
  if (stats) stats->merge(channel_stats[0]), stats->merge(channel_stats[1]);
  const ImageSize size{static_cast<int>(w), static_cast<int>(h)};
  return resemble::result_from_tally(tally[0], size, size, start);
}

}  // namespace aosuite
