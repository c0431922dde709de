// foglab — noise-model fit, step 1b: the sensor's output bandwidth
// (noise_fit_internal.h, core/sensor_bandwidth.h).
//
// A filtered output lowers the Allan variance of the first taus below
// N^2 / tau. Without a model of it the fit reaches for what else bends the
// short taus down: a Gauss-Markov term with Tc below the first tau and a
// large sigma (a random bias that is really the filter), and a white level
// below what the record shows (on the ADIS16405 records N came out 40 %
// low; docs/validation.md).
//
// The bandwidth is looked for with a large model that has no Gauss-Markov
// process (N, B, K and R, as many as the points allow): its deviance is
// profiled over the filtered fraction phi and the time constant T
// (tau0 / 20 .. 10 tau0) of a first-order low-pass, on a grid and then by a
// Nelder-Mead simplex (phi and T trade off along a narrow valley, which
// coordinate steps crawled down: they stopped at phi 0.77, T 0.67 tau0 for
// a whole-output filter of 0.54 tau0, with N 1 % high), over phi and
// the length k (2 .. 128 samples, kMovingAverageLengths) of a moving average, and over phi and the
// cut-off f_c (0.016 .. 0.45 / tau0) of a second-order Butterworth (a grid,
// then the same simplex). The better of the first two kinds is taken, and
// the Butterworth instead only when it beats that by more than one
// parameter's penalty (times the dispersion): where the first taus cannot
// tell the kinds apart (on the ADIS16405 z axes, whose 20 Hz line shares
// those taus, it is 1.6 better in deviance) the established kinds' answer
// stands; a real second-order filter wins by thousands. It is resolved when it lowers that deviance
// by more than its two parameters cost in the selection criterion (2 x the penalty, times the
// dispersion), both as the deviance counts the points and with their correlation
// (correlated_drop()), takes at least 0.5 % from the first point's Allan variance and does not sit
// at the longest T or k searched (nor at either end of the Butterworth's cut-offs). It is then held
// for every candidate, and kept only if the best candidate with it beats the best without it by
// more than those two parameters' cost (noise_fit.cc).
//
// On points whose first taus were left out (no modelled kind followed them;
// noise_fit.cc), the one kind tried is a filter known beyond its memory: its
// factor 1 - c tau0 / tau (core/sensor_bandwidth.h) holds for every filter
// shape once tau is past the memory, and c is profiled from 0 to a third of the
// first kept tau's samples (a grid, then golden section). It is kept
// without the tests of significance (the filter is known to be there) when
// it takes at least 0.5 % from the first kept tau's Allan variance, and the
// c the data do not tell apart widen N's interval either way; at that upper
// end the first kept tau is still inside the memory (noise_fit.cc then
// leaves out more).
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>

#include "noise_fit_internal.h"

namespace foglab::model::detail {
namespace {

constexpr double kShortestT = 1.0 / 20.0;  // in tau0
constexpr double kLongestT = 10.0;         // in tau0
constexpr int kTSteps = 16;
constexpr int kFractionSteps = 20;
constexpr int kEveryMovingAverageTo = 32;  // samples: every length up to here is tried
// The moving averages' lengths [samples]: every one to 32, then about a
// sixth apart to 128 (a 1 kHz output averaged over 40 samples had stood
// beyond the search, and the fit had lost N altogether).
constexpr std::array kMovingAverageLengths = {
    2,  3,  4,  5,  6,  7,  8,  9,  10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20,  21,
    22, 23, 24, 25, 26, 27, 28, 29, 30, 31, 32, 37, 43, 50, 58, 68, 80, 93, 108, 128};
constexpr int kLongestMovingAverage = kMovingAverageLengths.back();  // samples
constexpr double kLowestCutoff = 0.016;    // Butterworth f_c, in 1/tau0 (as 1/(2 pi 10 tau0))
constexpr double kHighestCutoff = 0.45;
constexpr int kButterworth = 0;       // Trial::k of the Butterworth kind
constexpr int kBeyondMemory = -1;     // Trial::k of a filter known beyond its memory
constexpr int kMemorySteps = 24;      // the grid of c
constexpr double kSmallestEffect = 0.005;

// The reference model: white noise, flicker, random walk and ramp (and, on
// the second look noise_fit.cc takes, a Gauss-Markov process of a given Tc),
// as many as leave three points to spare for phi, T and the judge. Not the angle
// quantisation Q: its 3 Q^2 / tau^2 raises the first taus where the
// bandwidth lowers them, and with both free the pair trades off (a spurious
// Q and a too long T), which biases N by about 1 %.
NoiseTermSet reference_terms(const Points& p, bool gauss_markov) {
  NoiseTermSet terms;
  for (NoiseTerm t : {NoiseTerm::white, NoiseTerm::gauss_markov, NoiseTerm::flicker,
                      NoiseTerm::random_walk, NoiseTerm::ramp}) {
    if (t == NoiseTerm::gauss_markov && !gauss_markov) continue;
    if (terms.with(t).parameter_count() + 3 <= static_cast<int>(p.y.size())) terms = terms.with(t);
  }
  return terms;
}

// The 95 % points of chi-square with two degrees of freedom and with one.
constexpr double kTwoParameters95 = 5.991464547107979;
constexpr double kOneParameter95 = 3.841458820694124;

// One (phi, T) of the first-order filter, (phi, k) of the moving average,
// (phi, f_c) of the Butterworth, or c of a filter known beyond its memory.
struct Trial {
  double fraction = 0.0;
  // ln(T / tau0); for the Butterworth ln(f_c tau0); c [samples] for kBeyondMemory
  double log_t = 0.0;
  double deviance = kInf;
  int k = 1;  // > 1: a moving average over k samples; kButterworth; kBeyondMemory
};

// Golden section of f on [a, b]; returns the best abscissa and value.
template <class F>
std::pair<double, double> golden(F f, double a, double b) {
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  double x1 = b - g * (b - a), x2 = a + g * (b - a);
  double f1 = f(x1), f2 = f(x2);
  for (int it = 0; it < 30 && b - a > 1e-4; ++it) {
    if (f1 < f2) {
      b = x2, x2 = x1, f2 = f1, x1 = b - g * (b - a), f1 = f(x1);
    } else {
      a = x1, x1 = x2, f1 = f2, x2 = a + g * (b - a), f2 = f(x2);
    }
  }
  return f1 < f2 ? std::pair{x1, f1} : std::pair{x2, f2};
}

class Search {
 public:
  Search(Points& p, NoiseTermSet terms, double tc, double penalty, BandwidthKinds kinds)
      : p_(p),
        terms_(terms),
        tc_(tc),
        tau0_(p.sample_interval_s()),
        penalty_(penalty),
        kinds_(kinds) {}

  SensorBandwidth bandwidth_of(double fraction, double log_t, int k) const {
    if (k == kBeyondMemory) return SensorBandwidth{1.0, 0.0, 1, 0.0, log_t};
    if (k == kButterworth) return SensorBandwidth{fraction, 0.0, 1, std::exp(log_t) / tau0_};
    return k > 1 ? SensorBandwidth{fraction, 0.0, k}
                 : SensorBandwidth{fraction, tau0_ * std::exp(log_t), 1};
  }

  // The reference model's deviance with this bandwidth; infinite when the
  // fit fails or leaves out the white term (a shape that removes the white
  // noise it describes; with every term dropped the deviance can even be 0).
  double deviance(double fraction, double log_t, int k = 1) {
    set_shape(bandwidth_of(fraction, log_t, k));
    const SubsetFit f = fit_subset(p_, terms_, tc_, std::nullopt, NonPositive::drop_term);
    if (!f.feasible || !f.terms.contains(NoiseTerm::white) || !(f.deviance > 0.0)) return kInf;
    return f.deviance;
  }

  // The shapes of the bandwidth; the flicker factor with the whole output
  // filtered depends on the filter alone (not on phi), so it is kept per
  // filter across the trials.
  void set_shape(const SensorBandwidth& bandwidth) {
    p_.white_shape.resize(p_.tau.size());
    p_.flicker_shape.resize(p_.tau.size());
    SensorBandwidth whole = bandwidth;
    whole.filtered_fraction = 1.0;
    auto [it, added] =
        flicker_cache_.try_emplace({whole.moving_average_samples, whole.time_constant_s,
                                    whole.butterworth_cutoff_hz, whole.memory_constant_samples});
    if (added) {
      for (std::size_t i = 0; i < p_.tau.size(); ++i) {
        it->second.push_back(flicker_allan_factor(whole, p_.tau[i], tau0_));
      }
    }
    for (std::size_t i = 0; i < p_.tau.size(); ++i) {
      p_.white_shape[i] = white_allan_factor(bandwidth, p_.tau[i], tau0_);
      p_.flicker_shape[i] = 1.0 - bandwidth.filtered_fraction * (1.0 - it->second[i]);
    }
  }

  std::vector<Trial> trials;  // every (phi, T) tried

  // Nelder-Mead on the first-order filter's (phi, ln T) (or the
  // Butterworth's (phi, ln f_c tau0)) from `start`, with a first simplex of
  // one grid step in each, inside [0, 1] x [lo, hi]; until the simplex's
  // deviances agree to 1e-9 of the best (at most 300 evaluations).
  Trial nelder_mead(const Trial& start, double lo, double hi, double t_step) {
    const int k = start.k;
    struct Vertex {
      double f, t, d;
    };
    auto make = [&](double f, double t) {
      f = std::clamp(f, 0.0, 1.0);
      t = std::clamp(t, lo, hi);
      return Vertex{f, t, tried(f, t, k)};
    };
    const double f_step = 1.0 / kFractionSteps;
    std::array<Vertex, 3> v = {Vertex{start.fraction, start.log_t, start.deviance},
                               make(start.fraction - f_step, start.log_t),
                               make(start.fraction, start.log_t + t_step)};
    for (int evaluations = 2; evaluations < 300;) {
      std::sort(v.begin(), v.end(), [](const Vertex& a, const Vertex& b) { return a.d < b.d; });
      if (!(v[2].d - v[0].d > 1e-9 * std::fabs(v[0].d))) break;
      const double cf = 0.5 * (v[0].f + v[1].f), ct = 0.5 * (v[0].t + v[1].t);
      const Vertex r = make(cf + (cf - v[2].f), ct + (ct - v[2].t));
      ++evaluations;
      if (r.d < v[0].d) {
        const Vertex e = make(cf + 2.0 * (cf - v[2].f), ct + 2.0 * (ct - v[2].t));
        ++evaluations;
        v[2] = e.d < r.d ? e : r;
      } else if (r.d < v[1].d) {
        v[2] = r;
      } else {
        const Vertex c = make(cf + 0.5 * (v[2].f - cf), ct + 0.5 * (v[2].t - ct));
        ++evaluations;
        if (c.d < v[2].d) {
          v[2] = c;
        } else {  // shrink towards the best
          for (int i = 1; i < 3; ++i) {
            v[i] = make(0.5 * (v[0].f + v[i].f), 0.5 * (v[0].t + v[i].t));
            ++evaluations;
          }
        }
      }
    }
    const auto it = std::min_element(v.begin(), v.end(),
                                     [](const Vertex& a, const Vertex& b) { return a.d < b.d; });
    return {it->f, it->t, it->d, k};
  }

  double tried(double fraction, double log_t, int k = 1) {
    const double d = deviance(fraction, log_t, k);
    trials.push_back({fraction, log_t, d, k});
    return d;
  }

  // The best of a grid of kTSteps + 1 values of ln T (or ln f_c tau0) from
  // `lo` in steps of `step`, by kFractionSteps fractions, for kind `k`.
  Trial best_on_grid(double lo, double step, int k) {
    Trial best;
    for (int s = 0; s <= kTSteps; ++s) {
      for (int f = 1; f <= kFractionSteps; ++f) {
        const double fraction = static_cast<double>(f) / kFractionSteps;
        const double d = tried(fraction, lo + step * s, k);
        if (d < best.deviance) best = {fraction, lo + step * s, d, k};
      }
    }
    return best;
  }

  // The largest c tried: a third of the first point's samples (a moving
  // average's memory ends at 2 c samples, a first-order filter's factor
  // differs from 1 - c / m by 4/3 exp(-1.5 m / c) of its correction, 1.5 %
  // at m = 3 c; a cascade's lies between).
  double largest_memory_constant() const { return p_.tau.front() / tau0_ / kMemoryReach; }

  // A filter known beyond its memory: c on a grid up to
  // largest_memory_constant(), then golden section around the grid's best.
  Trial best_beyond_memory() {
    const double most = largest_memory_constant();
    const double step = most / kMemorySteps;
    Trial best;
    for (int s = 1; s <= kMemorySteps; ++s) {
      const double d = tried(1.0, step * s, kBeyondMemory);
      if (d < best.deviance) best = {1.0, step * s, d, kBeyondMemory};
    }
    if (!std::isfinite(best.deviance)) return best;
    const auto [c, d] =
        golden([&](double x) { return tried(1.0, x, kBeyondMemory); },
               std::max(1e-3 * step, best.log_t - step), std::min(most, best.log_t + step));
    if (d < best.deviance) best = {1.0, c, d, kBeyondMemory};
    return best;
  }

  Trial best() {
    if (kinds_ == BandwidthKinds::beyond_memory) return best_beyond_memory();
    const double lo = std::log(kShortestT), hi = std::log(kLongestT);
    const double t_step = (hi - lo) / kTSteps;
    Trial best = best_on_grid(lo, t_step, 1);
    // The moving averages: each length at kFractionSteps fractions.
    Trial best_ma;
    auto try_length = [&](int k) {
      for (int f = 1; f <= kFractionSteps; ++f) {
        const double fraction = static_cast<double>(f) / kFractionSteps;
        const double d = tried(fraction, 0.0, k);
        if (d < best_ma.deviance) best_ma = {fraction, 0.0, d, k};
      }
    };
    for (const int k : kMovingAverageLengths) try_length(k);
    // Beyond the lengths tried one by one, every length between the grid's
    // neighbours of the best.
    const int grid_best = best_ma.k;
    const auto at =
        std::find(kMovingAverageLengths.begin(), kMovingAverageLengths.end(), grid_best);
    if (at != kMovingAverageLengths.end() && grid_best > kEveryMovingAverageTo) {
      const int from = *std::prev(at) + 1;
      const int to = std::next(at) == kMovingAverageLengths.end() ? grid_best : *std::next(at) - 1;
      for (int k = from; k <= to; ++k) {
        if (k != grid_best) try_length(k);
      }
    }
    if (std::isfinite(best_ma.deviance)) {
      const double f_step = 1.0 / kFractionSteps;
      const auto [fraction, d_f] = golden([&](double x) { return tried(x, 0.0, best_ma.k); },
                                          std::max(0.0, best_ma.fraction - f_step),
                                          std::min(1.0, best_ma.fraction + f_step));
      if (d_f < best_ma.deviance) best_ma = {fraction, 0.0, d_f, best_ma.k};
    }
    // The Butterworth cut-offs.
    const double c_lo = std::log(kLowestCutoff), c_hi = std::log(kHighestCutoff);
    const double c_step = (c_hi - c_lo) / kTSteps;
    Trial best_bw = kinds_ == BandwidthKinds::with_butterworth
                        ? best_on_grid(c_lo, c_step, kButterworth)
                        : Trial{};
    // Refinement from the best grid point: phi and T trade off along a
    // narrow valley (0.77 of the noise through a 25 % longer T looks much
    // the same), which steps along one coordinate at a time crawl down, so
    // a Nelder-Mead simplex in (phi, ln T), kept inside the box; the same
    // for the Butterworth's (phi, ln f_c).
    if (std::isfinite(best.deviance)) best = nelder_mead(best, lo, hi, t_step);
    if (best_ma.deviance < best.deviance) best = best_ma;
    if (!std::isfinite(best_bw.deviance)) return best;
    best_bw = nelder_mead(best_bw, c_lo, c_hi, c_step);
    const int spare = static_cast<int>(p_.y.size()) - terms_.parameter_count() - 2;
    const double margin = std::isfinite(best.deviance)
                              ? penalty_ * std::max(1.0, best.deviance / std::max(1, spare))
                              : 0.0;
    return best_bw.deviance < best.deviance - margin ? best_bw : best;
  }

 private:
  Points& p_;
  NoiseTermSet terms_;
  double tc_;  // the reference's Gauss-Markov Tc (1 without the term)
  double tau0_;
  double penalty_;        // one parameter's cost in the selection criterion
  BandwidthKinds kinds_;  // the kinds tried
  // (k, T, f_c, c): the flicker factors
  std::map<std::tuple<int, double, double, double>, std::vector<double>> flicker_cache_;
};

// The bandwidth's drop in the points' generalised-least-squares distance
// r' C^-1 r from the reference fit, with C the exact covariance of the
// points under that fit (point_covariance()). Neighbouring taus share most
// of their data, so the gamma deviance, which counts the points as
// independent, counts a bend over a few neighbouring taus about twice: on
// unfiltered white noise with weak flicker (1 h at 10 Hz, 400 units) it
// passed 2 x the penalty in 1 % of the records, where this drop was 5.6-8.4;
// a real filter's is 10^2-10^5 (docs/validation.md). NaN where the
// covariance is unknown (no averaging factors) or singular.
double correlated_drop(Points& p, const SubsetFit& plain, const SensorBandwidth& bandwidth,
                       NoiseTermSet terms, double tc) {
  if (p.factors.empty()) return kNaN;
  set_bandwidth_shapes(p, bandwidth);
  const SubsetFit with = fit_subset(p, terms, tc, std::nullopt, NonPositive::drop_term);
  set_bandwidth_shapes(p, {});
  if (!with.feasible) return 0.0;
  const auto n = static_cast<Eigen::Index>(p.y.size());
  Eigen::VectorXd without_r(n), with_r(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    without_r(i) = p.y[k] - plain.mu[k];
    with_r(i) = p.y[k] - with.mu[k];
  }
  const Eigen::LDLT<Eigen::MatrixXd> c(point_covariance(p, plain));
  if (c.info() != Eigen::Success || !c.isPositive()) return kNaN;
  return without_r.dot(c.solve(without_r)) - with_r.dot(c.solve(with_r));
}

}  // namespace

double find_line_scale(Points& p, const NoiseFitOptions& options) {
  if (p.line_avar.empty()) return p.line_scale;
  const NoiseTermSet terms = reference_terms(p, false);
  if (!terms.contains(NoiseTerm::white)) return p.line_scale;
  auto set_scale = [&p](double scale) {
    for (std::size_t i = 0; i < p.fixed_avar.size(); ++i) {
      p.fixed_avar[i] += (scale - p.line_scale) * p.line_avar[i];
    }
    p.line_scale = scale;
  };
  auto deviance = [&](double log_scale) {
    set_scale(std::exp(log_scale));
    const SubsetFit f = fit_subset(p, terms, 1.0, std::nullopt, NonPositive::drop_term);
    return f.feasible && f.terms.contains(NoiseTerm::white) ? f.deviance : kInf;
  };
  const double as_read = deviance(0.0);
  // A grid over 1/8 .. 8, then golden-section steps around its best.
  constexpr double kLogRange = 2.0794415416798357;  // ln 8
  constexpr int kSteps = 24;
  double best_log = 0.0, best = as_read;
  for (int k = 0; k <= kSteps; ++k) {
    const double x = -kLogRange + 2.0 * kLogRange * k / kSteps;
    if (const double d = deviance(x); d < best) best = d, best_log = x;
  }
  const double step = 2.0 * kLogRange / kSteps;
  const auto [x, d] = golden(deviance, best_log - step, best_log + step);
  if (d < best) best = d, best_log = x;
  const int spare = static_cast<int>(p.y.size()) - terms.parameter_count() - 1;
  const double dispersion = std::max(1.0, best / std::max(1, spare));
  const bool taken = std::isfinite(best) && as_read - best > options.penalty * dispersion;
  set_scale(taken ? std::exp(best_log) : 1.0);
  return p.line_scale;
}

double memory_constant_of(const SensorBandwidth& bandwidth, double sample_interval_s) {
  if (bandwidth.beyond_memory())
    return bandwidth.filtered_fraction * bandwidth.memory_constant_samples;
  // Far beyond every kind's memory (128 samples, T of 10 samples, f_c of
  // 0.016 / tau0), where m (1 - factor) is c.
  constexpr double kFar = 65536.0;
  return kFar * (1.0 - white_allan_factor(bandwidth, kFar * sample_interval_s, sample_interval_s));
}

void set_bandwidth_shapes(Points& p, const SensorBandwidth& bandwidth) {
  p.white_shape.clear();
  p.flicker_shape.clear();
  const double tau0 = p.sample_interval_s();
  if (!bandwidth.any() || !(tau0 > 0.0)) return;
  for (std::size_t i = 0; i < p.tau.size(); ++i) {
    p.white_shape.push_back(white_allan_factor(bandwidth, p.tau[i], tau0));
    p.flicker_shape.push_back(flicker_allan_factor(bandwidth, p.tau[i], tau0));
  }
}

BandwidthSearch find_bandwidth(Points& p, const NoiseFitOptions& options, double gm_tc_s,
                               BandwidthKinds kinds) {
  BandwidthSearch result;
  BandwidthEstimate& e = result.estimate;
  e.sample_interval_s = p.sample_interval_s();
  set_bandwidth_shapes(p, {});
  if (!options.model_bandwidth || !(e.sample_interval_s > 0.0)) return result;
  const bool gauss_markov = gm_tc_s > 0.0;
  const double tc = gauss_markov ? gm_tc_s : 1.0;
  const NoiseTermSet terms = reference_terms(p, gauss_markov);
  if (!terms.contains(NoiseTerm::white)) return result;
  const SubsetFit plain = fit_subset(p, terms, tc, std::nullopt, NonPositive::drop_term);
  Search search(p, terms, tc, options.penalty, kinds);
  const Trial best = search.best();
  set_bandwidth_shapes(p, {});
  result.reference_deviance = plain.deviance;
  if (!std::isfinite(best.deviance) || !std::isfinite(plain.deviance)) return result;

  const SensorBandwidth bandwidth = search.bandwidth_of(best.fraction, best.log_t, best.k);
  const double reduction = 1.0 - white_allan_factor(bandwidth, p.tau.front(), e.sample_interval_s);
  const int parameters = best.k == kBeyondMemory ? 1 : 2;  // the kind's
  const int spare = static_cast<int>(p.y.size()) - terms.parameter_count() - parameters;
  const double dispersion = std::max(1.0, best.deviance / std::max(1, spare));
  e.deviance_drop = plain.deviance - best.deviance;
  // At the longest T searched the data want a correlation longer than a
  // filter's: a random-bias process the reference model lacks (a Gauss-
  // Markov hump) bends the first taus, and that is left to the candidates.
  // For the Butterworth: the lowest cut-off, and the highest too, where the
  // data want a roll-off at the Nyquist frequency or beyond, which no
  // sampled filter makes (an aliased PSD that falls towards the Nyquist
  // frequency, as in the ADIS16405 z axes with every fourth sample kept).
  const bool butterworth_bound =
      best.log_t <= std::log(kLowestCutoff) + 1e-3 || best.log_t >= std::log(kHighestCutoff) - 1e-3;
  e.at_search_bound = best.k > 1               ? best.k == kLongestMovingAverage
                      : best.k == kButterworth ? butterworth_bound
                      : best.k == kBeyondMemory
                          ? best.log_t >= (1.0 - 1e-3) * search.largest_memory_constant()
                          : best.log_t >= std::log(kLongestT) - 1e-3;
  const double cost = parameters * options.penalty;
  if (e.at_search_bound) return result;
  const double near = parameters == 1 ? kOneParameter95 : kTwoParameters95;
  const auto collect_near = [&] {
    for (const Trial& t : search.trials) {
      if (t.deviance <= best.deviance + near * dispersion) {
        result.near.push_back(search.bandwidth_of(t.fraction, t.log_t, t.k));
      }
    }
  };
  if (best.k == kBeyondMemory) {
    // Sought only where the first taus were left out for a filter no kind
    // followed: it is there, and its c is carried, with the c the data do
    // not tell apart, even where the kept taus cannot resolve it. Dropped
    // as unresolved it left its c / m in N: a 3-sample average behind a
    // 1 s low-pass (c = 2) at 1 Hz, 24 h, the taus from 8 s, where flicker
    // soon takes over: N 20 % low. With c near 0 it is not reported (on
    // the ADIS16405 z axes with every fourth sample kept, c came out 0: no
    // filter left there), but the intervals still span the c not told
    // apart (a Gauss-Markov process beside the same cascade took the bend
    // and c came out 0: N 17 % low, B 33-44 % high, both outside their
    // intervals on three seeds; with the intervals over c, N's holds the
    // truth on one of them and B's on two).
    collect_near();
    if (reduction < kSmallestEffect) return result;
  } else {
    if (!(e.deviance_drop > cost * dispersion) || reduction < kSmallestEffect) return result;
    e.correlated_deviance_drop = correlated_drop(p, plain, bandwidth, terms, tc);
    if (e.correlated_deviance_drop <= cost * dispersion) return result;
    collect_near();
  }
  e.resolved = true;
  result.reference_deviance = best.deviance;
  e.bandwidth = bandwidth;
  e.cutoff_hz = cutoff_hz(bandwidth, e.sample_interval_s);
  e.lag1_correlation = white_lag1_correlation(bandwidth, e.sample_interval_s);
  e.first_tau_reduction = reduction;
  set_bandwidth_shapes(p, bandwidth);
  return result;
}

void widen_over_bandwidths(const Points& p, const SubsetFit& chosen,
                           std::span<const SensorBandwidth> near, NoiseFitResult& r) {
  if (near.empty()) return;
  // Each coefficient's interval as the chosen bandwidth gives it, moved by
  // each near bandwidth's ratio: the union of those, not a product (the
  // ends had been widened in place, each ratio on top of the last: on a 1 Hz
  // record with 42 near c, N's upper end came out 35 times the estimate
  // where the largest single ratio was 1.38).
  std::array<ParameterEstimate, kNoiseParameters.size()> as_chosen;
  for (std::size_t i = 0; i < kNoiseParameters.size(); ++i) {
    as_chosen[i] = r.estimate(kNoiseParameters[i]);
  }
  Points q = p;
  q.v = chosen.v;
  for (const SensorBandwidth& b : near) {
    set_bandwidth_shapes(q, b);
    const SubsetFit f = fit_subset(q, chosen.terms, chosen.tc);
    if (!f.feasible) continue;
    for (std::size_t i = 0; i < kNoiseParameters.size(); ++i) {
      const NoiseParameter& parameter = kNoiseParameters[i];
      const NoiseTerm t = parameter.term;
      if (!chosen.terms.contains(t) || parameter.value == &NoiseModel::gm_tc) continue;
      ParameterEstimate& e = r.estimate(parameter);
      if (e.status != TermStatus::resolved || !(chosen.squared(t) > 0.0)) continue;
      const double ratio = std::sqrt(std::max(0.0, f.squared(t)) / chosen.squared(t));
      e.ci95_low = std::min(e.ci95_low, as_chosen[i].ci95_low * ratio);
      e.ci95_high = std::max(e.ci95_high, as_chosen[i].ci95_high * ratio);
    }
  }
}

}  // namespace foglab::model::detail
