// foglab — numerically careful building blocks shared by the modules.
//
// Long gyro records (up to 10^9 samples) with a large constant bias demand
// compensated summation: a plain running sum of 10^9 values near 1e6 deg/h
// loses the 1e-3 deg/h noise entirely. These helpers use Neumaier's variant
// of Kahan summation (Neumaier 1974) inside fixed-size chunks, and combine
// chunk results in a fixed order so the answer does not depend on the number
// of threads.
#pragma once

#include <cstddef>
#include <limits>
#include <span>
#include <string_view>
#include <vector>

namespace foglab {

/// A quiet NaN: a value not measured, in result fields and tables.
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Neumaier (improved Kahan-Babuska) compensated accumulator.
class CompensatedSum {
 public:
  void add(double value) {
    const double t = sum_ + value;
    if ((sum_ >= 0 ? sum_ : -sum_) >= (value >= 0 ? value : -value)) {
      compensation_ += (sum_ - t) + value;
    } else {
      compensation_ += (value - t) + sum_;
    }
    sum_ = t;
  }
  void add(const CompensatedSum& other) {
    add(other.sum_);
    add(other.compensation_);
  }
  double value() const { return sum_ + compensation_; }

 private:
  double sum_ = 0.0;
  double compensation_ = 0.0;
};

/// Compensated sum of (values[i] - shift) over a short span (one chunk):
/// sixteen interleaved Kahan accumulators, so the loop vectorises, combined with
/// Neumaier's rule. Serial; the building block of the parallel sums below.
CompensatedSum chunk_sum(std::span<const double> values, double shift = 0.0);

/// chunk_sum() of every `chunk`-long piece of `values` (by default
/// kChunkSamples), in parallel; combining them in order gives a thread-count
/// independent result.
std::vector<CompensatedSum> chunk_sums(std::span<const double> values, double shift = 0.0,
                                       std::size_t chunk = 0);

/// Compensated sum of `values`, computed in parallel with a thread-count
/// independent result.
double compensated_sum(std::span<const double> values);

/// Compensated arithmetic mean of `values` (0 for an empty span).
double compensated_mean(std::span<const double> values);

/// The index of the first value of `values` that is NaN or infinite, or
/// values.size() if every one is finite; in parallel, a vectorised pass.
std::size_t first_non_finite(std::span<const double> values);

/// Throws DataError "the record is constant: all N samples equal X UNIT,
/// so there is no noise to analyse" when every value is the same (an
/// analysis of it would give deviations of 0, which no model fits). A
/// record of fewer than 2 samples passes (too short is said elsewhere).
void require_varying(std::span<const double> values, std::string_view unit = "deg/h");

/// The median of `values` (of an even count, the upper of the middle two),
/// found by reordering them in place (std::nth_element). Not empty.
double median_in_place(std::span<double> values);

/// A robust location and scale: the median and 1.4826 times the median
/// absolute deviation from it, the standard deviation for Gaussian data,
/// which a few outliers do not move (0 when more than half the values are
/// equal).
struct RobustSpread {
  double centre = 0.0;
  double spread = 0.0;
};
/// The robust centre and spread of `values` (not empty).
RobustSpread robust_spread(std::span<const double> values);

/// A vector of `size` copies of `fill` with room for `capacity` elements
/// (at least `size`), for records of up to 10^9 samples. On Linux the
/// memory is advised for transparent huge pages before it is first touched:
/// on virtual machines the first-touch page faults of a fresh 4 KiB-paged
/// array can cost more than the statistics computed on it (bench/RESULTS.md).
std::vector<double> large_vector(std::size_t size, double fill = 0.0, std::size_t capacity = 0);

/// Advises transparent huge pages for the not yet touched memory
/// [data, data + count) (Linux madvise; a no-op elsewhere or for small spans).
void advise_huge_pages(double* data, std::size_t count);

/// Number of worker threads foglab uses (OpenMP's limit, at least 1).
int worker_threads();

/// Work is split into chunks of this many samples for parallel loops; the
/// split, and therefore every floating-point result, is independent of the
/// number of threads. (Not of the processor: the hottest loops have an AVX2
/// form, whose sums run in another order, so a result may differ in its last
/// bits between a processor with AVX2 and one without.)
inline constexpr std::size_t kChunkSamples = std::size_t{1} << 16;

/// The two-sided 95 % point of the standard normal distribution.
inline constexpr double kZ95 = 1.959963984540054;

}  // namespace foglab
