// foglab — Welch PSD and log-frequency smoothing (see include/foglab/stats/psd.h).
//
// Choices made here (all fixed, none switched by build options):
//
// * Window: the PERIODIC Hann window w[n] = 0.5 - 0.5 cos(2 pi n / L),
//   n = 0 .. L-1 (scipy.signal.welch's default, "DFT-even" in Harris 1978).
//   Its equivalent noise bandwidth is 1.5 bins and sum(w^2) = 3L/8; the
//   density scaling below divides by sum(w^2), so a white record is flat at
//   its variance / fs whatever the window.
// * Default segment length: the largest power of two not above N/4, at least
//   16 and at most N (with 50 % overlap that gives at least 7 segments),
//   and never above 2^20 (long transforms are slow to plan and run).
// * Scaling (two-sided density, docs/conventions.md section 5): for bins k = 1 .. floor(L/2)
//       P_k = (1 / S) sum_s |X_{s,k}|^2 / (fs sum_n w[n]^2),
//   X_{s,k} the DFT of segment s after removing its mean and windowing.
//   Not doubled: 2 sum_k P_k df recovers the variance (Parseval), white noise
//   of variance s^2 is flat at s^2 / fs = N^2, and a Wiener rate random walk
//   x_n = x_{n-1} + K sqrt(dt) w_n follows K^2 / (2 pi f)^2 for f << fs.
//   (Welch 1967; Heinzel, Ruediger & Schilling 2002, "Spectrum and spectral
//   density estimation by the DFT", sections 9-10.)
//   Removing each segment's mean also removes its windowed leak into bin 1:
//   for white noise E[P_1] is 5/6 of the true level (1/6 = |W_1|^2 /
//   (L sum w^2) with W_1 = -L/4); bins k >= 2 are unaffected.
//
// Speed and reproducibility: one FFTW plan (FFTW_ESTIMATE, real-to-complex)
// is made per call and shared by all OpenMP threads through the new-array
// execute interface (fftw_execute_dft_r2c is thread-safe; planning is not, so
// planning and plan destruction are serialised by fftw_support.h's mutex).
// Each thread owns fftw_malloc'ed buffers, which are all equally aligned, so
// every thread runs the same FFT code path. Segments are grouped into
// chunks of a fixed size that depends only on L (at least kChunkSamples
// samples of work each); a chunk's periodograms are summed in segment order
// into the chunk's own slot, and after each round of chunks (all of them when
// the slots fit in kPartialBudgetBytes) the slots are added to the total in
// chunk order. Threads thus meet only once per round, and the result is
// bitwise independent of the thread count. The number of threads is also
// capped so that per-thread FFT buffers stay under about
// kWorkspaceBudgetBytes (a 10^9-sample record with the default L = 2^27
// would otherwise need 2 GB per thread).

#include "foglab/stats/psd.h"

#include <fftw3.h>
#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstddef>
#include <memory>
#include <mutex>
#include <new>
#include <numbers>
#include <vector>

#include "fftw_support.h"
#include "foglab/core/error.h"
#include "foglab/core/numeric.h"

namespace foglab::stats {

std::mutex& detail::fftw_planner_mutex() {
  static std::mutex mutex;
  return mutex;
}

namespace {

constexpr std::size_t kMinSegmentLength = 16;
/// The default is capped at 2^20 samples: longer transforms cost seconds each
/// with FFTW_ESTIMATE plans, and 2^20 already resolves fs / 10^6.
/// (FFTW's basic planner takes an int length, so explicit lengths stop at INT_MAX.)
constexpr std::size_t kMaxDefaultSegmentLength = std::size_t{1} << 20;
/// Extra threads are used only while their FFT buffers fit in this budget.
constexpr std::size_t kWorkspaceBudgetBytes = std::size_t{1} << 30;
/// Chunk sums kept between reductions (at least one per thread).
constexpr std::size_t kPartialBudgetBytes = std::size_t{1} << 28;
/// A frequency this close (in bins) below a log bin edge counts to the upper
/// bin, so exact decades (1 Hz, 10 Hz, ...) open their bin despite rounding.
constexpr double kEdgeTolerance = 1e-9;

using detail::fftw_planner_mutex;
using detail::FftwArray;

/// One real-to-complex plan of length n, destroyed on scope exit.
class R2cPlan {
 public:
  R2cPlan(int n, double* in, fftw_complex* out) {
    const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    plan_ = fftw_plan_dft_r2c_1d(n, in, out, FFTW_ESTIMATE);
    if (plan_ == nullptr) throw std::bad_alloc();
  }
  R2cPlan(const R2cPlan&) = delete;
  R2cPlan& operator=(const R2cPlan&) = delete;
  ~R2cPlan() {
    const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    fftw_destroy_plan(plan_);
  }
  /// Thread-safe: only reads the plan (FFTW manual, "Thread safety").
  void execute(double* in, fftw_complex* out) const { fftw_execute_dft_r2c(plan_, in, out); }

 private:
  fftw_plan plan_ = nullptr;
};

/// Buffers owned by one thread.
struct Workspace {
  explicit Workspace(std::size_t segment_length)
      : in(segment_length), out(segment_length / 2 + 1) {}
  FftwArray<double> in;         ///< the windowed segment
  FftwArray<fftw_complex> out;  ///< its spectrum, bins 0 .. L/2
};

std::size_t default_segment_length(std::size_t n) {
  std::size_t length = kMinSegmentLength;
  while (length * 2 <= n / 4 && length * 2 <= kMaxDefaultSegmentLength) length *= 2;
  return std::min(length, n);
}

// `n` is the longest contiguous stretch, `stretches` how many there are.
// Too few samples is the data's fault (a record too short, or cut by its
// gaps into stretches too short), as allan_deviation() says too.
void validate(std::size_t n, std::size_t stretches, double sample_rate_hz,
              const WelchOptions& options) {
  if (!(std::isfinite(sample_rate_hz) && sample_rate_hz > 0.0)) {
    throw UsageError(fmt::format("welch_psd: sample_rate_hz must be positive and finite, got {}",
                                 sample_rate_hz));
  }
  if (n < kMinSegmentLength) {
    throw DataError(fmt::format(
        "the Welch PSD needs at least {} rate samples in a row, the {} {}", kMinSegmentLength,
        stretches > 1 ? "longest stretch between gaps has" : "record has", n));
  }
  const std::size_t length = options.segment_length;
  if (length != 0 && (length < kMinSegmentLength || length > n)) {
    throw UsageError(
        fmt::format("welch_psd: segment_length must be 0 (automatic) or in [{}, {}] (the record "
                    "length), got {}",
                    kMinSegmentLength, n, length));
  }
  if (length > static_cast<std::size_t>(INT_MAX)) {
    throw UsageError(fmt::format(
        "welch_psd: segment_length must not exceed {} (FFTW's limit), got {}", INT_MAX, length));
  }
  if (!(options.overlap >= 0.0 && options.overlap <= kMaxWelchOverlap)) {
    throw UsageError(fmt::format("welch_psd: overlap must be in [0, {}], got {}", kMaxWelchOverlap,
                                 options.overlap));
  }
}

}  // namespace

PsdResult welch_psd(std::span<const double> rate, double sample_rate_hz,
                    const WelchOptions& options, std::span<const Gap> gaps) {
  check_gaps(gaps, static_cast<std::int64_t>(rate.size()), "welch_psd");
  const std::vector<Stretch> stretches =
      contiguous_stretches(static_cast<std::int64_t>(rate.size()), gaps);
  // the longest stretch (the record, without gaps)
  const auto n = static_cast<std::size_t>(longest_stretch(stretches));
  validate(n, stretches.size(), sample_rate_hz, options);

  const std::size_t length =
      options.segment_length != 0 ? options.segment_length : default_segment_length(n);
  const std::size_t bins = length / 2;  // k = 1 .. bins
  const double hop_real = std::round(static_cast<double>(length) * (1.0 - options.overlap));
  const std::size_t hop = std::max<std::size_t>(1, static_cast<std::size_t>(hop_real));
  // Welch segments wholly inside one stretch (core/gaps.h): stretch j holds
  // segments first_segment[j] .. first_segment[j + 1] - 1.
  std::vector<std::size_t> first_segment{0};
  for (const Stretch& s : stretches) {
    const auto size = static_cast<std::size_t>(s.size());
    first_segment.push_back(first_segment.back() +
                            (size >= length ? (size - length) / hop + 1 : 0));
  }
  const std::size_t segments = first_segment.back();
  auto segment_start = [&](std::size_t segment) {
    const auto j = static_cast<std::size_t>(
        std::upper_bound(first_segment.begin(), first_segment.end(), segment) -
        first_segment.begin() - 1);
    return static_cast<std::size_t>(stretches[j].begin) + (segment - first_segment[j]) * hop;
  };

  // Periodic Hann window and its power sum (3L/8 up to rounding).
  std::vector<double> window(length);
#pragma omp parallel for schedule(static) if (length >= kChunkSamples)
  for (std::size_t i = 0; i < length; ++i) {
    const double phase =
        2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(length);
    window[i] = 0.5 - 0.5 * std::cos(phase);
  }
  CompensatedSum window_power_sum;
  for (const double v : window) window_power_sum.add(v * v);
  const double window_power = window_power_sum.value();

  // Fixed chunking: depends on L only, never on the number of threads.
  const std::size_t chunk_segments = std::max<std::size_t>(1, kChunkSamples / length);
  const std::size_t chunks = (segments + chunk_segments - 1) / chunk_segments;

  const std::size_t bytes_per_thread = sizeof(double) * length + sizeof(fftw_complex) * (bins + 1);
  const std::size_t affordable = std::max<std::size_t>(1, kWorkspaceBudgetBytes / bytes_per_thread);
  const std::size_t threads =
      std::min<std::size_t>({static_cast<std::size_t>(worker_threads()), chunks, affordable});
  // Chunk sums are kept until they are added, in chunk order, at the end of a
  // round of `slots` chunks. The round size changes only how often the
  // threads meet, not the order of any addition.
  const std::size_t slots =
      std::min(chunks, std::max(threads, kPartialBudgetBytes / (sizeof(double) * bins)));

  // All allocation happens here, outside the parallel regions, so nothing in
  // them can throw; RAII frees everything on any exit path.
  std::vector<Workspace> workspaces;
  workspaces.reserve(threads);
  for (std::size_t t = 0; t < threads; ++t) workspaces.emplace_back(length);
  const R2cPlan plan(static_cast<int>(length), workspaces[0].in.get(), workspaces[0].out.get());
  std::vector<double> partial(slots * bins);
  std::vector<double> total(bins, 0.0);

  const double* data = rate.data();
  const double* w = window.data();
  const double inv_length = 1.0 / static_cast<double>(length);
  const int team = static_cast<int>(threads);

  for (std::size_t round = 0; round < chunks; round += slots) {
    const std::size_t round_end = std::min(chunks, round + slots);
    // Which thread takes which chunk does not matter: a chunk's sum depends
    // only on its segments.
#pragma omp parallel for schedule(dynamic) num_threads(team)
    for (std::size_t c = round; c < round_end; ++c) {
      Workspace& ws = workspaces[static_cast<std::size_t>(omp_get_thread_num())];
      double* in = ws.in.get();
      fftw_complex* out = ws.out.get();
      double* sum = partial.data() + (c - round) * bins;
      const std::size_t first = c * chunk_segments;
      const std::size_t last = std::min(segments, first + chunk_segments);
      for (std::size_t s = first; s < last; ++s) {
        const double* x = data + segment_start(s);
        CompensatedSum mean_sum;
        for (std::size_t i = 0; i < length; ++i) mean_sum.add(x[i]);
        const double mean = mean_sum.value() * inv_length;
        for (std::size_t i = 0; i < length; ++i) in[i] = (x[i] - mean) * w[i];
        plan.execute(in, out);
        if (s == first) {
          for (std::size_t k = 0; k < bins; ++k) {
            sum[k] = out[k + 1][0] * out[k + 1][0] + out[k + 1][1] * out[k + 1][1];
          }
        } else {
          for (std::size_t k = 0; k < bins; ++k) {
            sum[k] += out[k + 1][0] * out[k + 1][0] + out[k + 1][1] * out[k + 1][1];
          }
        }
      }
    }
    // Add the round's chunk sums in chunk order (parallel over bins only).
    const std::size_t round_chunks = round_end - round;
#pragma omp parallel for schedule(static) num_threads(team) if (bins >= kChunkSamples)
    for (std::size_t k = 0; k < bins; ++k) {
      double t = total[k];
      for (std::size_t j = 0; j < round_chunks; ++j) t += partial[j * bins + k];
      total[k] = t;
    }
  }

  PsdResult result;
  result.segment_length = length;
  result.segments = segments;
  result.sample_rate_hz = sample_rate_hz;
  result.resolution_hz = sample_rate_hz / static_cast<double>(length);
  result.frequency_hz.resize(bins);
  result.psd.resize(bins);
  result.sqrt_psd.resize(bins);
  const double scale = 1.0 / (static_cast<double>(segments) * sample_rate_hz * window_power);
  for (std::size_t k = 0; k < bins; ++k) {
    result.frequency_hz[k] =
        static_cast<double>(k + 1) * sample_rate_hz / static_cast<double>(length);
    result.psd[k] = total[k] * scale;
    result.sqrt_psd[k] = std::sqrt(result.psd[k]);
  }
  return result;
}

PsdResult log_smooth(const PsdResult& psd, double bins_per_decade) {
  if (!(std::isfinite(bins_per_decade) && bins_per_decade > 0.0)) {
    throw UsageError(fmt::format("log_smooth: bins_per_decade must be positive and finite, got {}",
                                 bins_per_decade));
  }
  const std::size_t n = psd.frequency_hz.size();
  if (psd.psd.size() != n) {
    throw UsageError(
        fmt::format("log_smooth: psd has {} frequencies (frequency_hz) but {} values (psd)", n,
                    psd.psd.size()));
  }
  for (std::size_t i = 0; i < n; ++i) {
    const double f = psd.frequency_hz[i];
    if (!(std::isfinite(f) && f > 0.0)) {
      throw UsageError(
          fmt::format("log_smooth: frequency_hz[{}] must be positive and finite, got {}", i, f));
    }
    if (i > 0 && !(f > psd.frequency_hz[i - 1])) {
      throw UsageError(fmt::format(
          "log_smooth: frequency_hz must increase, but frequency_hz[{}] = {} follows {}", i, f,
          psd.frequency_hz[i - 1]));
    }
  }

  PsdResult result;
  result.segment_length = psd.segment_length;
  result.segments = psd.segments;
  result.resolution_hz = psd.resolution_hz;
  result.sample_rate_hz = psd.sample_rate_hz;

  // Bin j covers [10^(j/b), 10^((j+1)/b)); frequencies increase, so each bin
  // is a contiguous run of the input.
  const auto bin_of = [bins_per_decade](double f) {
    return std::floor(std::log10(f) * bins_per_decade + kEdgeTolerance);
  };
  std::size_t i = 0;
  while (i < n) {
    const double bin = bin_of(psd.frequency_hz[i]);
    CompensatedSum value_sum;
    CompensatedSum log_frequency_sum;
    std::size_t j = i;
    for (; j < n && bin_of(psd.frequency_hz[j]) == bin; ++j) {
      value_sum.add(psd.psd[j]);
      log_frequency_sum.add(std::log(psd.frequency_hz[j]));
    }
    const double count = static_cast<double>(j - i);
    const double value = value_sum.value() / count;
    result.frequency_hz.push_back(std::exp(log_frequency_sum.value() / count));
    result.psd.push_back(value);
    result.sqrt_psd.push_back(std::sqrt(value));
    i = j;
  }
  return result;
}

}  // namespace foglab::stats
