// foglab — spectral lines in a Welch PSD (spectral_lines.h).
#include "foglab/model/spectral_lines.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <numeric>
#include <optional>

#include "foglab/core/numeric.h"

namespace foglab::model {
namespace {

constexpr double kBandsPerDecade = 20.0;
constexpr double kSmoothing = 0.005;        // moving-average width, relative to f
constexpr double kSkirtSignificance = 4.0;  // a found line extends while they stand this many
                                            // standard errors above the floor
constexpr double kSkirtShare = 1e-3;        // of the line's peak excess, the least a skirt holds
constexpr double kSignificance = 10.0;      // its excess this many standard errors
constexpr std::size_t kClosedGap = 2;    // bins
// The long-segment PSD of the slow lines: segments the largest power of two
// up to half the longest stretch (3 segments or more at 50 % overlap), at
// most this long, of the record's means over blocks that leave this many
// samples a segment.
constexpr std::size_t kLongestSlowLineSegment = std::size_t{1} << 21;
constexpr std::size_t kSlowLineSegmentBlocks = 4096;
// A narrow line of the record's own PSD below this share of the block
// means' rate is tried as a sinusoid too (take_as_sinusoid()): the block
// mean passes it with at least 97 % of its amplitude, which the fit takes
// out, and nothing folds onto it.
constexpr double kSlowestBlockShare = 0.125;

// What makes a run of bins a line, for one noise floor.
struct LinePass {
  double floor_half_width;  // decades either side of a band's centre
  double bin_ratio;         // a line's smoothed bins stand this far above the floor
  double peak_ratio;        // its highest smoothed bin this far
  double least_width;       // the run of high bins at least this wide, relative to f
  double least_beside;      // beside the line (as far out as it is wide), the PSD stays this
                            // far above the floor
  std::size_t lowest_bin;   // runs of high bins start from this bin up (bin k lies at k + 1
                            // resolutions; a line's skirts may reach down to half of it)
};

// Narrow lines (a sinusoid, a resonance up to about a quarter of its
// frequency wide) over the median of +-0.2 decade, from the 17th bin up
// (the window holds 15 bins or more there, and a sinusoid's main lobe of 4
// does not lift its median).
constexpr LinePass kNarrow{0.2, 3.0, 4.0, 0.0, 0.0, 16};
// Broad humps, which lift that median themselves: an aliased resonance
// (the ADIS16405 z axes' 20 Hz resonance at 5 Hz when every fourth sample
// is kept, 3.5-7 Hz wide, its PSD 2.6-5 times the floor) over the median of
// +-0.5 decade; a run of high bins 0.15 of its frequency wide or more (the
// aliased humps' runs are 0.35-0.39 of it). Beside it the PSD stays at
// half the floor or more: a hump on the noise floor returns to it, while a
// moving average's side lobe (between its nulls at multiples of fs / k)
// falls into them (the side lobes of 6- to 24-sample averages had been
// taken for lines 3-9 Hz wide). From 64 resolutions up: over +-0.5 decade
// the median of a steep low-frequency spectrum (a random walk's 1/f^2) lies
// well under the PSD.
constexpr LinePass kBroad{0.5, 2.0, 2.5, 0.15, 0.5, 64};

// The noise floor at every bin: at the centre of each band of 1/20 decade,
// the median of the PSD within `half_width` decade either side (0.2 is wide
// enough that a resonance hump a quarter of its frequency wide does not lift
// it), interpolated in log-log between the centres.
std::vector<double> noise_floor(const stats::PsdResult& psd, double half_width) {
  const std::vector<double>& f = psd.frequency_hz;
  const std::size_t n = f.size();
  const double step = std::pow(10.0, 1.0 / kBandsPerDecade);
  const double half = std::pow(10.0, half_width);
  std::vector<double> centre, level, window;
  for (double fc = f.front(); fc <= f.back() * step; fc *= step) {
    const auto lo = std::lower_bound(f.begin(), f.end(), fc / half);
    const auto hi = std::upper_bound(f.begin(), f.end(), fc * half);
    if (hi - lo < 8) continue;
    window.assign(psd.psd.begin() + (lo - f.begin()), psd.psd.begin() + (hi - f.begin()));
    centre.push_back(std::log(fc));
    level.push_back(std::log(std::max(median_in_place(window), 1e-300)));
  }
  std::vector<double> floor(n, 0.0);
  if (centre.empty()) return floor;
  std::size_t j = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double x = std::log(f[k]);
    while (j + 1 < centre.size() && centre[j + 1] < x) ++j;
    double y = level[j];
    if (j + 1 < centre.size() && x > centre[j]) {
      const double w = (x - centre[j]) / (centre[j + 1] - centre[j]);
      y = (1.0 - w) * level[j] + w * level[j + 1];
    }
    floor[k] = std::exp(y);
  }
  return floor;
}

// The PSD averaged over a window 0.5 % of f wide (at least 3 bins), which
// takes the Welch estimate's scatter off a broad hump.
std::size_t smoothing_half_width(std::size_t k) {
  return static_cast<std::size_t>(std::max(1.0, 0.5 * kSmoothing * static_cast<double>(k)));
}

std::vector<double> smoothed(const stats::PsdResult& psd) {
  const std::size_t n = psd.psd.size();
  std::vector<double> prefix(n + 1, 0.0);
  for (std::size_t k = 0; k < n; ++k) prefix[k + 1] = prefix[k] + psd.psd[k];
  std::vector<double> out(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t h = smoothing_half_width(k);
    const std::size_t a = k >= h ? k - h : 0, b = std::min(n, k + h + 1);
    out[k] = (prefix[b] - prefix[a]) / static_cast<double>(b - a);
  }
  return out;
}

// Whether the smoothed PSD at bin k stands above the floor by more than its
// scatter allows: a Welch average of K segments over 2h+1 bins scatters by
// about sqrt(2 / (K (2h+1))) of its mean (the factor 2 for the Hann window's
// correlation of neighbouring bins).
bool above_floor(double smooth, double floor, std::size_t k, double segments) {
  const double bins = static_cast<double>(2 * smoothing_half_width(k) + 1);
  return smooth > floor * (1.0 + kSkirtSignificance * std::sqrt(2.0 / (segments * bins)));
}

// The lowest ratio of the PSD to the floor beside the bins [low, high], as
// far out on either side as they are wide, each side in bands of 1/100
// decade and at least 16 bins, a shorter remainder joined to the last
// (the mean PSD over the mean floor: a single bin's Welch scatter is too
// wide to take its least).
double lowest_beside(const stats::PsdResult& psd, const std::vector<double>& floor,
                     std::size_t lowest_bin, std::size_t low, std::size_t high) {
  const std::vector<double>& f = psd.frequency_hz;
  const std::size_t n = f.size(), reach = high - low + 1;
  constexpr std::size_t kLeastBins = 16;
  const double band = std::pow(10.0, 0.01);
  double lowest = std::numeric_limits<double>::infinity();
  auto scan = [&](std::size_t from, std::size_t to) {  // bins [from, to)
    std::size_t a = from;
    while (a < to) {
      std::size_t b = a + 1;
      while (b < to && (f[b] < f[a] * band || b - a < kLeastBins)) ++b;
      if (to - b < kLeastBins) b = to;  // a short remainder joins this band
      double sum = 0.0, floor_sum = 0.0;
      for (std::size_t i = a; i < b; ++i) sum += psd.psd[i], floor_sum += floor[i];
      lowest = std::min(lowest, sum / floor_sum);
      a = b;
    }
  };
  scan(low > lowest_bin + reach ? low - reach : lowest_bin, low);
  scan(high + 1, std::min(n, high + 1 + reach));
  return lowest;
}

// The frequencies [low, high] of a line found [Hz].
struct FrequencyRange {
  double low, high;
};

// The lines of one pass whose run of high bins starts below `start_below_hz`,
// added to `lines`; `taken` holds the frequencies of the lines found before,
// which a line of this pass may not overlap.
void find_lines(const stats::PsdResult& psd, const std::vector<double>& smooth,
                const LinePass& pass, double start_below_hz, std::vector<FrequencyRange>& taken,
                std::vector<SpectralLine>& lines) {
  const std::size_t n = psd.psd.size();
  const std::size_t lowest = pass.lowest_bin;
  const std::vector<double> floor = noise_floor(psd, pass.floor_half_width);
  const double df = psd.resolution_hz;
  const double segments = static_cast<double>(psd.segments);

  std::size_t k = lowest;
  while (k < n && psd.frequency_hz[k] < start_below_hz) {
    if (!(smooth[k] > pass.bin_ratio * floor[k])) {
      ++k;
      continue;
    }
    // A run of high bins, gaps of up to kClosedGap closed.
    std::size_t end = k + 1, last = k;
    while (end < n && end <= last + kClosedGap + 1) {
      if (smooth[end] > pass.bin_ratio * floor[end]) last = end;
      ++end;
    }
    double excess = 0.0, floor_sum = 0.0, peak_ratio = 0.0;
    for (std::size_t b = k; b <= last; ++b) {
      excess += std::max(0.0, psd.psd[b] - floor[b]);
      floor_sum += floor[b];
      peak_ratio = std::max(peak_ratio, smooth[b] / floor[b]);
    }
    const double bins = static_cast<double>(last - k + 1);
    const double standard_error = floor_sum / bins * std::sqrt(bins / segments);
    const double run_width = psd.frequency_hz[last] - psd.frequency_hz[k];
    if (!(excess > kSignificance * standard_error && peak_ratio > pass.peak_ratio &&
          run_width >= pass.least_width * psd.frequency_hz[(k + last) / 2])) {
      k = last + 1;
      continue;
    }
    // The skirts of a found line (a broad resonance's flanks) belong to it,
    // down to kSkirtShare of its peak's excess: below that a bin's excess
    // is the floor's error, not the line (near a moving average's null the
    // floor, a median over +-0.2 decade, runs 30-50 % off the filtered PSD,
    // and a 20 Hz sinusoid behind a 4-sample average took 9 Hz of it as
    // skirts, N then 1-2 % low with a deviance of 120-200).
    double peak_excess = 0.0;
    for (std::size_t b = k; b <= last; ++b)
      peak_excess = std::max(peak_excess, smooth[b] - floor[b]);
    auto skirt = [&](std::size_t b) {
      return above_floor(smooth[b], floor[b], b, segments) &&
             smooth[b] - floor[b] >= kSkirtShare * peak_excess;
    };
    std::size_t low = k, high = last;
    // A line at the search's start has skirts below it.
    while (low > lowest / 2 && skirt(low - 1)) --low;
    while (high + 1 < n && skirt(high + 1)) ++high;
    // A line falls on both sides: its highest averaged bin stands the bin ratio
    // above the PSD where its skirts end. A steep roll-off of the output
    // filter (or a moving average's side lobe) can stand above the running
    // median on one side only, where the passband's level goes on.
    double peak = 0.0;
    for (std::size_t b = k; b <= last; ++b) peak = std::max(peak, smooth[b]);
    const double below = smooth[low > 0 ? low - 1 : low];
    const double above = smooth[high + 1 < n ? high + 1 : high];
    if (!(peak > pass.bin_ratio * below && peak > pass.bin_ratio * above)) {
      k = last + 1;  // a real line on the shoulder is still looked for
      continue;
    }
    if (pass.least_beside > 0.0 &&
        !(lowest_beside(psd, floor, lowest, low, high) >= pass.least_beside)) {
      k = high + 1;
      continue;
    }
    const double f_low = psd.frequency_hz[low], f_high = psd.frequency_hz[high];
    const bool overlaps = std::any_of(taken.begin(), taken.end(), [&](const FrequencyRange& r) {
      return f_low <= r.high && r.low <= f_high;
    });
    if (overlaps) {
      k = high + 1;
      continue;
    }
    taken.push_back({f_low, f_high});
    SpectralLine line;
    line.peak_ratio = peak_ratio;
    double line_excess = 0.0, weighted_f = 0.0;
    for (std::size_t b = low; b <= high; ++b) {
      const double e = std::max(0.0, psd.psd[b] - floor[b]);
      line.bin_frequency_hz.push_back(psd.frequency_hz[b]);
      line.bin_variance.push_back(2.0 * e * df);
      line_excess += e;
      weighted_f += e * psd.frequency_hz[b];
    }
    line.frequency_hz = weighted_f / line_excess;
    line.width_hz = psd.frequency_hz[high] - psd.frequency_hz[low];
    line.variance = 2.0 * line_excess * df;
    lines.push_back(std::move(line));
    k = high + 1;
  }
}

// The means of `rate` over blocks of `block` samples inside each of its
// contiguous `stretches` (a stretch's last partial block dropped), with a
// gap of one block wherever a stretch ends: the slow lines' band lies far below the blocks'
// Nyquist frequency, and what folds into it is tiny (content near k fs / block
// meets the block mean's nulls there: a line at k fs / block + 0.01 Hz is
// cut to below 1e-4 of its power for 2 h at 100 Hz).
struct BlockMeans {
  std::vector<double> rate;
  std::vector<Gap> gaps;
  std::vector<double> time_s;   ///< [s] each block's centre, the gaps' time counted
  std::size_t block = 1;        ///< samples a block
  double sample_rate_hz = 0.0;  ///< of the samples
};

BlockMeans block_means(std::span<const double> rate, std::span<const Stretch> stretches,
                       std::span<const Gap> gaps, double sample_rate_hz, std::size_t block) {
  BlockMeans out;
  out.block = block;
  out.sample_rate_hz = sample_rate_hz;
  for (const Stretch& s : stretches) {
    const std::size_t blocks = static_cast<std::size_t>(s.size()) / block;
    if (blocks == 0) continue;
    if (!out.rate.empty()) out.gaps.push_back({static_cast<std::int64_t>(out.rate.size()), 1});
    const double start_s = elapsed_s(s.begin, gaps, sample_rate_hz) +
                           0.5 * static_cast<double>(block - 1) / sample_rate_hz;
    for (std::size_t b = 0; b < blocks; ++b) {
      out.rate.push_back(
          compensated_mean(rate.subspan(static_cast<std::size_t>(s.begin) + b * block, block)));
      out.time_s.push_back(start_s + static_cast<double>(b * block) / sample_rate_hz);
    }
  }
  return out;
}

// [s] The record's span as its block means cover it, T.
double record_span_s(const BlockMeans& m) {
  return m.time_s.back() - m.time_s.front() + static_cast<double>(m.block) / m.sample_rate_hz;
}

// The least-squares sinusoid of the block means at `frequency_hz`, beside
// a constant: the samples' sinusoid it stands for, a cos(w t) + b sin(w t)
// [deg/h] (the block mean's Dirichlet factor taken out), and the sum of
// squares it explains (what the frequency search maximises).
struct SineFit {
  double frequency_hz = 0.0;
  double cos_deg_h = 0.0;
  double sin_deg_h = 0.0;
  double explained = 0.0;
  double variance() const { return 0.5 * (cos_deg_h * cos_deg_h + sin_deg_h * sin_deg_h); }
  /// as amplitude cos(w t + phase): [deg/h], [rad]
  double amplitude_deg_h() const { return std::hypot(cos_deg_h, sin_deg_h); }
  double phase_rad() const { return std::atan2(-sin_deg_h, cos_deg_h); }
};

// The block mean's gain on a sinusoid of `frequency_hz`.
double block_gain(const BlockMeans& m, double frequency_hz) {
  return dirichlet_kernel(frequency_hz, static_cast<double>(m.block), 1.0 / m.sample_rate_hz);
}

SineFit fit_sine(const BlockMeans& m, double frequency_hz) {
  const double w = 2.0 * std::numbers::pi * frequency_hz;
  // cos and sin advanced by a rotation from one block to the next, set
  // afresh after a gap and every kExact blocks
  constexpr std::size_t kExact = 1024;
  const double block_s = static_cast<double>(m.block) / m.sample_rate_hz;
  const double step_cos = std::cos(w * block_s), step_sin = std::sin(w * block_s);
  // the normal equations' sums: of c, s, c^2, s^2, c s, and y, y c, y s
  double sc = 0.0, ss = 0.0, scc = 0.0, sss = 0.0, scs = 0.0, sy = 0.0, syc = 0.0, sys = 0.0;
  double c = 0.0, sn = 0.0;
  for (std::size_t i = 0; i < m.rate.size(); ++i) {
    if (i % kExact == 0 || !(std::fabs(m.time_s[i] - m.time_s[i - 1] - block_s) < 1e-6 * block_s)) {
      c = std::cos(w * m.time_s[i]), sn = std::sin(w * m.time_s[i]);
    } else {
      const double next = c * step_cos - sn * step_sin;
      sn = sn * step_cos + c * step_sin;
      c = next;
    }
    const double y = m.rate[i];
    sc += c, ss += sn, scc += c * c, sss += sn * sn, scs += c * sn;
    sy += y, syc += y * c, sys += y * sn;
  }
  Eigen::Matrix3d a;
  a << static_cast<double>(m.rate.size()), sc, ss, sc, scc, scs, ss, scs, sss;
  const Eigen::Vector3d b(sy, syc, sys);
  const Eigen::Vector3d beta = a.ldlt().solve(b);
  const double mean = b(0) / static_cast<double>(m.rate.size());
  SineFit fit;
  fit.frequency_hz = frequency_hz;
  fit.explained = beta.dot(b) - mean * b(0);
  const double gain = block_gain(m, frequency_hz);
  fit.cos_deg_h = beta(1) / gain;
  fit.sin_deg_h = beta(2) / gain;
  return fit;
}

// A slow line (spectral_lines.h says which), taken again as the least-
// squares sinusoid of the record's block means, to be removed from the
// record, when that holds most of the line's variance (kCoherentShare; the
// header says why): its frequency searched over +-(2 / T + half the line's
// width) around the bins' centre (T the record's span; the bins' centre
// lies within a Welch resolution of the sinusoid's frequency), in steps of
// 1 / (4 T), a quarter of the least-squares fit's main lobe, then refined
// by golden section over one step either side.
constexpr double kCoherentShare = 0.8;
// A line whose least-squares sinusoid leaves, within the band, another of
// more than this share of its variance is not one sinusoid: a carrier with
// sidebands (an amplitude that changes over the record: a 0.5 deg/h line at
// 0.01 Hz whose amplitude swings by +-50 % once over 2 h left its
// sidebands, 6 % of its variance each, in the record, and they passed for
// a Gauss-Markov process).
constexpr double kSecondShare = 0.03;
// ... and stands out of the band's noise: more than this many times the
// median of the rest's sinusoids over the band (the noise's sinusoids
// scatter as an exponential; where the line is weak against a random
// walk, 3 % of it is within that scatter).
constexpr double kSecondOverNoise = 10.0;

// The frequencies searched for a line's sinusoid: centre + j step for
// |j| <= steps.
struct SearchBand {
  double centre_hz, step_hz;
  int steps;
  double span_s;  ///< the record's, T
  double at(int j) const { return centre_hz + j * step_hz; }
};

// The best sinusoid over the band's grid, refined by golden section over
// one step either side of the best point.
SineFit best_sinusoid(const BlockMeans& m, const SearchBand& band) {
  SineFit best;
  for (int j = -band.steps; j <= band.steps; ++j) {
    if (!(band.at(j) > 0.0)) continue;
    if (const SineFit fit = fit_sine(m, band.at(j)); fit.explained > best.explained) best = fit;
  }
  if (!(best.explained > 0.0)) return best;
  double lo = best.frequency_hz - band.step_hz, hi = best.frequency_hz + band.step_hz;
  const double golden = (std::sqrt(5.0) - 1.0) / 2.0;
  double x1 = hi - golden * (hi - lo), x2 = lo + golden * (hi - lo);
  SineFit f1 = fit_sine(m, x1), f2 = fit_sine(m, x2);
  for (int it = 0; it < 24; ++it) {
    if (f1.explained > f2.explained) {
      hi = x2, x2 = x1, f2 = f1;
      x1 = hi - golden * (hi - lo), f1 = fit_sine(m, x1);
    } else {
      lo = x1, x1 = x2, f1 = f2;
      x2 = lo + golden * (hi - lo), f2 = fit_sine(m, x2);
    }
  }
  for (const SineFit& f : {f1, f2}) {
    if (f.explained > best.explained) best = f;
  }
  return best;
}

// Takes the samples' sinusoid `fit` out of the block means `m`.
void subtract(BlockMeans& m, const SineFit& fit) {
  const double w = 2.0 * std::numbers::pi * fit.frequency_hz;
  const double gain = block_gain(m, fit.frequency_hz);
  for (std::size_t i = 0; i < m.rate.size(); ++i) {
    m.rate[i] -= gain * (fit.cos_deg_h * std::cos(w * m.time_s[i]) +
                         fit.sin_deg_h * std::sin(w * m.time_s[i]));
  }
}

// Whether `rest`, the block means with the sinusoid `first` taken out,
// holds only noise in the band: its strongest sinusoid there, off the
// first's main lobe, holds under kSecondShare of the first's variance or
// under kSecondOverNoise times the band's median.
bool only_noise_beside(const BlockMeans& rest, const SineFit& first, const SearchBand& band) {
  std::vector<double> beside;
  for (int j = -band.steps; j <= band.steps; ++j) {
    const double f = band.at(j);
    if (!(f > 0.0) || std::fabs(f - first.frequency_hz) < 0.5 / band.span_s) continue;
    beside.push_back(fit_sine(rest, f).variance());
  }
  if (beside.empty()) return true;
  const double second = *std::max_element(beside.begin(), beside.end());
  return !(second > kSecondShare * first.variance() &&
           second > kSecondOverNoise * median_in_place(beside));
}

// The frequencies searched for `line`'s sinusoid in the record of span T.
SearchBand search_band(const SpectralLine& line, double span_s) {
  SearchBand band;
  band.span_s = span_s;
  band.centre_hz = line.frequency_hz;
  band.step_hz = 1.0 / (4.0 * span_s);
  band.steps = static_cast<int>(std::ceil((2.0 / span_s + 0.5 * line.width_hz) / band.step_hz));
  return band;
}

// Sets `line` as the sinusoid `fit`, to be removed from the record.
void set_removed(SpectralLine& line, const SineFit& fit) {
  line.frequency_hz = fit.frequency_hz;
  line.variance = fit.variance();
  line.bin_frequency_hz = {fit.frequency_hz};
  line.bin_variance = {fit.variance()};
  line.removed_from_record = true;
  line.takes_variance_scale = false;  // the sinusoid holds all of it
  line.amplitude_deg_h = fit.amplitude_deg_h();
  line.phase_rad = fit.phase_rad();
}

// Whether `line` is taken as a sinusoid: then set as the sinusoid.
bool take_as_sinusoid(SpectralLine& line, const BlockMeans& m) {
  if (m.time_s.size() < 16) return false;
  const SearchBand band = search_band(line, record_span_s(m));
  const SineFit best = best_sinusoid(m, band);
  if (!(best.explained > 0.0) || !(best.variance() >= kCoherentShare * line.variance)) return false;
  BlockMeans rest = m;
  subtract(rest, best);
  if (!only_noise_beside(rest, best, band)) return false;
  set_removed(line, best);
  return true;
}

// A line's frequency and how far off it may be: its least-squares
// sinusoid's to within 1 / (2 T), else its bins' centre to within half its
// width.
struct Located {
  double frequency_hz, off_hz;
};

// Whether `high` is a harmonic of `low`: k when it lies within their
// uncertainties (the lower's k times) of k = 2 to kHighestHarmonic times
// the lower, else 0.
constexpr int kHighestHarmonic = 9;

int harmonic_number(const Located& low, const Located& high) {
  if (!(high.frequency_hz > low.frequency_hz)) return 0;
  const double k = std::round(high.frequency_hz / low.frequency_hz);
  const bool within =
      std::fabs(high.frequency_hz - k * low.frequency_hz) <= high.off_hz + k * low.off_hz;
  return k >= 2.0 && k <= kHighestHarmonic && within ? static_cast<int>(k) : 0;
}

bool in_harmonic_series(std::size_t i, std::span<const Located> at) {
  for (std::size_t j = 0; j < at.size(); ++j) {
    if (j != i && (harmonic_number(at[i], at[j]) > 0 || harmonic_number(at[j], at[i]) > 0)) {
      return true;
    }
  }
  return false;
}

// A periodic disturbance that is not one sinusoid (a thermostat's square or
// triangle wave) shows as a harmonic series, of which the line search finds
// only the first few. Taking those out of the record one by one left the
// rest (on a 0.5 deg/h square wave at 0.01 Hz over tactical-grade noise a
// moving average was then found, N +5.4 %); their Allan variance taken as
// known left B 37-45 % high. It is taken out as a whole: the period's
// frequency f0 from the found harmonics' least-squares frequencies (each
// over its k, weighted by k^2 times its variance, as each tells f0), then
// the sinusoid at every k f0 in the block means' band, fitted in turn on
// what the earlier leave; kept where it stands out of the noise's
// sinusoids beside it (kSecondOverNoise times their median: one in 200 of
// pure noise does, harmless when subtracted).
//
// The harmonics are fitted up to kPeriodicBlockShare of the block means'
// rate, above the lines' kSlowestBlockShare: at known frequencies what
// folds in is mostly the noise's; a harmonic folds onto another only when
// the blocks' rate is a multiple of f0, and then adds at most 0.43 of its
// amplitude there (the block mean's gain at 0.7 against 0.3 of the rate;
// a square wave's harmonic at 0.7 is 0.43 of that at 0.3: 18 % of a
// harmonic near the noise). On a 0.5 deg/h square wave at
// 0.01 Hz over tactical-grade noise (2 h at 100 Hz, seeds 1-3) the
// harmonics up to kSlowestBlockShare (19 f0) left B 1.1-5.3 % above the
// clean record's, up to this share (14-17 harmonics found) -0.1-+1.7 %.
constexpr double kPeriodicBlockShare = 0.3;
constexpr int kMostHarmonics = 256;
// the noise's sinusoids at +-(j + 1/2) / T, j = 1 to this: a sinusoid of
// noise stands kSecondOverNoise above the median of 16 in 1 of 200 (of 8,
// in 1 of 100)
constexpr int kNoiseBeside = 8;
constexpr double kRounding = 1e-20;  // of the fundamental's variance

struct Harmonic {
  int number;
  SineFit fit;
  double over_noise = 0.0;  ///< its variance over the median of the noise's sinusoids beside it
};

// The harmonics of f0 below `highest_hz` that stand out of the noise, and
// the block means with them taken out (`rest`).
std::vector<Harmonic> periodic_fit(const BlockMeans& m, double f0_hz, double highest_hz,
                                   BlockMeans& rest) {
  rest = m;
  std::vector<Harmonic> all;
  for (int k = 1; k <= kMostHarmonics && k * f0_hz < highest_hz; ++k) {
    all.push_back({k, fit_sine(rest, k * f0_hz)});
    subtract(rest, all.back().fit);
  }
  const double span_s = record_span_s(m);
  std::vector<Harmonic> standing;
  for (Harmonic& h : all) {
    std::vector<double> noise;
    for (int j = -kNoiseBeside; j <= kNoiseBeside; ++j) {
      const double f = h.fit.frequency_hz + (j + (j < 0 ? -0.5 : 0.5)) / span_s;
      if (j != 0 && f > 0.0) noise.push_back(fit_sine(rest, f).variance());
    }
    // (a harmonic below the rounding of a noiseless record's samples has
    // nothing to stand out of)
    const bool rounding = !(h.fit.variance() > kRounding * all.front().fit.variance());
    h.over_noise = rounding ? 0.0 : h.fit.variance() / median_in_place(noise);
    if (h.number == 1 || h.over_noise > kSecondOverNoise) standing.push_back(h);
  }
  rest = m;
  for (const Harmonic& h : standing) subtract(rest, h.fit);
  return standing;
}

// A found line of the series: its index and harmonic number.
struct Member {
  std::size_t line;
  int number;
};

// Takes the series of line `members[0]` (the fundamental, found as one
// sinusoid; the others its harmonics found as lines, if any) as one
// periodic disturbance when the harmonics' fits hold kCoherentShare of the
// found lines' variance (together: a weak line's own share scatters with
// the noise in its bins; on a gm-fog record the 15th harmonic's failed
// it), a line found alone has a harmonic standing
// kHarmonicOverNoise out of the noise, and the fundamental's fit leaves
// only noise beside it (as for one sinusoid; a weak harmonic's own band
// tells little: one found 10.5 times the median of the noise's sinusoids
// beside it on a clean square wave): then lines[members[0]] becomes the
// disturbance.
//
// A harmonic of a line found alone: the line search missed a triangle
// wave's third harmonic (1/9 of the fundamental's amplitude, about 25
// times the noise's sinusoids there), and the harmonics left in the record
// put B 5-6 % above the clean record's. One of harmonics 2 to
// kHighestAloneHarmonic (a periodic wave's strongest after the first)
// must stand kHarmonicOverNoise times above the median of the noise's 16
// sinusoids beside it, which noise does in 1 of 5,000 tests (standing 15
// times above the median of 8 sinusoids, over every harmonic up to 0.47
// Hz, one of ten records of a pure sinusoid passed for periodic).
constexpr double kHarmonicOverNoise = 20.0;
constexpr int kHighestAloneHarmonic = 5;

bool take_periodic(std::vector<SpectralLine>& lines, std::span<const Member> members, double f0_hz,
                   const BlockMeans& m, double highest_hz) {
  BlockMeans rest;
  const std::vector<Harmonic> harmonics = periodic_fit(m, f0_hz, highest_hz, rest);
  if (harmonics.size() < 2) return false;
  if (members.size() == 1 && std::ranges::none_of(harmonics, [](const Harmonic& h) {
        return h.number > 1 && h.number <= kHighestAloneHarmonic &&
               h.over_noise > kHarmonicOverNoise;
      })) {
    return false;
  }
  double fitted = 0.0, found = 0.0;  // of the found lines
  for (const Member& member : members) {
    found += lines[member.line].variance;
    const auto h = std::ranges::find(harmonics, member.number, &Harmonic::number);
    if (h != harmonics.end()) fitted += h->fit.variance();
  }
  if (!(fitted >= kCoherentShare * found)) return false;
  SpectralLine& line = lines[members.front().line];
  if (!only_noise_beside(rest, harmonics.front().fit, search_band(line, record_span_s(m)))) {
    return false;
  }
  set_removed(line, harmonics.front().fit);
  for (const Harmonic& h : harmonics) {
    if (h.number == 1) continue;
    line.harmonics.push_back({h.number, h.fit.amplitude_deg_h(), h.fit.phase_rad()});
    line.bin_frequency_hz.push_back(h.fit.frequency_hz);
    line.bin_variance.push_back(h.fit.variance());
    line.variance += h.fit.variance();
  }
  return true;
}

// Takes each of `lines`' candidates (indices) that is one sinusoid, and no
// harmonic of another line, as that sinusoid, and each harmonic series
// whose lowest line is such a candidate as one periodic disturbance,
// removed from the record; the series' other lines are then dropped.
void take_sinusoids(std::vector<SpectralLine>& lines, std::span<const std::size_t> candidates,
                    const BlockMeans& m) {
  const double span_s = record_span_s(m);
  const double highest_hz = kPeriodicBlockShare * m.sample_rate_hz / static_cast<double>(m.block);
  std::vector<Located> at;
  for (const SpectralLine& line : lines) at.push_back({line.frequency_hz, 0.5 * line.width_hz});
  std::vector<std::optional<SpectralLine>> sinusoids(lines.size());
  for (const std::size_t i : candidates) {
    SpectralLine line = lines[i];
    if (!take_as_sinusoid(line, m)) continue;
    at[i] = {line.frequency_hz, 0.5 / span_s};
    sinusoids[i] = std::move(line);
  }
  std::vector<bool> dropped(lines.size(), false);
  std::vector<std::size_t> upwards(candidates.begin(), candidates.end());
  std::sort(upwards.begin(), upwards.end(),
            [&](std::size_t a, std::size_t b) { return at[a].frequency_hz < at[b].frequency_hz; });
  for (const std::size_t i : upwards) {
    if (!sinusoids[i] || dropped[i]) continue;
    // i the series' lowest line; f0 from its sinusoids
    double weighted = 0.0, weights = 0.0;
    bool lowest = true;
    for (std::size_t j = 0; j < lines.size(); ++j) {
      if (harmonic_number(at[j], at[i]) > 0) lowest = false;
      const int k = j == i ? 1 : harmonic_number(at[i], at[j]);
      if (k == 0 || !sinusoids[j]) continue;
      const double weight = k * k * sinusoids[j]->variance;
      weighted += weight * at[j].frequency_hz / k, weights += weight;
    }
    if (!lowest) continue;
    const double f0_hz = weighted / weights;
    // every line at a harmonic of f0 in the block means' band is one
    std::vector<Member> members{{i, 1}};
    for (std::size_t j = 0; j < lines.size(); ++j) {
      const double k = std::round(at[j].frequency_hz / f0_hz);
      if (j == i || k < 2.0 || !(at[j].frequency_hz < highest_hz) ||
          std::fabs(at[j].frequency_hz - k * f0_hz) > at[j].off_hz + 0.5 / span_s) {
        continue;
      }
      members.push_back({j, static_cast<int>(k)});
    }
    if (!take_periodic(lines, members, f0_hz, m, highest_hz)) continue;
    for (std::size_t x = 1; x < members.size(); ++x) dropped[members[x].line] = true;
  }
  for (std::size_t i = 0; i < lines.size(); ++i) {
    // (a periodic disturbance's line has its harmonics: take_periodic())
    if (sinusoids[i] && lines[i].harmonics.empty() && !in_harmonic_series(i, at)) {
      lines[i] = std::move(*sinusoids[i]);
    }
  }
  std::size_t kept = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (dropped[i]) continue;
    if (kept != i) lines[kept] = std::move(lines[i]);
    ++kept;
  }
  lines.resize(kept);
}

bool searchable(const stats::PsdResult& psd) {
  return psd.psd.size() >= 2 * kNarrow.lowest_bin && psd.segments > 0 && psd.resolution_hz > 0.0;
}

void strongest_first(std::vector<SpectralLine>& lines, std::size_t max_lines) {
  std::sort(lines.begin(), lines.end(),
            [](const SpectralLine& a, const SpectralLine& b) { return a.variance > b.variance; });
  if (lines.size() > max_lines) lines.resize(max_lines);
}

// The lines of `psd` (both passes), their frequencies added to `taken`;
// `narrow` (when given) gets how many of them, the first, are the narrow
// pass's.
std::vector<SpectralLine> lines_of(const stats::PsdResult& psd, std::vector<FrequencyRange>& taken,
                                   std::size_t* narrow = nullptr) {
  std::vector<SpectralLine> lines;
  if (narrow) *narrow = 0;
  if (!searchable(psd)) return lines;
  const std::vector<double> smooth = smoothed(psd);
  constexpr double kEverywhere = std::numeric_limits<double>::infinity();
  find_lines(psd, smooth, kNarrow, kEverywhere, taken, lines);
  if (narrow) *narrow = lines.size();
  find_lines(psd, smooth, kBroad, kEverywhere, taken, lines);
  return lines;
}

// The block means' layout for the slow lines: the long segment (the
// longest power of two within half the longest stretch, at most
// kLongestSlowLineSegment samples), kSlowLineSegmentBlocks blocks to a
// segment, and the highest frequency the block means take lines at.
struct SlowBlocks {
  std::vector<Stretch> stretches;
  std::size_t segment = 1, block = 1;
  double slowest_hz = 0.0;  ///< [Hz] below which (kSlowestBlockShare of the blocks' rate)

  SlowBlocks(std::size_t samples, std::span<const Gap> gaps, double sample_rate_hz)
      : stretches(contiguous_stretches(static_cast<std::int64_t>(samples), gaps)) {
    const auto longest = static_cast<std::size_t>(longest_stretch(stretches));
    while (segment * 2 <= longest / 2 && segment * 2 <= kLongestSlowLineSegment) segment *= 2;
    block = std::max<std::size_t>(1, segment / kSlowLineSegmentBlocks);
    slowest_hz = sample_rate_hz / static_cast<double>(block) * kSlowestBlockShare;
  }
};

}  // namespace

std::vector<SpectralLine> find_spectral_lines(const stats::PsdResult& psd, std::size_t max_lines) {
  std::vector<FrequencyRange> taken;
  std::vector<SpectralLine> lines = lines_of(psd, taken);
  strongest_first(lines, max_lines);
  return lines;
}

std::vector<SpectralLine> find_spectral_lines(std::span<const double> rate, double sample_rate_hz,
                                              const stats::PsdResult& psd,
                                              std::span<const Gap> gaps, std::size_t max_lines) {
  std::vector<FrequencyRange> taken;
  std::size_t narrow = 0;
  std::vector<SpectralLine> lines = lines_of(psd, taken, &narrow);
  const SlowBlocks slow_blocks(rate.size(), gaps, sample_rate_hz);
  const std::size_t segment = slow_blocks.segment, block = slow_blocks.block;
  // The narrow lines slow enough for the block means (kSlowestBlockShare),
  // and the slow pass's.
  const double slow_below_hz = slow_blocks.slowest_hz;
  std::vector<std::size_t> slow;
  for (std::size_t i = 0; i < narrow; ++i) {
    if (lines[i].frequency_hz < slow_below_hz) slow.push_back(i);
  }
  const bool slow_pass = searchable(psd) && segment > psd.segment_length;
  if (!slow_pass && slow.empty()) {
    strongest_first(lines, max_lines);
    return lines;
  }
  const BlockMeans means = block_means(rate, slow_blocks.stretches, gaps, sample_rate_hz, block);
  if (slow_pass) {
    stats::WelchOptions welch;
    welch.segment_length = segment / block;
    const stats::PsdResult long_psd = stats::welch_psd(
        means.rate, sample_rate_hz / static_cast<double>(block), welch, means.gaps);
    if (searchable(long_psd)) {
      const double start_below_hz = psd.frequency_hz[kNarrow.lowest_bin];
      const std::size_t first_slow = lines.size();
      find_lines(long_psd, smoothed(long_psd), kNarrow, start_below_hz, taken, lines);
      for (std::size_t i = first_slow; i < lines.size(); ++i) {
        lines[i].takes_variance_scale = false;
        slow.push_back(i);
      }
    }
  }
  take_sinusoids(lines, slow, means);
  strongest_first(lines, max_lines);
  return lines;
}

namespace {

// rate += sign times the sinusoids (and harmonics) of the lines removed_from_record.
void add_times(double sign, std::span<double> rate, double sample_rate_hz,
               std::span<const Gap> gaps, std::span<const SpectralLine> lines) {
  struct Phasor {
    double amplitude, w, phase, step_cos, step_sin;
  };
  std::vector<Phasor> removed;
  const auto add = [&](double frequency_hz, double amplitude_deg_h, double phase_rad) {
    const double w = 2.0 * std::numbers::pi * frequency_hz;
    removed.push_back({sign * amplitude_deg_h, w, phase_rad, std::cos(w / sample_rate_hz),
                       std::sin(w / sample_rate_hz)});
  };
  for (const SpectralLine& line : lines) {
    if (!line.removed_from_record) continue;
    add(line.frequency_hz, line.amplitude_deg_h, line.phase_rad);
    for (const LineHarmonic& h : line.harmonics) {
      add(h.number * line.frequency_hz, h.amplitude_deg_h, h.phase_rad);
    }
  }
  if (removed.empty()) return;
  // Each line's phase advanced by a rotation every sample, set afresh from
  // cos and sin every kExact samples of a stretch.
  constexpr std::int64_t kExact = 4096;
  for (const Stretch& stretch :
       contiguous_stretches(static_cast<std::int64_t>(rate.size()), gaps)) {
    const double start_s = elapsed_s(stretch.begin, gaps, sample_rate_hz);
    for (std::int64_t chunk = stretch.begin; chunk < stretch.end; chunk += kExact) {
      const double t = start_s + static_cast<double>(chunk - stretch.begin) / sample_rate_hz;
      const auto first = static_cast<std::size_t>(chunk);
      const auto end = static_cast<std::size_t>(std::min(chunk + kExact, stretch.end));
      for (const Phasor& p : removed) {
        double c = std::cos(p.w * t + p.phase), s = std::sin(p.w * t + p.phase);
        for (std::size_t i = first; i < end; ++i) {
          rate[i] += p.amplitude * c;
          const double next = c * p.step_cos - s * p.step_sin;
          s = s * p.step_cos + c * p.step_sin;
          c = next;
        }
      }
    }
  }
}

}  // namespace

void remove_sinusoids(std::span<double> rate, double sample_rate_hz, std::span<const Gap> gaps,
                      std::span<const SpectralLine> lines) {
  add_times(-1.0, rate, sample_rate_hz, gaps, lines);
}

void add_sinusoids(std::span<double> rate, double sample_rate_hz, std::span<const Gap> gaps,
                   std::span<const SpectralLine> lines) {
  add_times(1.0, rate, sample_rate_hz, gaps, lines);
}

std::vector<SpectralLine> find_periodic_disturbances(std::span<const double> rate,
                                                     double sample_rate_hz,
                                                     std::span<const Gap> gaps) {
  std::vector<SpectralLine> lines;
  const SlowBlocks slow_blocks(rate.size(), gaps, sample_rate_hz);
  const BlockMeans means =
      block_means(rate, slow_blocks.stretches, gaps, sample_rate_hz, slow_blocks.block);
  stats::WelchOptions welch;
  welch.segment_length = slow_blocks.segment / slow_blocks.block;
  const stats::PsdResult psd = stats::welch_psd(
      means.rate, sample_rate_hz / static_cast<double>(slow_blocks.block), welch, means.gaps);
  if (!searchable(psd)) return lines;
  std::vector<FrequencyRange> taken;
  find_lines(psd, smoothed(psd), kNarrow, slow_blocks.slowest_hz, taken, lines);
  std::vector<std::size_t> all(lines.size());
  std::iota(all.begin(), all.end(), std::size_t{0});
  take_sinusoids(lines, all, means);
  std::erase_if(lines, [](const SpectralLine& line) { return line.harmonics.empty(); });
  return lines;
}

}  // namespace foglab::model
