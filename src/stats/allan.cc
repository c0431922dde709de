#include "foglab/stats/allan.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>

#include "../core/simd_clones.h"
#include "foglab/core/error.h"
#include "foglab/core/numeric.h"
#include "foglab/stats/confidence.h"
#include "foglab/stats/edf.h"
#include "foglab/stats/noise_id.h"
#include "theo1_kernel.h"
#include "total_kernel.h"

namespace foglab::stats {
namespace {

constexpr std::array<AllanKind, 11> kKinds = {
    AllanKind::adev,    AllanKind::oadev,   AllanKind::mdev,   AllanKind::hdev,
    AllanKind::ohdev,   AllanKind::tdev,    AllanKind::totdev, AllanKind::mtotdev,
    AllanKind::ttotdev, AllanKind::htotdev, AllanKind::theo1};

// Positions handled together: every offset stream of a block stays in the
// L2 cache while all averaging factors use it, so each distinct offset is
// read from memory once per pass (see bench/RESULTS.md).
constexpr std::int64_t kBlock = 4096;
constexpr auto kChunk = static_cast<std::int64_t>(kChunkSamples);

std::int64_t chunk_count(std::int64_t n, std::int64_t chunk) { return (n + chunk - 1) / chunk; }

// Sum over i in [i0, i1) of the squared D-th difference at lag m (D = 2:
// Allan, D = 3: Hadamard).
template <int D>
FOGLAB_CLONED_INLINE double difference_sum(const double* p, std::int64_t i0, std::int64_t i1,
                                           std::int64_t m) {
  double s = 0.0;
  if constexpr (D == 2) {
#pragma omp simd reduction(+ : s)
    for (std::int64_t i = i0; i < i1; ++i) {
      const double d = p[i + 2 * m] - 2.0 * p[i + m] + p[i];
      s += d * d;
    }
  } else {
#pragma omp simd reduction(+ : s)
    for (std::int64_t i = i0; i < i1; ++i) {
      const double d = p[i + 3 * m] - 3.0 * p[i + 2 * m] + 3.0 * p[i + m] - p[i];
      s += d * d;
    }
  }
  return s;
}

FOGLAB_SIMD_CLONES double second_difference_sum(const double* p, std::int64_t i0, std::int64_t i1,
                                                std::int64_t m) {
  return difference_sum<2>(p, i0, i1, m);
}

FOGLAB_SIMD_CLONES double third_difference_sum(const double* p, std::int64_t i0, std::int64_t i1,
                                               std::int64_t m) {
  return difference_sum<3>(p, i0, i1, m);
}

// An octave chain: the factors m, 2m, 4m, 8m, whose second differences at i
// use the angle points i, i + m, i + 2m, ..., i + 16m. Their four sums over
// i in [i0, i1) are taken in one loop that loads each of those six points
// once, not twelve times (about twice as fast as four separate loops on an
// octave grid).
constexpr int kChainLength = 4;

FOGLAB_SIMD_CLONES void octave_chain_sums(const double* p, std::int64_t i0, std::int64_t i1,
                                          std::int64_t m, double* sums) {
  const double* q0 = p + m;
  const double* q1 = p + 2 * m;
  const double* q2 = p + 4 * m;
  const double* q3 = p + 8 * m;
  const double* q4 = p + 16 * m;
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
#pragma omp simd reduction(+ : s0, s1, s2, s3)
  for (std::int64_t i = i0; i < i1; ++i) {
    const double x = p[i];
    const double d0 = q1[i] - 2.0 * q0[i] + x;
    const double d1 = q2[i] - 2.0 * q1[i] + x;
    const double d2 = q3[i] - 2.0 * q2[i] + x;
    const double d3 = q4[i] - 2.0 * q3[i] + x;
    s0 += d0 * d0;
    s1 += d1 * d1;
    s2 += d2 * d2;
    s3 += d3 * d3;
  }
  sums[0] += s0;
  sums[1] += s1;
  sums[2] += s2;
  sums[3] += s3;
}

// Where each octave chain of `factors` starts (Allan family only): a factor
// followed by its doubles 2m, 4m, 8m. The other factors are summed alone.
std::vector<bool> octave_chain_starts(std::span<const std::int64_t> factors, int order) {
  std::vector<bool> starts(factors.size(), false);
  if (order != 2) return starts;
  for (std::size_t k = 0; k + kChainLength <= factors.size();) {
    bool chain = true;
    for (int g = 1; g < kChainLength; ++g) chain = chain && factors[k + g] == (factors[k] << g);
    if (chain) {
      starts[k] = true;
      k += kChainLength;
    } else {
      ++k;
    }
  }
  return starts;
}

// Sum over i = 0 .. N - D m - 1 of the squared D-th difference at lag m, for
// every m at once (D = 2: Allan, D = 3: Hadamard).
template <int D>
std::vector<double> overlapping_sums(std::span<const double> x,
                                     std::span<const std::int64_t> factors) {
  const auto n = static_cast<std::int64_t>(x.size());
  const auto k_count = static_cast<std::int64_t>(factors.size());
  const std::int64_t chunks = chunk_count(n, kChunk);
  const std::vector<bool> chain_starts = octave_chain_starts(factors, D);
  std::vector<double> partial(static_cast<std::size_t>(chunks * k_count), 0.0);
  const double* p = x.data();
  auto single = [p](std::int64_t i0, std::int64_t i1, std::int64_t m) {
    if (i0 >= i1) return 0.0;
    return D == 2 ? second_difference_sum(p, i0, i1, m) : third_difference_sum(p, i0, i1, m);
  };
#pragma omp parallel for schedule(dynamic, 2) if (chunks > 1)
  for (std::int64_t c = 0; c < chunks; ++c) {
    const std::int64_t c_end = std::min(n, (c + 1) * kChunk);
    double* sums = &partial[static_cast<std::size_t>(c * k_count)];
    for (std::int64_t b = c * kChunk; b < c_end; b += kBlock) {
      const std::int64_t b_end = std::min(c_end, b + kBlock);
      for (std::int64_t k = 0; k < k_count;) {
        if (!chain_starts[k]) {
          const std::int64_t m = factors[k];
          sums[k] += single(b, std::min(b_end, n - D * m), m);
          ++k;
          continue;
        }
        // The whole chain where its longest factor still has terms, then
        // each factor alone up to its own end.
        const std::int64_t m = factors[k];
        const std::int64_t shared_end = std::max(b, std::min(b_end, n - 2 * (m << 3)));
        if (b < shared_end) octave_chain_sums(p, b, shared_end, m, sums + k);
        for (int g = 0; g < kChainLength; ++g) {
          const std::int64_t mg = factors[k + g];
          sums[k + g] += single(shared_end, std::min(b_end, n - 2 * mg), mg);
        }
        k += kChainLength;
      }
    }
  }
  std::vector<double> sums(factors.size());
  for (std::int64_t k = 0; k < k_count; ++k) {
    CompensatedSum total;
    for (std::int64_t c = 0; c < chunks; ++c) total.add(partial[c * k_count + k]);
    sums[k] = total.value();
  }
  return sums;
}

// Sum of the squared D-th differences at lag m taken at i = 0, m, 2m, ...
// (`terms` of them).
template <int D>
double strided_sum(std::span<const double> x, std::int64_t m, std::int64_t terms) {
  const std::int64_t chunks = chunk_count(terms, kChunk);
  std::vector<double> partial(static_cast<std::size_t>(chunks), 0.0);
  const double* p = x.data();
#pragma omp parallel for schedule(static) if (chunks > 1)
  for (std::int64_t c = 0; c < chunks; ++c) {
    double s = 0.0;
    const std::int64_t end = std::min(terms, (c + 1) * kChunk);
    for (std::int64_t j = c * kChunk; j < end; ++j) {
      const std::int64_t i = j * m;
      double d;
      if constexpr (D == 2) {
        d = p[i + 2 * m] - 2.0 * p[i + m] + p[i];
      } else {
        d = p[i + 3 * m] - 3.0 * p[i + 2 * m] + 3.0 * p[i + m] - p[i];
      }
      s += d * d;
    }
    partial[c] = s;
  }
  CompensatedSum total;
  for (const double s : partial) total.add(s);
  return total.value();
}

// Modified Allan: sum over j = 0 .. n-1 of (sum_{i=j}^{j+m-1} d_i)^2 with
// d_i = x_{i+2m} - 2 x_{i+m} + x_i, by sliding windows. Each chunk starts its
// windows afresh, so rounding never accumulates beyond one chunk; chunks are
// at least m long, so the restarts cost at most one extra pass. For short
// factors a chunk runs four windows side by side (independent dependency
// chains, about three times faster).
double modified_sum(std::span<const double> x, std::int64_t m, std::int64_t terms) {
  const std::int64_t chunk = std::max(kChunk, m);
  const std::int64_t chunks = chunk_count(terms, chunk);
  std::vector<double> partial(static_cast<std::size_t>(chunks), 0.0);
  const double* p = x.data();
  auto d = [p, m](std::int64_t i) { return p[i + 2 * m] - 2.0 * p[i + m] + p[i]; };
  auto start_window = [&](std::int64_t j) {
    double w = 0.0;
    for (std::int64_t i = j; i < j + m; ++i) w += d(i);
    return w;
  };
  constexpr std::int64_t kLanes = 4;
#pragma omp parallel for schedule(dynamic, 1) if (chunks > 1)
  for (std::int64_t c = 0; c < chunks; ++c) {
    const std::int64_t begin = c * chunk;
    const std::int64_t end = std::min(terms, begin + chunk);
    const std::int64_t length = end - begin;
    double s = 0.0;
    std::int64_t j = begin;
    if (m * 16 <= length) {
      // The lanes stop at least one term before the chunk's end, so every
      // window update below reads inside the record; the tail loop finishes.
      const std::int64_t lane = (length - 1) / kLanes;
      double w[kLanes], acc[kLanes];
      for (std::int64_t l = 0; l < kLanes; ++l) {
        w[l] = start_window(begin + l * lane);
        acc[l] = 0.0;
      }
      for (std::int64_t t = 0; t < lane; ++t) {
        for (std::int64_t l = 0; l < kLanes; ++l) {
          const std::int64_t jl = begin + l * lane + t;
          acc[l] += w[l] * w[l];
          w[l] += d(jl + m) - d(jl);
        }
      }
      for (std::int64_t l = 0; l < kLanes; ++l) s += acc[l];
      j = begin + kLanes * lane;
    }
    double window = start_window(j);
    for (; j < end; ++j) {
      s += window * window;
      if (j + 1 < terms) window += d(j + m) - d(j);
    }
    partial[c] = s;
  }
  CompensatedSum total;
  for (const double v : partial) total.add(v);
  return total.value();
}

// Total variance: second differences at i = 1 .. N-2 of the record extended
// by point reflection at both ends (SP1065 section 5.2.11). For i in
// [m, N-1-m] no reflection is involved and the terms are exactly the OADEV
// terms, so only the 2(m-1) edge terms are computed here; the caller adds
// the OADEV sum of the same factor.
double total_edge_sum(std::span<const double> x, std::int64_t m) {
  const auto n = static_cast<std::int64_t>(x.size());
  const double* p = x.data();
  auto extended = [p, n](std::int64_t k) {
    if (k < 0) return 2.0 * p[0] - p[-k];
    if (k > n - 1) return 2.0 * p[n - 1] - p[2 * (n - 1) - k];
    return p[k];
  };
  CompensatedSum s;
  auto add = [&](std::int64_t i) {
    const double d = extended(i - m) - 2.0 * p[i] + extended(i + m);
    s.add(d * d);
  };
  for (std::int64_t i = 1; i < std::min(m, n - 1); ++i) add(i);               // left edge
  for (std::int64_t i = std::max(m, n - m); i <= n - 2; ++i) add(i);          // right edge
  return s.value();
}

std::int64_t term_count(AllanKind kind, std::int64_t n, std::int64_t m) {
  switch (kind) {
    case AllanKind::adev: return (n - 1) / m - 1;
    case AllanKind::oadev: return n - 2 * m;
    case AllanKind::mdev:
    case AllanKind::tdev: return n - 3 * m + 1;
    case AllanKind::hdev: return (n - 1) / m - 2;
    case AllanKind::ohdev: return n - 3 * m;
    case AllanKind::totdev: return n - 2;
    case AllanKind::mtotdev:
    case AllanKind::ttotdev:
      return n - 3 * m + 1;
    case AllanKind::htotdev:
      return n - 3 * m;
    case AllanKind::theo1:
      return (n - m) * (m / 2);
  }
  return 0;
}

}  // namespace

std::string_view to_string(AllanKind kind) {
  switch (kind) {
    case AllanKind::adev: return "adev";
    case AllanKind::oadev: return "oadev";
    case AllanKind::mdev: return "mdev";
    case AllanKind::hdev: return "hdev";
    case AllanKind::ohdev: return "ohdev";
    case AllanKind::tdev: return "tdev";
    case AllanKind::totdev: return "totdev";
    case AllanKind::mtotdev:
      return "mtotdev";
    case AllanKind::ttotdev:
      return "ttotdev";
    case AllanKind::htotdev:
      return "htotdev";
    case AllanKind::theo1:
      return "theo1";
  }
  return "?";
}

AllanKind allan_kind_from_string(std::string_view text) {
  for (const AllanKind kind : kKinds) {
    if (to_string(kind) == text) return kind;
  }
  throw UsageError(fmt::format(
      "unknown statistic '{}': expected adev, oadev, mdev, hdev, ohdev, tdev, totdev, mtotdev, "
      "ttotdev, htotdev or theo1",
      text));
}

std::span<const AllanKind> all_allan_kinds() { return kKinds; }

std::string_view to_string(NoiseRules rules) {
  return rules == NoiseRules::stable32 ? "stable32" : "foglab";
}

bool is_time_deviation(AllanKind kind) {
  return kind == AllanKind::tdev || kind == AllanKind::ttotdev;
}

NoiseRules noise_rules_from_string(std::string_view text) {
  if (text == "foglab") return NoiseRules::foglab;
  if (text == "stable32") return NoiseRules::stable32;
  throw UsageError(
      fmt::format("unknown noise identification rules '{}': expected foglab or stable32", text));
}

std::int64_t max_factor(AllanKind kind, std::int64_t phase_points) {
  const std::int64_t n = phase_points;
  switch (kind) {
    case AllanKind::adev:
    case AllanKind::oadev:
    case AllanKind::totdev: return (n - 1) / 2;
    case AllanKind::mdev:
    case AllanKind::tdev: return n / 3;
    case AllanKind::hdev:
    case AllanKind::ohdev:
    case AllanKind::htotdev:
      return (n - 1) / 3;
    case AllanKind::mtotdev:
    case AllanKind::ttotdev:
      return n / 3;
    case AllanKind::theo1:
      return (n - 1) / 2 * 2 >= kTheo1MinFactor ? (n - 1) / 2 * 2 : 0;
  }
  return 0;
}

std::vector<double> detail::deviations_from_phase(std::span<const double> phase, AllanKind kind,
                                                  std::span<const std::int64_t> factors,
                                                  std::vector<std::int64_t>* terms) {
  const auto n = static_cast<std::int64_t>(phase.size());
  const std::int64_t limit = max_factor(kind, n);
  std::vector<std::int64_t> counts(factors.size());
  for (std::size_t k = 0; k < factors.size(); ++k) {
    if (factors[k] < 1 || factors[k] > limit) {
      throw DataError(fmt::format(
          "{} at averaging factor {} needs more data: {} angle points allow factors {} to {}",
          to_string(kind), factors[k], n, kind == AllanKind::theo1 ? kTheo1MinFactor : 1, limit));
    }
    if (kind == AllanKind::theo1 && (factors[k] % 2 != 0 || factors[k] < kTheo1MinFactor)) {
      throw UsageError(fmt::format("theo1 needs even averaging factors of at least {}, not {}",
                                   kTheo1MinFactor, factors[k]));
    }
    counts[k] = term_count(kind, n, factors[k]);
  }
  std::vector<double> sums(factors.size());
  switch (kind) {
    case AllanKind::oadev: sums = overlapping_sums<2>(phase, factors); break;
    case AllanKind::totdev:
      sums = overlapping_sums<2>(phase, factors);
      for (std::size_t k = 0; k < factors.size(); ++k) sums[k] += total_edge_sum(phase, factors[k]);
      break;
    case AllanKind::ohdev: sums = overlapping_sums<3>(phase, factors); break;
    case AllanKind::htotdev: {
      // The rate record, y_k = x_{k+1} - x_k; at m = 1 the OHDEV sum.
      std::vector<double> rate(phase.size() - 1);
      for (std::size_t k = 0; k + 1 < phase.size(); ++k) rate[k] = phase[k + 1] - phase[k];
      for (std::size_t k = 0; k < factors.size(); ++k) {
        const std::int64_t m = factors[k];
        sums[k] = m == 1 ? overlapping_sums<3>(phase, factors.subspan(k, 1))[0]
                         : detail::total_modified_sum(rate, m);
      }
      break;
    }
    case AllanKind::theo1:
      sums = detail::theo1_sums(phase, factors);
      break;
    default:
      for (std::size_t k = 0; k < factors.size(); ++k) {
        const std::int64_t m = factors[k];
        switch (kind) {
          case AllanKind::adev: sums[k] = strided_sum<2>(phase, m, counts[k]); break;
          case AllanKind::hdev: sums[k] = strided_sum<3>(phase, m, counts[k]); break;
          case AllanKind::mdev:
          case AllanKind::tdev: sums[k] = modified_sum(phase, m, counts[k]); break;
          case AllanKind::mtotdev:
          case AllanKind::ttotdev:
            sums[k] = detail::total_modified_sum(phase, m);
            break;
          default: break;
        }
      }
  }
  // In tau0 = 1 units the tau^2 of the definitions is m^2 (allan.h).
  std::vector<double> dev(factors.size());
  for (std::size_t k = 0; k < factors.size(); ++k) {
    const double m = static_cast<double>(factors[k]);
    const double count = static_cast<double>(counts[k]);
    double variance = 0.0;
    switch (kind) {
      case AllanKind::adev:
      case AllanKind::oadev:
      case AllanKind::totdev: variance = sums[k] / (2.0 * m * m * count); break;
      case AllanKind::hdev:
      case AllanKind::ohdev: variance = sums[k] / (6.0 * m * m * count); break;
      case AllanKind::mdev:
      case AllanKind::tdev: variance = sums[k] / (2.0 * m * m * m * m * count); break;
      case AllanKind::mtotdev:
      case AllanKind::ttotdev:
        variance = sums[k] / (12.0 * m * m * m * m * m * count);
        break;
      case AllanKind::htotdev:
        variance = factors[k] == 1 ? sums[k] / (6.0 * count) : sums[k] / (36.0 * m * m * m * count);
        break;
      case AllanKind::theo1: {
        const double outer = static_cast<double>(n - factors[k]);  // N - m
        variance = sums[k] / (0.75 * outer * m * m);
        break;
      }
    }
    dev[k] = std::sqrt(variance);
  }
  if (terms != nullptr) *terms = std::move(counts);
  return dev;
}

namespace {

// The edf of a statistic at factor m, pooled over the stretches of
// `segment_points` angle points (one stretch without gaps).
double statistic_edf(AllanKind kind, int alpha, std::int64_t m,
                     std::span<const std::int64_t> segment_points) {
  switch (kind) {
    case AllanKind::adev:
      return pooled_edf(alpha, m, segment_points, {.stride = Stride::non_overlapping});
    case AllanKind::oadev: return pooled_edf(alpha, m, segment_points);
    case AllanKind::mdev:
    case AllanKind::tdev: return pooled_edf(alpha, m, segment_points, {.filter = Filter::modified});
    case AllanKind::hdev:
      return pooled_edf(alpha, m, segment_points, {.order = 3, .stride = Stride::non_overlapping});
    case AllanKind::ohdev: return pooled_edf(alpha, m, segment_points, {.order = 3});
    case AllanKind::totdev: return pooled_totdev_edf(alpha, m, segment_points);
    case AllanKind::mtotdev:
    case AllanKind::ttotdev:
      return pooled_mtotdev_edf(alpha, m, segment_points);
    case AllanKind::htotdev:
      return pooled_htotdev_edf(alpha, m, segment_points);
    case AllanKind::theo1:
      return pooled_theo1_edf(alpha, m, segment_points);
  }
  return std::numeric_limits<double>::quiet_NaN();
}

// The term spread check (AllanResult::edf_reduction): at most this many
// angle points are read, in batches of max(kBatchPerFactor m, kShortestBatch)
// terms and every doubling of that length that leaves kFewestBatches.
constexpr std::int64_t kSpreadCheckPoints = std::int64_t{1} << 21;
constexpr std::int64_t kBatchPerFactor = 64;
constexpr std::int64_t kShortestBatch = 1024;
constexpr std::int64_t kFewestBatches = 64;
constexpr double kSpreadCheckFalseAlarm = 0.001;

// The exact OADEV edf of white rate noise at m = 1 from n + 2 angle
// points: 2 n^2 / (3 n - 1) for its n sampled terms (their lag-one
// correlation is -1/2; tests/model/allan_covariance_test.cc). Greenhall's
// is 1.174 times that, and against it the term spread check had seen the
// excess on long records of white noise.
double white_m1_edf(std::size_t points) {
  const auto n = static_cast<double>(points) - 2.0;
  return 2.0 * n * n / (3.0 * n - 1.0);
}

// What the OADEV edf `edf` of the angle points `phase` at factor m is to be
// divided by: the variance of the mean of the squared second differences
// from the spread of batch means, over 2 mean^2 / edf, where that ratio is
// beyond chance; 1 otherwise or where too few batches fit. Short batches
// see only the correlation shorter than they are, long ones are few: every
// doubling of the batch is tried and the largest ratio beyond chance
// taken, each tried at kSpreadCheckFalseAlarm over the number of lengths.
double edf_reduction(std::span<const double> phase, std::int64_t m, double edf) {
  const auto terms = static_cast<std::int64_t>(phase.size()) - 2 * m;
  const std::int64_t shortest = std::max(kBatchPerFactor * m, kShortestBatch);
  if (terms / shortest < kFewestBatches || !(edf > 0.0)) return 1.0;
  std::vector<double> sums(static_cast<std::size_t>(terms / shortest));
  for (std::size_t b = 0; b < sums.size(); ++b) {
    double sum = 0.0;
    const auto first = b * static_cast<std::size_t>(shortest);
    for (std::size_t i = first; i < first + static_cast<std::size_t>(shortest); ++i) {
      const double d = phase[i + 2 * static_cast<std::size_t>(m)] -
                       2.0 * phase[i + static_cast<std::size_t>(m)] + phase[i];
      sum += d * d;
    }
    sums[b] = sum;
  }
  int lengths = 0;
  for (std::int64_t b = std::ssize(sums); b >= kFewestBatches; b /= 2) ++lengths;
  double reduction = 1.0;
  for (std::int64_t batch = shortest; std::ssize(sums) >= kFewestBatches; batch *= 2) {
    const double count = static_cast<double>(sums.size());
    double mean = 0.0;
    for (double x : sums) mean += x;
    mean /= count;
    // Neighbours' differences (von Neumann's mean square successive
    // difference): a slow change of the noise over the run, which the
    // record's Allan variance averages, does not count as its spread.
    double spread = 0.0;
    for (std::size_t b = 1; b < sums.size(); ++b) {
      spread += (sums[b] - sums[b - 1]) * (sums[b] - sums[b - 1]);
    }
    spread /= 2.0 * (count - 1.0);
    if (!(mean > 0.0)) return 1.0;
    // per term, and the noise type's edf for the batches' terms alone
    const double term_mean = mean / static_cast<double>(batch);
    const double spread_of_mean = spread / (static_cast<double>(batch * batch) * count);
    const double batches_edf =
        edf * count * static_cast<double>(batch) / static_cast<double>(terms);
    const double ratio = spread_of_mean * batches_edf / (2.0 * term_mean * term_mean);
    // that spread's degrees of freedom for independent batches:
    // 2 (n - 1)^2 / (3 n - 4) for n batches
    const double dof = 2.0 * (count - 1.0) * (count - 1.0) / (3.0 * count - 4.0);
    const double chance = chi2_quantile(dof, 1.0 - kSpreadCheckFalseAlarm / lengths) / dof;
    if (ratio > chance) reduction = std::max(reduction, ratio);
    // the next length: pairs of these batches
    for (std::size_t b = 0; 2 * b + 1 < sums.size(); ++b) sums[b] = sums[2 * b] + sums[2 * b + 1];
    sums.resize(sums.size() / 2);
  }
  return reduction;
}

// Theo1's averaging factors: a generated grid's even factors from
// kTheo1MinFactor on; an explicit list's Theo1 taus (0.75 m / fs) each at the
// nearest even factor.
std::vector<std::int64_t> theo1_factors(const TauGrid& grid, std::int64_t phase_points,
                                        double sample_rate_hz, std::int64_t limit) {
  std::vector<std::int64_t> factors;
  if (grid.kind == TauGridKind::list) {
    for (const double tau_s : grid.taus_s) {
      if (!(tau_s > 0.0) || !std::isfinite(tau_s)) {
        throw UsageError(fmt::format("tau {} s is not positive", tau_s));
      }
      // The nearest even factor to tau / (0.75 tau0), at least the smallest.
      const double half = tau_s * sample_rate_hz / 1.5;
      const std::int64_t m = std::max<std::int64_t>(
          kTheo1MinFactor, 2 * static_cast<std::int64_t>(std::llround(half)));
      if (m > limit) {
        throw DataError(fmt::format(
            "theo1 tau {} s needs more samples than the record has: {} angle points allow "
            "theo1 taus up to {} s",
            tau_s, phase_points, 0.75 * static_cast<double>(limit) / sample_rate_hz));
      }
      factors.push_back(m);
    }
    return factors;
  }
  for (const std::int64_t m : averaging_factors(grid, phase_points, sample_rate_hz, limit)) {
    if (m % 2 == 0 && m >= kTheo1MinFactor) factors.push_back(m);
  }
  return factors;
}

// The stretches' pooled sums: each factor's variance times its terms,
// summed over every stretch long enough for it, and the terms (allan.h,
// "Gaps"); `factors` ascend.
void pooled_sums(std::span<const double> phase, std::span<const Stretch> stretches, AllanKind kind,
                 std::span<const std::int64_t> factors, std::vector<double>& weighted,
                 std::vector<std::int64_t>& terms) {
  weighted.assign(factors.size(), 0.0);
  terms.assign(factors.size(), 0);
  for (const Stretch& s : stretches) {
    const std::int64_t limit = max_factor(kind, s.size());
    const auto usable = static_cast<std::size_t>(
        std::upper_bound(factors.begin(), factors.end(), limit) - factors.begin());
    if (usable == 0) continue;
    std::vector<std::int64_t> counts;
    const std::vector<double> dev = detail::deviations_from_phase(
        phase.subspan(static_cast<std::size_t>(s.begin), static_cast<std::size_t>(s.size())), kind,
        factors.first(usable), &counts);
    for (std::size_t k = 0; k < usable; ++k) {
      weighted[k] += dev[k] * dev[k] * static_cast<double>(counts[k]);
      terms[k] += counts[k];
    }
  }
}

// The stretches' pooled deviations: sum / count over the terms of every
// stretch long enough for a factor.
std::vector<double> pooled_deviations(std::span<const double> phase,
                                      std::span<const Stretch> stretches, AllanKind kind,
                                      std::span<const std::int64_t> factors,
                                      std::vector<std::int64_t>& terms) {
  std::vector<double> weighted;
  pooled_sums(phase, stretches, kind, factors, weighted, terms);
  std::vector<double> dev(factors.size());
  for (std::size_t k = 0; k < factors.size(); ++k) {
    dev[k] = std::sqrt(weighted[k] / static_cast<double>(terms[k]));
  }
  return dev;
}

// Where a rate record's samples sit on its whole time axis, the missing
// ones counted: per stretch of the samples present, its first sample's place
// on the axis and among those present, and its length; each gap's places.
struct TimeAxis {
  std::vector<std::int64_t> full_begin, present_begin, length;
  std::vector<std::pair<std::int64_t, std::int64_t>> gaps;  // [start, end) on the axis
  std::vector<bool> bridged;                                // per gap: a term may span it
  std::int64_t samples = 0;                                 // present and missing
};

// The time axis of a rate record of `samples` samples with `gaps`, of
// which those whose before_sample is in `unbridged` no term may span.
TimeAxis time_axis(std::int64_t samples, std::span<const Gap> gaps,
                   std::span<const std::int64_t> unbridged) {
  TimeAxis a;
  std::int64_t missing = 0, begin = 0;
  auto stretch_to = [&](std::int64_t end) {
    a.full_begin.push_back(begin + missing);
    a.present_begin.push_back(begin);
    a.length.push_back(end - begin);
  };
  for (const Gap& g : gaps) {
    stretch_to(g.before_sample);
    a.gaps.emplace_back(g.before_sample + missing, g.before_sample + missing + g.missing_samples);
    a.bridged.push_back(std::ranges::find(unbridged, g.before_sample) == unbridged.end());
    missing += g.missing_samples;
    begin = g.before_sample;
  }
  stretch_to(samples);
  a.samples = samples + missing;
  return a;
}

// The number of samples present before place x of the time axis; x may
// only grow from one call to the next.
class PresentBefore {
 public:
  explicit PresentBefore(const TimeAxis& axis) : axis_(axis) {}
  std::int64_t operator()(std::int64_t x) {
    while (s_ + 1 < axis_.full_begin.size() && axis_.full_begin[s_ + 1] <= x) ++s_;
    return axis_.present_begin[s_] +
           std::clamp<std::int64_t>(x - axis_.full_begin[s_], 0, axis_.length[s_]);
  }

 private:
  const TimeAxis& axis_;
  std::size_t s_ = 0;
};

// The overlapping Allan terms at factor m that span a gap and whose two
// clusters each miss at most `allowed` samples, each cluster's mean taken
// over the samples it has: the sum of their halved squares, and their
// count. `phase` is the rate's angle record (tau0 = 1 units).
std::pair<double, std::int64_t> gap_spanning_sums(std::span<const double> phase,
                                                  const TimeAxis& axis, std::int64_t m,
                                                  std::int64_t allowed) {
  const double* x = phase.data();
  double sum = 0.0;
  std::int64_t terms = 0;
  PresentBefore at_a(axis), at_b(axis), at_c(axis);
  const std::int64_t last = axis.samples - 2 * m;  // the last term's first place
  std::int64_t next = 0;                           // the first place not yet visited
  std::size_t hard = 0;  // the first gap no term may span that ends after place i
  for (const auto& [start, end] : axis.gaps) {
    // the terms whose span [i, i + 2m) holds a place of [start, end)
    const std::int64_t from = std::max({next, start - 2 * m + 1, std::int64_t{0}});
    const std::int64_t to = std::min(end - 1, last);
    for (std::int64_t i = from; i <= to; ++i) {
      while (hard < axis.gaps.size() && (axis.bridged[hard] || axis.gaps[hard].second <= i)) {
        ++hard;
      }
      if (hard < axis.gaps.size() && axis.gaps[hard].first < i + 2 * m) continue;
      const std::int64_t a = at_a(i), b = at_b(i + m), c = at_c(i + 2 * m);
      const std::int64_t first = b - a, second = c - b;
      if (m - first > allowed || m - second > allowed) continue;
      const double d =
          (x[c] - x[b]) / static_cast<double>(second) - (x[b] - x[a]) / static_cast<double>(first);
      sum += 0.5 * d * d;
      ++terms;
    }
    next = std::max(next, to + 1);
  }
  return {sum, terms};
}

// The record's parts that the bridged gaps join: the stretches, merged
// across each gap a term may span. Each part's first and last stretch.
std::vector<std::pair<std::size_t, std::size_t>> bridged_parts(const TimeAxis& a) {
  std::vector<std::pair<std::size_t, std::size_t>> parts;
  std::size_t first = 0;
  for (std::size_t s = 0; s + 1 < a.full_begin.size(); ++s) {
    if (a.bridged[s]) continue;
    parts.emplace_back(first, s);
    first = s + 1;
  }
  parts.emplace_back(first, a.full_begin.size() - 1);
  return parts;
}

// A part's angle points, the missing samples' places counted.
std::int64_t part_points(const TimeAxis& a, std::pair<std::size_t, std::size_t> part) {
  return a.full_begin[part.second] + a.length[part.second] - a.full_begin[part.first] + 1;
}

// A part's angle record with each missing sample at the record's mean (a
// zero step): for identifying the noise where no stretch is long enough,
// never for the statistic itself.
std::vector<double> part_with_mean_filled(std::span<const double> phase, const TimeAxis& axis,
                                          std::pair<std::size_t, std::size_t> part) {
  std::vector<double> filled(static_cast<std::size_t>(part_points(axis, part)));
  std::size_t k = 0;
  filled[0] = phase[static_cast<std::size_t>(axis.present_begin[part.first])];
  for (std::size_t s = part.first; s <= part.second; ++s) {
    if (s > part.first) {  // the gap before stretch s
      const std::int64_t missing = axis.gaps[s - 1].second - axis.gaps[s - 1].first;
      for (std::int64_t j = 0; j < missing; ++j, ++k) filled[k + 1] = filled[k];
    }
    for (std::int64_t j = 0; j < axis.length[s]; ++j, ++k) {
      const auto p = static_cast<std::size_t>(axis.present_begin[s] + j);
      filled[k + 1] = filled[k] + (phase[p + 1] - phase[p]);
    }
  }
  return filled;
}

// The statistic on an angle record made by to_phase(), whose contiguous
// stretches are `stretches` (angle points); `record_samples` is the length
// of the original record, for messages; `gaps` its gaps (for
// AllanOptions::max_missing_share).
AllanResult allan_from_phase(std::span<const double> phase, std::span<const Stretch> stretches,
                             std::size_t record_samples, double sample_rate_hz, InputKind input,
                             const AllanOptions& options, std::span<const Gap> gaps) {
  if (!(options.max_missing_share >= 0.0 && options.max_missing_share <= 0.1)) {
    throw UsageError(fmt::format("AllanOptions::max_missing_share must lie in [0, 0.1], got {}",
                                 options.max_missing_share));
  }
  const auto n = static_cast<std::int64_t>(phase.size());
  const Stretch longest =
      *std::max_element(stretches.begin(), stretches.end(),
                        [](const Stretch& a, const Stretch& b) { return a.size() < b.size(); });
  const std::int64_t limit = max_factor(options.kind, longest.size());
  if (limit < 1) {
    std::int64_t needed = 1;  // angle points for the smallest averaging factor
    while (max_factor(options.kind, needed) < 1) ++needed;
    const std::int64_t longest_samples = longest.size() - (input == InputKind::rate ? 1 : 0);
    throw DataError(fmt::format(
        "{} needs at least {} {} samples, the {} {}", to_string(options.kind),
        input == InputKind::rate ? needed - 1 : needed, to_string(input),
        stretches.size() > 1 ? "longest stretch between gaps has" : "record has",
        stretches.size() > 1 ? longest_samples : static_cast<std::int64_t>(record_samples)));
  }
  AllanResult result;
  result.kind = options.kind;
  result.input = input;
  result.sample_rate_hz = sample_rate_hz;
  result.phase_points = n;
  for (const Stretch& s : stretches) result.segment_points.push_back(s.size());
  const std::vector<std::int64_t> stretch_points = result.segment_points;
  // Clusters that may miss a few samples: the gaps a term at the whole time
  // axis's longest tau could span (each cluster missing at most its share)
  // are bridged, the rest, and those asked for, split the record as before.
  // With none bridged, nothing changes; else the grid runs over the axis.
  TimeAxis axis;
  std::vector<std::int64_t> axis_factors;
  if (options.max_missing_share > 0.0 && !gaps.empty() && input == InputKind::rate &&
      options.kind == AllanKind::oadev) {
    const std::int64_t axis_points =
        static_cast<std::int64_t>(record_samples) + missing_samples(gaps) + 1;
    axis_factors = averaging_factors(options.grid, axis_points, sample_rate_hz,
                                     max_factor(options.kind, axis_points));
    const std::int64_t widest =
        axis_factors.empty()
            ? 0
            : 2 * static_cast<std::int64_t>(std::floor(options.max_missing_share *
                                                       static_cast<double>(axis_factors.back())));
    std::vector<std::int64_t> unbridged = options.unbridged_gaps;
    for (const Gap& g : gaps) {
      if (g.missing_samples > widest) unbridged.push_back(g.before_sample);
    }
    axis = time_axis(static_cast<std::int64_t>(record_samples), gaps, unbridged);
  }
  const bool bridging = std::ranges::find(axis.bridged, true) != axis.bridged.end();
  // The parts the bridged gaps join, in time order, and the longest: no
  // term is longer.
  std::vector<std::pair<std::size_t, std::size_t>> parts;
  std::pair<std::size_t, std::size_t> longest_part;
  if (bridging) {
    parts = bridged_parts(axis);
    longest_part =
        *std::ranges::max_element(parts, {}, [&](const auto& p) { return part_points(axis, p); });
    if (options.grid.kind != TauGridKind::list) {  // a listed tau beyond it is an error below
      std::erase_if(axis_factors, [&](std::int64_t m) {
        return m > max_factor(options.kind, part_points(axis, longest_part));
      });
    }
  }
  result.m = options.kind == AllanKind::theo1
                 ? theo1_factors(options.grid, n, sample_rate_hz, limit)
             : bridging ? axis_factors
                        : averaging_factors(options.grid, n, sample_rate_hz, limit);
  if (result.m.empty() && options.kind == AllanKind::theo1) {
    throw DataError(fmt::format(
        "{} {} samples are too few for theo1 with at least {} clusters per tau: its averaging "
        "factors are even and at least {}; lower TauGrid::min_clusters or list the taus in "
        "TauGrid::taus_s",
        record_samples, to_string(input), options.grid.min_clusters, kTheo1MinFactor));
  }
  if (result.m.empty()) {
    throw DataError(fmt::format(
        "{} {} samples are too few for {} with at least {} clusters per tau "
        "({} samples needed); lower TauGrid::min_clusters or list the taus in TauGrid::taus_s",
        record_samples, to_string(input), to_string(options.kind), options.grid.min_clusters,
        options.grid.min_clusters + (input == InputKind::rate ? 0 : 1)));
  }
  if (bridging) {
    std::vector<double> weighted;
    pooled_sums(phase, stretches, options.kind, result.m, weighted, result.n);
    result.gap_spanning_terms.assign(result.m.size(), 0);
    for (std::size_t k = 0; k < result.m.size(); ++k) {
      const std::int64_t m = result.m[k];
      const auto allowed =
          static_cast<std::int64_t>(std::floor(options.max_missing_share * static_cast<double>(m)));
      if (allowed < 1) continue;
      const auto [sum, terms] = gap_spanning_sums(phase, axis, m, allowed);
      weighted[k] += sum;
      result.n[k] += terms;
      result.gap_spanning_terms[k] = terms;
    }
    // A tau stays while its terms fill (min_clusters - 2) m, as a gap-free
    // record's do at the grid's end; a listed tau needs one term.
    std::size_t kept = 0;
    for (std::size_t k = 0; k < result.m.size(); ++k) {
      const std::int64_t m = result.m[k];
      const bool enough =
          options.grid.kind == TauGridKind::list
              ? result.n[k] > 0
              : result.n[k] >= std::max<std::int64_t>(1, options.grid.min_clusters - 2) * m;
      if (!enough && options.grid.kind == TauGridKind::list) {
        throw DataError(fmt::format(
            "tau {} s: no Allan term of two clusters each missing at most {} % of their samples "
            "in this record with gaps",
            static_cast<double>(m) / sample_rate_hz, 100.0 * options.max_missing_share));
      }
      if (!enough) continue;
      result.m[kept] = m, result.n[kept] = result.n[k], weighted[kept] = weighted[k];
      result.gap_spanning_terms[kept] = result.gap_spanning_terms[k];
      ++kept;
    }
    result.m.resize(kept), result.n.resize(kept), weighted.resize(kept);
    result.gap_spanning_terms.resize(kept);
    result.dev.resize(kept);
    result.term_share.resize(kept);
    // The record's parts as the bridged gaps join them; each tau's terms
    // over theirs.
    result.segment_points.clear();
    for (const auto& part : parts) result.segment_points.push_back(part_points(axis, part));
    for (std::size_t k = 0; k < kept; ++k) {
      result.dev[k] = std::sqrt(weighted[k] / static_cast<double>(result.n[k]));
      std::int64_t model_terms = 0;
      for (const std::int64_t points : result.segment_points) {
        model_terms += std::max<std::int64_t>(0, points - 2 * result.m[k]);
      }
      result.term_share[k] = static_cast<double>(result.n[k]) /
                             static_cast<double>(std::max<std::int64_t>(1, model_terms));
    }
  } else {
    result.dev = stretches.size() == 1
                     ? detail::deviations_from_phase(phase, options.kind, result.m, &result.n)
                     : pooled_deviations(phase, stretches, options.kind, result.m, result.n);
  }
  const std::size_t count = result.m.size();
  const double tau0_s = 1.0 / sample_rate_hz;
  result.tau_s.resize(count);
  const bool time_like = is_time_deviation(options.kind);
  for (std::size_t k = 0; k < count; ++k) {
    const double m = static_cast<double>(result.m[k]);
    result.tau_s[k] = (options.kind == AllanKind::theo1 ? 0.75 * m : m) * tau0_s;
    if (time_like) result.dev[k] *= result.tau_s[k] / std::sqrt(3.0);
  }

  const double nan = std::numeric_limits<double>::quiet_NaN();
  result.alpha.assign(count, 0);
  result.alpha_method.assign(count, AlphaMethod{});
  result.edf.assign(count, nan);
  result.edf_reduction.assign(count, 1.0);
  result.ci68_low.assign(count, nan);
  result.ci68_high.assign(count, nan);
  result.ci95_low.assign(count, nan);
  result.ci95_high.assign(count, nan);
  const bool htot_bias = options.kind == AllanKind::htotdev && options.bias_correction;
  if (!options.confidence && !htot_bias) return result;

  const bool hadamard = options.kind == AllanKind::hdev || options.kind == AllanKind::ohdev ||
                        options.kind == AllanKind::htotdev;
  // Theo1 at factor m speaks for tau = 0.75 m: its noise is identified there.
  std::vector<std::int64_t> id_factors = result.m;
  if (options.kind == AllanKind::theo1) {
    for (std::int64_t& m : id_factors) m = std::max<std::int64_t>(1, (3 * m + 2) / 4);
  }
  const std::span<const double> longest_phase = phase.subspan(
      static_cast<std::size_t>(longest.begin), static_cast<std::size_t>(longest.size()));
  std::vector<NoiseId> ids = identify_noise(longest_phase, id_factors, hadamard ? 3 : 2);
  if (bridging) {  // beyond the longest stretch: the longest part the bridged gaps join,
                   // its missing samples at the record's mean
    std::vector<std::int64_t> beyond;
    for (std::size_t k = 0; k < count; ++k) {
      if (ids[k].method == NoiseIdMethod::none) beyond.push_back(id_factors[k]);
    }
    if (!beyond.empty()) {
      const std::vector<NoiseId> more = identify_noise(
          part_with_mean_filled(phase, axis, longest_part), beyond, hadamard ? 3 : 2);
      for (std::size_t k = 0, j = 0; k < count; ++k) {
        if (ids[k].method == NoiseIdMethod::none) ids[k] = more[j++];
      }
    }
  }
  // Phase-noise types (alpha > 0, ADEV ~ 1/tau) fall faster than every other
  // term, so once a frequency-noise type dominates at some tau, phase noise
  // cannot dominate at a longer one. With few decimated points the lag-1
  // method sometimes calls white FM "PM", which would give a far too large
  // edf, and so does B1 with 8-30 averages; such calls beyond the shortest
  // FM tau are taken as white FM, unless Stable32's rules are asked for.
  std::int64_t shortest_fm_m = std::numeric_limits<std::int64_t>::max();
  for (std::size_t k = 0; k < count; ++k) {
    if (ids[k].method != NoiseIdMethod::none && ids[k].alpha <= 0) {
      shortest_fm_m = std::min(shortest_fm_m, result.m[k]);
    }
  }
  // The term spread check reads the start of the longest stretch.
  const std::span<const double> checked = longest_phase.first(
      std::min<std::size_t>(longest_phase.size(), static_cast<std::size_t>(kSpreadCheckPoints)));
  int previous_alpha = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const std::int64_t m = result.m[k];
    NoiseId id = ids[k];
    AlphaMethod how{id.method, false};
    if (id.method == NoiseIdMethod::none) id.alpha = previous_alpha;
    if (id.alpha > 0 && m > shortest_fm_m && options.noise_rules == NoiseRules::foglab) {
      id.alpha = 0;
      how.fm_floor = true;
    }
    previous_alpha = id.alpha;
    result.alpha[k] = id.alpha;
    result.alpha_method[k] = how;
    if (htot_bias) result.dev[k] /= std::sqrt(htotdev_bias(id.alpha, m));
    if (!options.confidence) continue;
    // where terms spanning gaps entered, the gap-free record's edf for the share of its terms
    double edf =
        bridging && result.gap_spanning_terms[k] > 0
            ? statistic_edf(options.kind, id.alpha, m, result.segment_points) * result.term_share[k]
            : statistic_edf(options.kind, id.alpha, m, stretch_points);
    if (options.term_spread_check && options.kind == AllanKind::oadev) {
      // the checked terms' edf by the noise type (Greenhall's), but white
      // noise's exact one at m = 1
      const double greenhall = greenhall_edf(id.alpha, m, std::ssize(checked));
      const double baseline = m == 1 && id.alpha == 0 ? white_m1_edf(checked.size()) : greenhall;
      if (const double ratio = edf_reduction(checked, m, baseline); ratio > 1.0) {
        // what the noise type's edf is divided by to give the checked terms' own
        result.edf_reduction[k] = ratio * greenhall / baseline;
        edf /= result.edf_reduction[k];
      }
    }
    result.edf[k] = edf;
    const Interval ci68 = chi2_interval(result.dev[k], edf, kConfidence68);
    const Interval ci95 = chi2_interval(result.dev[k], edf, kConfidence95);
    result.ci68_low[k] = ci68.low;
    result.ci68_high[k] = ci68.high;
    result.ci95_low[k] = ci95.low;
    result.ci95_high[k] = ci95.high;
  }
  return result;
}

// The contiguous stretches, in angle points, of a record of `samples`
// samples with `gaps`: a rate stretch [a, b) integrates to the angle points
// a .. b, an angle stretch is itself.
std::vector<Stretch> angle_stretches(std::size_t samples, InputKind input,
                                     std::span<const Gap> gaps) {
  std::vector<Stretch> stretches = contiguous_stretches(static_cast<std::int64_t>(samples), gaps);
  if (input == InputKind::rate) {
    for (Stretch& s : stretches) ++s.end;
  }
  return stretches;
}

}  // namespace

AllanResult allan_deviation(std::span<const double> samples, double sample_rate_hz, InputKind input,
                            const AllanOptions& options, std::span<const Gap> gaps) {
  check_gaps(gaps, static_cast<std::int64_t>(samples.size()), "allan_deviation");
  // Not a zero-filled vector: writing 8 N bytes of zeros on one thread cost as
  // much as the integration that overwrites them (bench_allan_stages).
  const std::size_t points = detail::phase_points(samples.size(), input);
  const auto phase = std::make_unique_for_overwrite<double[]>(points);
  advise_huge_pages(phase.get(), points);
  detail::to_phase_into(samples, sample_rate_hz, input, phase.get());
  return allan_from_phase(std::span<const double>(phase.get(), points),
                          angle_stretches(samples.size(), input, gaps), samples.size(),
                          sample_rate_hz, input, options, gaps);
}

AllanResult allan_deviation_in_place(std::vector<double>& samples, double sample_rate_hz,
                                     InputKind input, const AllanOptions& options,
                                     std::span<const Gap> gaps) {
  const std::size_t record_samples = samples.size();
  check_gaps(gaps, static_cast<std::int64_t>(record_samples), "allan_deviation");
  detail::to_phase_in_place(samples, sample_rate_hz, input);
  return allan_from_phase(samples, angle_stretches(record_samples, input, gaps), record_samples,
                          sample_rate_hz, input, options, gaps);
}

}  // namespace foglab::stats
