// foglab — spikes: isolated outliers in a rate record (a bit error, a
// knock), found and taken out before the statistics, with what was done
// stated.
//
// A sample is a spike when it departs from the mean of its two neighbours,
// h_k = y_k - (y_(k-1) + y_(k+1)) / 2, by more than `threshold` robust
// standard deviations of h (1.4826 times the median absolute deviation of
// h, which a few spikes do not move; with an output word so coarse that
// this median is 0, the root mean square of h stands in). For Gaussian
// noise 8 of them is a false alarm about once in 10^15 samples. Each spike
// is replaced by the mean of its neighbours (a single sample's noise is
// lost, nothing is interpolated over a stretch); a spike's neighbours must
// each depart from their own neighbours by minus half of it, to within
// half the threshold, so a bias step or a run of two or more outlying
// samples is not a spike and is left alone.
//
// Heavy-tailed noise. Some sensors' noise is not Gaussian: bursts put
// outliers of every size into it, and a fixed threshold takes its tail for
// spikes (Student's t with 3 degrees of freedom: 750 "spikes" in 7.2 x 10^5
// samples, N 9 % low once they were replaced; the tail is part of the
// variance the angle accumulates). The outlier centres (|h| a local maximum)
// between 5 and 8 robust standard deviations tell: Gaussian noise puts
// 5.7 x 10^-7 of its samples there. When they are at least 25 and ten times
// that, the noise is taken as heavy-tailed: a power law S(x) ~ x^-alpha is
// fitted to the centres between 4 and 8 (the truncated Pareto law's maximum
// likelihood), and only departures beyond the size that law exceeds with
// probability 0.05 in the whole record are spikes.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace foglab::model {

/// Robust standard deviations of h beyond which Gaussian noise puts only
/// 5.7 x 10^-7 of its samples: where its bulk ends and a tail would show.
inline constexpr double kGaussianBulkEnd = 5.0;

struct SpikeOptions {
  bool remove = true;               ///< replace them (else only report them)
  double threshold = 8.0;           ///< robust standard deviations of h
  std::size_t max_reported = 1000;  ///< spikes listed individually
};

struct Spikes {
  std::int64_t count = 0;
  double robust_sd_deg_h = 0.0;       ///< [deg/h] of h, the scale of the threshold
  double threshold_deg_h = 0.0;       ///< [deg/h] threshold times that
  std::vector<std::int64_t> indices;  ///< the first max_reported, in order
  std::vector<double> sizes_deg_h;    ///< [deg/h] h at each
  bool removed = false;
  std::int64_t shoulder_count = 0;  ///< outlier centres between 5 and 8 robust sd
  double shoulder_expected = 0.0;   ///< what Gaussian noise puts there
  bool heavy_tailed = false;        ///< the shoulder holds the noise's own tail
  double tail_index = 0.0;          ///< its power law's alpha (heavy_tailed only)
  /// The noise's excess kurtosis, twice that of the record's first
  /// differences (heavy_tailed only): the sample variance, and with it N,
  /// scatters (2 + it) / 2 times as much as under Gaussian noise.
  double excess_kurtosis = 0.0;
};

/// Finds the spikes of `rate_deg_h` and, with options.remove, replaces
/// each by the mean of its neighbours in place. `lsb_deg_h` > 0: the output
/// word's step (model/output_quantisation.h); a spike then departs by at
/// least four of them (on an output whose step exceeds its noise, most
/// samples sit on one value, the robust scale collapses, and every
/// one-step excursion had been taken for a spike: 6,751 in one record).
Spikes find_spikes(std::span<double> rate_deg_h, const SpikeOptions& options = {},
                   double lsb_deg_h = 0.0);

}  // namespace foglab::model
