#include "theo1_kernel.h"

#include <fftw3.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <exception>
#include <map>
#include <mutex>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include "fftw_support.h"
#include "foglab/core/error.h"
#include "foglab/core/numeric.h"

namespace foglab::stats::detail {
namespace {

// The direct method (about 5 flops per term, vectorised) is used whenever it
// needs at most this many terms, (N - m) m / 2, per sample: m <= 384, and m
// near N. The blocked method costs about as much as 200 terms per sample at
// N = 10^5 .. 10^6 (see the harness timings).
constexpr double kDirectMaxTermsPerSample = 192.0;
// A block holds at most this many times m positions: larger blocks save
// transforms, smaller ones keep the detrended span, and so the cancellation,
// small (the residual of a span of B + m samples grows like (B + m)^{3/2} for
// random walk FM).
constexpr std::int64_t kBlockFactor = 4;
// Positions per chunk of the direct method (fixed: results do not depend on
// the thread count).
constexpr std::int64_t kDirectChunk = 4096;
// Triangles up to this size, and rectangles up to this many products, are
// summed directly.
constexpr std::int64_t kTriangleLeaf = 64;
constexpr std::int64_t kDirectRectangle = 4096;

void require_factor(std::size_t length, std::int64_t m, const char* caller) {
  const auto n = static_cast<std::int64_t>(length);
  if (m < 2 || m % 2 != 0 || m > n - 1) {
    throw UsageError(std::string(caller) + ": averaging factor m = " + std::to_string(m) +
                     " must be even with 2 <= m <= N - 1 = " + std::to_string(n - 1));
  }
}

// ---------------------------------------------------------------------------
// FFTW plumbing (as in psd.cc: FFTW_ESTIMATE plans shared by all threads
// through the thread-safe new-array execute functions, planning serialised).

/// Real-to-complex and complex-to-real plans of each length used in one call,
/// made on first use and destroyed with the cache.
class PlanCache {
 public:
  struct Pair {
    fftw_plan forward = nullptr;
    fftw_plan backward = nullptr;
  };

  PlanCache() = default;
  PlanCache(const PlanCache&) = delete;
  PlanCache& operator=(const PlanCache&) = delete;
  ~PlanCache() {
    const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    for (auto& [length, pair] : plans_) {
      if (pair.forward != nullptr) fftw_destroy_plan(pair.forward);
      if (pair.backward != nullptr) fftw_destroy_plan(pair.backward);
    }
  }

  /// The plans of length n (thread-safe; the reference stays valid).
  const Pair& get(std::int64_t n) {
    const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    auto found = plans_.find(n);
    if (found != plans_.end()) return found->second;
    const FftwArray<double> real(static_cast<std::size_t>(n));
    const FftwArray<fftw_complex> spectrum(static_cast<std::size_t>(n / 2 + 1));
    Pair pair;
    const int length = static_cast<int>(n);
    pair.forward = fftw_plan_dft_r2c_1d(length, real.get(), spectrum.get(), FFTW_ESTIMATE);
    pair.backward = fftw_plan_dft_c2r_1d(length, spectrum.get(), real.get(), FFTW_ESTIMATE);
    if (pair.forward == nullptr || pair.backward == nullptr) {
      if (pair.forward != nullptr) fftw_destroy_plan(pair.forward);
      if (pair.backward != nullptr) fftw_destroy_plan(pair.backward);
      throw std::bad_alloc();
    }
    return plans_.emplace(n, pair).first->second;
  }

 private:
  std::map<std::int64_t, Pair> plans_;
};

/// The smallest n' >= n whose prime factors are 2, 3, 5 and 7 (fast in FFTW).
std::int64_t transform_length(std::int64_t n) {
  for (std::int64_t candidate = std::max<std::int64_t>(n, 1);; ++candidate) {
    std::int64_t rest = candidate;
    for (const std::int64_t p : {2, 3, 5, 7}) {
      while (rest % p == 0) rest /= p;
    }
    if (rest == 1) return candidate;
  }
}

/// The smallest power of two >= n (the many small transforms of the triangle
/// recursion then share a few plans).
std::int64_t power_of_two_length(std::int64_t n) {
  std::int64_t length = 1;
  while (length < n) length *= 2;
  return length;
}

/// FFT buffers of one task, grown on demand and reused (fresh pages would
/// cost more than the transforms). Every buffer starts an fftw_malloc block,
/// so all have the alignment the plans were made with.
class Workspace {
 public:
  void reserve(std::int64_t length) {
    if (length <= capacity_) return;
    const auto half = static_cast<std::size_t>(length / 2 + 1);
    real_.emplace(static_cast<std::size_t>(length));
    spectrum_a_.emplace(half);
    spectrum_b_.emplace(half);
    capacity_ = length;
  }
  double* real() const { return real_->get(); }
  fftw_complex* spectrum_a() const { return spectrum_a_->get(); }
  fftw_complex* spectrum_b() const { return spectrum_b_->get(); }

 private:
  std::int64_t capacity_ = 0;
  std::optional<FftwArray<double>> real_;
  std::optional<FftwArray<fftw_complex>> spectrum_a_, spectrum_b_;
};

/// out[t] = sum_p a_p a_{p+t} for t = 0 .. max_lag (max_lag < na): the
/// autocorrelation of a_0 .. a_{na-1}.
void autocorrelation(const double* a, std::int64_t na, std::int64_t max_lag, double* out,
                     PlanCache& plans, Workspace& work) {
  const std::int64_t f = transform_length(na + max_lag);
  const PlanCache::Pair& plan = plans.get(f);
  work.reserve(f);
  double* r = work.real();
  fftw_complex* c = work.spectrum_a();
  std::copy(a, a + na, r);
  std::fill(r + na, r + f, 0.0);
  fftw_execute_dft_r2c(plan.forward, r, c);
  for (std::int64_t j = 0; j <= f / 2; ++j) {
    c[j][0] = c[j][0] * c[j][0] + c[j][1] * c[j][1];
    c[j][1] = 0.0;
  }
  fftw_execute_dft_c2r(plan.backward, c, r);
  const double scale = 1.0 / static_cast<double>(f);
  for (std::int64_t t = 0; t <= max_lag; ++t) out[t] = r[t] * scale;
}

/// out[shift + t] += sum_p a_p b_{p+t} (t = -(na-1) .. nb-1) wherever
/// 0 <= shift + t < out_size: a cross-correlation of a_0 .. a_{na-1} and
/// b_0 .. b_{nb-1}.
void add_cross_correlation(const double* a, std::int64_t na, const double* b, std::int64_t nb,
                           std::int64_t shift, double* out, std::int64_t out_size, PlanCache& plans,
                           Workspace& work) {
  const std::int64_t t_begin = std::max(-(na - 1), -shift);
  const std::int64_t t_end = std::min(nb, out_size - shift);  // exclusive
  if (t_begin >= t_end) return;
  if (na * nb <= kDirectRectangle) {
    for (std::int64_t p = 0; p < na; ++p) {
      const std::int64_t q_begin = std::max<std::int64_t>(0, p + t_begin);
      const std::int64_t q_end = std::min(nb, p + t_end);
      for (std::int64_t q = q_begin; q < q_end; ++q) out[shift + q - p] += a[p] * b[q];
    }
    return;
  }
  const std::int64_t f = power_of_two_length(na + nb - 1);
  const PlanCache::Pair& plan = plans.get(f);
  work.reserve(f);
  double* r = work.real();
  fftw_complex* ca = work.spectrum_a();
  fftw_complex* cb = work.spectrum_b();
  std::copy(a, a + na, r);
  std::fill(r + na, r + f, 0.0);
  fftw_execute_dft_r2c(plan.forward, r, ca);
  std::copy(b, b + nb, r);
  std::fill(r + nb, r + f, 0.0);
  fftw_execute_dft_r2c(plan.forward, r, cb);
  for (std::int64_t j = 0; j <= f / 2; ++j) {  // conj(A) B
    const double re = ca[j][0] * cb[j][0] + ca[j][1] * cb[j][1];
    const double im = ca[j][0] * cb[j][1] - ca[j][1] * cb[j][0];
    ca[j][0] = re;
    ca[j][1] = im;
  }
  fftw_execute_dft_c2r(plan.backward, ca, r);
  const double scale = 1.0 / static_cast<double>(f);
  for (std::int64_t t = t_begin; t < t_end; ++t) out[shift + t] += r[(t + f) % f] * scale;
}

/// Adds s_{a0+p} s_{b0+q} to out[(b0+q) - (a0+p)] for p, q in [0, n) with
/// p + q < n, wherever that index lies in [0, out_size). Divide and conquer:
/// the rectangle p < c, q < n - c (c = n/2) lies wholly inside, and the rest
/// is two triangles of sizes c and n - c.
void add_triangle(const double* s, std::int64_t a0, std::int64_t b0, std::int64_t n, double* out,
                  std::int64_t out_size, PlanCache& plans, Workspace& work) {
  const std::int64_t shift = b0 - a0;
  if (n <= 0 || shift + n - 1 < 0) return;  // no pair with a non-negative lag
  if (n <= kTriangleLeaf) {
    for (std::int64_t p = 0; p < n; ++p) {
      const double sp = s[a0 + p];
      const std::int64_t q_begin = std::max<std::int64_t>(0, p - shift);
      const std::int64_t q_end = std::min(n - p, out_size + p - shift);
      for (std::int64_t q = q_begin; q < q_end; ++q) out[shift + q - p] += sp * s[b0 + q];
    }
    return;
  }
  const std::int64_t c = n / 2;
  add_cross_correlation(s + a0, c, s + b0, n - c, shift, out, out_size, plans, work);
  add_triangle(s, a0, b0 + n - c, c, out, out_size, plans, work);
  add_triangle(s, a0 + c, b0, n - c, out, out_size, plans, work);
}

// ---------------------------------------------------------------------------
// Detrending.

// z_j = x_j minus the least-squares line of x_0 .. x_{n-1}. The line is taken
// about the middle sample and the centre; its value at j is subtracted with
// an exact product (fma) and an exact difference, so the residual carries
// rounding of its own size only, however large the offset and slope.
void detrend(const double* x, std::int64_t n, double* z) {
  const double level = x[n / 2];
  const double centre = 0.5 * static_cast<double>(n - 1);
  CompensatedSum sum;
  for (std::int64_t j = 0; j < n; ++j) sum.add(x[j] - level);
  const double mean = sum.value() / static_cast<double>(n);
  CompensatedSum moment;
  for (std::int64_t j = 0; j < n; ++j) {
    moment.add((static_cast<double>(j) - centre) * ((x[j] - level) - mean));
  }
  const auto l = static_cast<double>(n);
  const double slope = n > 1 ? moment.value() * 12.0 / (l * (l * l - 1.0)) : 0.0;
  for (std::int64_t j = 0; j < n; ++j) {
    const double u = static_cast<double>(j) - centre;
    const double d = x[j] - level;  // d + d_error = x_j - level exactly
    const double t = d - x[j];
    const double d_error = (x[j] - (d - t)) + (-level - t);
    const double ramp = slope * u;  // ramp + ramp_error = slope u exactly
    const double ramp_error = std::fma(slope, u, -ramp);
    z[j] = ((d - ramp) - mean) + (d_error - ramp_error);
  }
}

// ---------------------------------------------------------------------------
// The blocked method.

// Buffers of one thread, reused from block to block and factor to factor.
struct BlockWork {
  std::vector<double> z, tail_reversed, r, rh, rt, th, tt;
  std::vector<long double> prefix;
  std::array<Workspace, 4> fft;  // one per concurrent correlation
};

// sum_k S_k / k over the positions of one block: x_0 .. x_{n-1} with
// M = n - m positions. `parallel`: run the correlations concurrently.
long double block_sum(const double* x, std::int64_t n, std::int64_t m, PlanCache& plans,
                      BlockWork& work, bool parallel) {
  const std::int64_t positions = n - m, h = m / 2;
  const auto size = [](std::int64_t count) { return static_cast<std::size_t>(count); };
  work.z.resize(size(n));
  double* z = work.z.data();
  detrend(x, n, z);
  work.tail_reversed.assign(work.z.rbegin(), work.z.rbegin() + m);
  work.r.resize(size(m + 1));
  work.rh.resize(size(m));
  work.rt.resize(size(m));
  work.th.assign(size(m), 0.0);
  work.tt.assign(size(m), 0.0);

  std::exception_ptr failure;
  std::mutex failure_mutex;
  const auto guarded = [&](auto&& task) {
    try {
      task();
    } catch (...) {
      const std::lock_guard<std::mutex> lock(failure_mutex);
      if (!failure) failure = std::current_exception();
    }
  };
#pragma omp parallel sections num_threads(2) if (parallel)
  {
#pragma omp section
    guarded([&] { add_triangle(z, 0, 0, m, work.th.data(), m, plans, work.fft[0]); });
#pragma omp section
    guarded([&] {
      add_triangle(work.tail_reversed.data(), 0, 0, m, work.tt.data(), m, plans, work.fft[1]);
    });
#pragma omp section
    guarded([&] { autocorrelation(z, n, m, work.r.data(), plans, work.fft[2]); });
#pragma omp section
    guarded([&] {
      autocorrelation(z, m, m - 1, work.rh.data(), plans, work.fft[3]);
      autocorrelation(z + positions, m, m - 1, work.rt.data(), plans, work.fft[3]);
    });
  }
  if (failure) std::rethrow_exception(failure);

  // Window energies E(a) = P(a + M) - P(a), P the prefix sums of z^2.
  work.prefix.resize(size(n + 1));
  long double* prefix = work.prefix.data();
  prefix[0] = 0.0L;
  for (std::int64_t j = 0; j < n; ++j) {
    const long double v = z[j];
    prefix[j + 1] = prefix[j] + v * v;
  }
  const auto energy = [&](std::int64_t a) { return prefix[a + positions] - prefix[a]; };

  const double* r = work.r.data();
  const double* rh = work.rh.data();
  const double* rt = work.rt.data();
  const double* th = work.th.data();
  const double* tt = work.tt.data();
  const long double e0m = energy(0) + energy(m);
  const long double rm = r[m];
  long double total = 0.0L;
  for (std::int64_t k = 1; k <= h; ++k) {
    const std::int64_t g = m - k, lag = m - 2 * k;
    const long double energies = e0m + energy(k) + energy(g);
    const long double full = rm + r[lag] - 2.0L * (static_cast<long double>(r[k]) + r[g]);
    const long double heads = static_cast<long double>(rh[k]) + rh[g] + rt[k] + rt[g];
    const long double triangles = static_cast<long double>(th[lag]) + tt[lag];
    total += (energies + 2.0L * (full + heads - triangles)) / static_cast<long double>(k);
  }
  return total;
}

// The blocked method for one factor; `work` holds one BlockWork per thread.
double blocked_sum(std::span<const double> x, std::int64_t m, PlanCache& plans,
                   std::vector<BlockWork>& work) {
  const auto n = static_cast<std::int64_t>(x.size());
  const std::int64_t positions = n - m;
  const std::int64_t blocks = (positions + kBlockFactor * m - 1) / (kBlockFactor * m);
  const auto block_begin = [&](std::int64_t b) { return positions * b / blocks; };
  std::vector<long double> partial(static_cast<std::size_t>(blocks));
  const auto threads = static_cast<std::int64_t>(work.size());
  if (blocks >= 2 * threads) {
    std::exception_ptr failure;
#pragma omp parallel for schedule(dynamic, 1) num_threads(static_cast <int>(threads))
    for (std::int64_t b = 0; b < blocks; ++b) {
      try {
        const std::int64_t i0 = block_begin(b), i1 = block_begin(b + 1);
        partial[b] = block_sum(x.data() + i0, i1 - i0 + m, m, plans,
                               work[static_cast<std::size_t>(omp_get_thread_num())], false);
      } catch (...) {
#pragma omp critical(foglab_theo1_failure)
        if (!failure) failure = std::current_exception();
      }
    }
    if (failure) std::rethrow_exception(failure);
  } else {
    for (std::int64_t b = 0; b < blocks; ++b) {
      const std::int64_t i0 = block_begin(b), i1 = block_begin(b + 1);
      partial[b] = block_sum(x.data() + i0, i1 - i0 + m, m, plans, work[0], threads > 1);
    }
  }
  long double total = 0.0L;
  for (const long double p : partial) total += p;
  return static_cast<double>(total);
}

}  // namespace

double theo1_sum_blocked(std::span<const double> x, std::int64_t m) {
  require_factor(x.size(), m, "theo1_sum_blocked");
  PlanCache plans;
  std::vector<BlockWork> work(static_cast<std::size_t>(std::max(1, omp_get_max_threads())));
  return blocked_sum(x, m, plans, work);
}

double theo1_sum_direct(std::span<const double> x, std::int64_t m) {
  require_factor(x.size(), m, "theo1_sum_direct");
  const auto n = static_cast<std::int64_t>(x.size());
  const std::int64_t positions = n - m, h = m / 2;
  const std::int64_t chunks = (positions + kDirectChunk - 1) / kDirectChunk;
  std::vector<double> partial(static_cast<std::size_t>(chunks));
  const double* p = x.data();
#pragma omp parallel for schedule(dynamic, 1) if (chunks > 1)
  for (std::int64_t c = 0; c < chunks; ++c) {
    const std::int64_t i0 = c * kDirectChunk;
    const std::int64_t i1 = std::min(positions, i0 + kDirectChunk);
    double chunk_total = 0.0;
    for (std::int64_t k = 1; k <= h; ++k) {
      const std::int64_t g = m - k;
      double s = 0.0;
      // Differences of neighbours first: exact for a large offset or slope.
#pragma omp simd reduction(+ : s)
      for (std::int64_t i = i0; i < i1; ++i) {
        const double e = (p[i] - p[i + k]) + (p[i + m] - p[i + g]);
        s += e * e;
      }
      chunk_total += s / static_cast<double>(k);
    }
    partial[c] = chunk_total;
  }
  CompensatedSum total;
  for (const double v : partial) total.add(v);
  return total.value();
}

std::vector<double> theo1_sums(std::span<const double> x, std::span<const std::int64_t> factors) {
  for (std::size_t j = 0; j < factors.size(); ++j) {
    require_factor(x.size(), factors[j], "theo1_sums");
    if (j > 0 && factors[j] <= factors[j - 1]) {
      throw UsageError("theo1_sums: averaging factors must increase, but " +
                       std::to_string(factors[j]) + " follows " + std::to_string(factors[j - 1]));
    }
  }
  std::vector<double> sums(factors.size());
  PlanCache plans;
  std::vector<BlockWork> work;
  const auto n = static_cast<double>(x.size());
  for (std::size_t j = 0; j < factors.size(); ++j) {
    const std::int64_t m = factors[j];
    // The direct cost, (N - m) m / 2 terms, against the blocked one.
    const double direct_terms = (n - static_cast<double>(m)) * static_cast<double>(m / 2);
    if (direct_terms <= kDirectMaxTermsPerSample * n) {
      sums[j] = theo1_sum_direct(x, m);
    } else {
      if (work.empty()) work.resize(static_cast<std::size_t>(std::max(1, omp_get_max_threads())));
      sums[j] = blocked_sum(x, m, plans, work);
    }
  }
  return sums;
}

}  // namespace foglab::stats::detail
