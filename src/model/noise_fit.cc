// foglab — the noise-model fit (noise_fit.h): its six steps in order
// (noise_fit_internal.h names the files that do each).
#include "foglab/model/noise_fit.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>

#include "foglab/core/error.h"
#include "foglab/stats/edf.h"
#include "noise_fit_internal.h"

namespace foglab::model {
namespace {

// How the fit ended, in the chosen candidate's reweighting loop, and how
// many of the other candidates stopped at the iteration limit.
void set_status(const detail::SubsetFit& chosen, std::span<const detail::SubsetFit> fits,
                const NoiseFitOptions& options, NoiseFitResult& r) {
  r.status = chosen.status;
  r.iterations = chosen.iterations;
  const auto limited = std::count_if(fits.begin(), fits.end(), [](const detail::SubsetFit& f) {
    return f.status == FitStatus::iteration_limit;
  });
  const Message others = limited == 0 ? Message(Text::fit_others_converged)
                                      : Message(Text::fit_others_limited, limited, fits.size());
  r.outcome = Message(
      chosen.status == FitStatus::converged ? Text::fit_converged : Text::fit_iteration_limit,
      chosen.terms, chosen.iterations, options.tolerance, others);
  r.message = r.outcome.text();
}

// A fit that could not be done: no candidate was feasible. Every parameter
// is absent, with no value and no bound.
NoiseFitResult degenerate(const detail::Points& p) {
  NoiseFitResult r;
  r.status = FitStatus::degenerate;
  r.outcome = Message(Text::fit_degenerate, p.y.size());
  r.message = r.outcome.text();
  r.points = static_cast<int>(p.y.size());
  r.deviance = kNaN;
  r.dispersion = kNaN;
  for (const NoiseParameter& parameter : kNoiseParameters) {
    r.estimate(parameter) = {kNaN, kNaN, kNaN, kNaN, TermStatus::absent};
  }
  return r;
}

// The known Allan variance at every point: the output word's rounding
// (white noise of level `known_white`) and the spectral lines still in the
// record (not removed_from_record).
void add_known_allan_variance(detail::Points& p, double known_white,
                              std::span<const SpectralLine> lines) {
  if (!(known_white >= 0.0) || !std::isfinite(known_white)) {
    throw UsageError(fmt::format(
        "NoiseFitOptions::known_white_deg_h_sqrt_hz must be finite and >= 0, got {}", known_white));
  }
  const double tau0 = p.sample_interval_s();
  const bool with_lines = !lines.empty() && tau0 > 0.0;
  if (!with_lines && known_white == 0.0) return;
  p.fixed_avar.assign(p.tau.size(), 0.0);
  const bool scaled = with_lines && std::any_of(lines.begin(), lines.end(), [](const auto& line) {
                        return line.takes_variance_scale;
                      });
  if (scaled) p.line_avar.assign(p.tau.size(), 0.0);
  for (std::size_t i = 0; i < p.tau.size(); ++i) {
    p.fixed_avar[i] += known_white * known_white / p.tau[i];
    if (!with_lines) continue;
    for (const SpectralLine& line : lines) {
      if (line.removed_from_record) continue;
      const double avar = line_allan_variance(line, p.tau[i], tau0);
      if (line.takes_variance_scale) p.line_avar[i] += avar;
      p.fixed_avar[i] += avar;
    }
  }
}

// The sensor bandwidth, then the lines' variance factor the short taus ask
// for (the PSD's bins hold a broad line's variance only in part), and, when
// that moved, the bandwidth again with it: both shape the first taus.
// With lines the search is made twice, with the first-order and moving-
// average kinds and with the Butterworth too, and the Butterworth's answer
// is taken only when it ends more than one parameter's penalty better: a
// line and a filter share the first taus, and before the line's factor is
// found the Butterworth can win for the line's sake (on the ADIS16405 z
// axes it did, and N came out 1-2 % lower with a worse model).
detail::BandwidthSearch find_bandwidth_and_line_scale(detail::Points& p,
                                                      const NoiseFitOptions& options) {
  using detail::BandwidthKinds;
  auto search = [&options](detail::Points& q, BandwidthKinds kinds) {
    detail::BandwidthSearch bandwidth = detail::find_bandwidth(q, options, 0.0, kinds);
    if (q.line_avar.empty() || detail::find_line_scale(q, options) == 1.0) return bandwidth;
    return detail::find_bandwidth(q, options, 0.0, kinds);
  };
  if (p.line_avar.empty()) return search(p, BandwidthKinds::with_butterworth);
  detail::Points with = p;
  detail::BandwidthSearch established = search(p, BandwidthKinds::established);
  detail::BandwidthSearch all = search(with, BandwidthKinds::with_butterworth);
  if (!all.estimate.bandwidth.butterworth()) return established;
  const int spare = static_cast<int>(p.y.size()) - 7;  // the reference's terms, phi, f_c, scale
  const double margin =
      options.penalty * std::max(1.0, established.reference_deviance / std::max(1, spare));
  if (!(all.reference_deviance < established.reference_deviance - margin)) return established;
  p = std::move(with);
  return all;
}

// The bandwidth was found against a reference model without a random bias;
// a slow Gauss-Markov hump the reference lacks can pass for a filter (a
// 29-sample moving average on a 20 Hz record with Tc = 47 s). When the
// chosen model has such a process (Tc beyond 100 samples, far from any
// filter), the search is repeated with it in the reference, and a bandwidth
// it no longer finds is dropped (with the candidates refitted). The chosen
// Tc was fitted beside the bandwidth, which can have taken the hump's short
// side and pushed Tc out (a 108-sample moving average with 95 % of N^2 and
// Tc 306 s, for a 100 s process on a 1 Hz record, N 4.5 times too high):
// the Tc the best Gauss-Markov candidate has without any bandwidth is tried
// as well, when it is a process the taus resolve (10 samples or more; the
// ADIS16405's half-sample Gauss-Markov term is the filter itself). Another
// filter found beside the process replaces the first when its candidates
// fit better.
//
// Conversely, that hump can hide a filter: on a 1 Hz record with a 100 s
// process the reference bent its white level to the hump, no bandwidth
// stood out, and a 0.54 s low-pass left N 6-7 % low with the first taus
// left out. When none was found and a candidate has a process the taus
// resolve, the search is repeated with the best such candidate's in the
// reference.
void recheck_bandwidth(detail::Points& p, detail::BandwidthSearch& bandwidth,
                       std::vector<detail::SubsetFit>& fits, const NoiseFitOptions& options) {
  constexpr double kSlowProcessSamples = 100.0;
  constexpr double kResolvedProcessSamples = 10.0;
  // Takes a bandwidth found again, the points it shaped and the fits over them.
  const auto adopt = [&](detail::Points& with, detail::BandwidthSearch& found,
                         std::vector<detail::SubsetFit> refits) {
    p = std::move(with);
    bandwidth = std::move(found);
    fits = std::move(refits);
  };
  if (!bandwidth.estimate.resolved) {
    // The best candidate with such a process (the chosen one can be without
    // it while the filtered first taus spoil every fit).
    const auto slow = std::find_if(fits.begin(), fits.end(), [&](const detail::SubsetFit& f) {
      return f.terms.contains(NoiseTerm::gauss_markov) &&
             f.tc >= kResolvedProcessSamples * p.sample_interval_s();
    });
    if (slow == fits.end()) return;
    detail::Points with = p;
    detail::BandwidthSearch found = detail::find_bandwidth(with, options, slow->tc);
    if (found.estimate.resolved) adopt(with, found, detail::fit_candidates(with, options));
    return;
  }
  if (fits.empty() || !fits.front().terms.contains(NoiseTerm::gauss_markov) ||
      fits.front().tc < kSlowProcessSamples * p.sample_interval_s()) {
    return;
  }
  std::vector<double> tcs = {fits.front().tc};
  detail::Points unfiltered = p;
  detail::set_bandwidth_shapes(unfiltered, {});
  for (const detail::SubsetFit& f : detail::fit_candidates(unfiltered, options)) {
    if (!f.terms.contains(NoiseTerm::gauss_markov)) continue;
    if (f.tc >= kResolvedProcessSamples * p.sample_interval_s()) tcs.push_back(f.tc);
    break;
  }
  std::optional<std::pair<detail::Points, detail::BandwidthSearch>> beside;
  for (const double tc : tcs) {
    detail::Points plain = p;
    detail::BandwidthSearch again = detail::find_bandwidth(plain, options, tc);
    if (again.estimate.resolved) {
      if (!beside) beside.emplace(std::move(plain), std::move(again));
      continue;
    }
    adopt(plain, again, detail::fit_candidates(plain, options));
    return;
  }
  // Found beside the process too: when it is another filter than the one
  // found without it (another kind or length, a time constant or cut-off
  // 10 % away, or a filtered fraction 0.05 away), that one, if its best
  // candidate fits better (on a 1 Hz record with a 4-sample moving average
  // and a 100 s process the search without the process took a 3-sample
  // one, every candidate's deviance 505 on 14 points). The same filter
  // found again stands as it was (adopting it anyway moved the ADIS16405
  // 2z axis from N+B+K to N+R+GM for a filtered fraction 0.002 apart).
  if (!beside) return;
  const SensorBandwidth& first = bandwidth.estimate.bandwidth;
  const SensorBandwidth& again = beside->second.estimate.bandwidth;
  auto apart = [](double a, double b) { return std::fabs(a - b) > 0.1 * std::max(a, b); };
  if (std::fabs(first.filtered_fraction - again.filtered_fraction) <= 0.05 &&
      first.moving_average_samples == again.moving_average_samples &&
      first.butterworth() == again.butterworth() &&
      !apart(first.butterworth_cutoff_hz, again.butterworth_cutoff_hz) &&
      !apart(first.time_constant_s, again.time_constant_s)) {
    return;
  }
  std::vector<detail::SubsetFit> refits = detail::fit_candidates(beside->first, options);
  if (!refits.empty() && refits.front().deviance < fits.front().deviance) {
    adopt(beside->first, beside->second, std::move(refits));
  }
}

// The result with fits.front() as the chosen model: its status, the
// candidates, the random-bias evidence (step 3) and the intervals (4-6).
NoiseFitResult conclude(const detail::Points& p, const std::vector<detail::SubsetFit>& fits,
                        const detail::BandwidthSearch& bandwidth, double known_white,
                        std::span<const SpectralLine> lines, const NoiseFitOptions& options) {
  const detail::SubsetFit& chosen = fits.front();
  NoiseFitResult r;
  set_status(chosen, fits, options, r);
  r.model = detail::to_model(chosen);
  r.bandwidth = bandwidth.estimate;
  if (!lines.empty() && p.sample_interval_s() > 0.0) {
    r.lines.assign(lines.begin(), lines.end());
    r.line_variance_scale = p.line_scale;
    for (SpectralLine& line : r.lines) {
      if (!line.takes_variance_scale) continue;
      line.variance *= p.line_scale;
      for (double& v : line.bin_variance) v *= p.line_scale;
    }
  }
  r.known_white_deg_h_sqrt_hz = known_white;
  r.terms = chosen.terms;
  r.deviance = chosen.deviance;
  r.points = static_cast<int>(p.y.size());
  r.parameters = chosen.terms.parameter_count();
  r.dispersion = std::max(1.0, chosen.deviance / std::max(1, r.points - r.parameters));
  for (const detail::SubsetFit& f : fits)
    r.candidates.push_back(detail::candidate(f, options.penalty));
  detail::collect_random_bias_evidence(fits, options.penalty, r);
  const detail::ChosenModel model = detail::chosen_model(p, chosen, r.dispersion);
  detail::set_chosen_intervals(model, options, r);
  detail::bound_left_out_terms(model, options, r);
  detail::widen_over_near_candidates(p, model, fits, options, r);
  detail::widen_over_bandwidths(p, chosen, bandwidth.near, r);
  return r;
}

// A Gauss-Markov term is the random bias only when the record shows its
// hump turning down: the Allan variance of the process peaks near 1.89 Tc,
// so Tc's 95 % interval must close below the longest tau over 1.89.
// Otherwise, unless it fits better than the best Wiener candidate by more
// than two parameters' worth of the criterion, the record cannot tell it
// from a random walk (a Gauss-Markov process far from its Tc is one) and
// the Wiener candidate goes to the front of `fits`; returns why (empty:
// the chosen model stands).
Message set_aside_unresolved_gauss_markov(const detail::Points& p,
                                          std::vector<detail::SubsetFit>& fits,
                                          const NoiseFitResult& r, const NoiseFitOptions& options) {
  constexpr double kHumpOverTc = 1.89;
  if (r.random_bias_process != RandomBiasProcess::gauss_markov ||
      kHumpOverTc * r.gm_tc.ci95_high <= p.tau.back()) {
    return {};
  }
  const auto wiener = std::find_if(fits.begin(), fits.end(), [](const detail::SubsetFit& f) {
    return f.terms.contains(NoiseTerm::random_walk) && !f.terms.contains(NoiseTerm::gauss_markov);
  });
  if (wiener == fits.end()) return {};
  const double gm_criterion = detail::candidate(fits.front(), options.penalty).criterion;
  const double wiener_criterion = detail::candidate(*wiener, options.penalty).criterion;
  if (wiener_criterion - gm_criterion > 2.0 * options.penalty) return {};
  Message why(Text::fit_gm_set_aside, fits.front().terms, gm_criterion, wiener_criterion,
              r.gm_tc.value, r.gm_tc.ci95_low, r.gm_tc.ci95_high, kHumpOverTc,
              p.tau.back() / kHumpOverTc, wiener->terms);
  std::rotate(fits.begin(), wiener, wiener + 1);
  return why;
}

// A rate ramp R is a deterministic trend, which the record's least-squares
// slope estimates (NoiseFitOptions::record_slope_deg_h_s). When the chosen
// model's R is resolved and its 95 % interval lies above |slope| + 3
// standard deviations of the slope under the model's other terms, the
// rise at the last taus is not a ramp in this record (a random walk's
// excursion ends a record steeper than it runs through it): every
// candidate with R is left out of `fits`; returns why (empty: it stands).
Message set_aside_unsupported_ramp(std::vector<detail::SubsetFit>& fits, const NoiseFitResult& r,
                                   const NoiseFitOptions& options) {
  constexpr double kSigmas = 3.0;
  const double slope = options.record_slope_deg_h_s, span = options.record_span_s;
  if (!r.terms.contains(NoiseTerm::ramp) || r.R.status != TermStatus::resolved ||
      !std::isfinite(slope) || !(span > 0.0)) {
    return {};
  }
  NoiseModel others = r.model;
  others.R = 0.0;
  const double sd = slope_standard_deviation(others, span);
  const double supported = std::fabs(slope) + kSigmas * sd;
  if (!(r.R.ci95_low > supported)) return {};
  const auto kept = std::count_if(fits.begin(), fits.end(), [](const detail::SubsetFit& f) {
    return !f.terms.contains(NoiseTerm::ramp);
  });
  if (kept == 0) return {};
  std::erase_if(fits, [](const detail::SubsetFit& f) { return f.terms.contains(NoiseTerm::ramp); });
  return Message(Text::fit_ramp_set_aside, r.terms, r.model.R, r.R.ci95_low, r.R.ci95_high, span,
                 slope, r.terms.without(NoiseTerm::ramp), supported);
}

// The chosen model's dispersion: its deviance over its degrees of freedom
// (infinite when it has none to spare).
double dispersion_of(const detail::Points& p, const detail::SubsetFit& chosen) {
  const int dof = static_cast<int>(p.y.size()) - chosen.terms.parameter_count();
  return dof > 0 ? chosen.deviance / dof : detail::kInf;
}

// Leaves out the first point of `p`.
void drop_first_point(detail::Points& p) {
  auto drop = [](auto& v) {
    if (!v.empty()) v.erase(v.begin());
  };
  drop(p.tau), drop(p.y), drop(p.v), drop(p.index), drop(p.edf_by_alpha), drop(p.factors);
  drop(p.term_share), drop(p.edf_reduction);
  drop(p.fixed_avar), drop(p.line_avar), drop(p.white_shape), drop(p.flicker_shape);
}

// `p` without its first `count` points, the bandwidth searched again (a
// filter known beyond its memory, the one kind that holds for any shape
// there) and every candidate refitted on the rest. The spectral lines keep
// the factor found on all the points: the first taus, where a line's Allan
// signature stands out, are what fix it (without them it fell back to the
// PSD's, and a broad resonance lost a quarter of its variance).
struct Refit {
  detail::Points points;
  detail::BandwidthSearch bandwidth;
  std::vector<detail::SubsetFit> fits;
};

Refit refit_without_first(const detail::Points& p, int count, const NoiseFitOptions& options) {
  Refit r{p, {}, {}};
  for (int i = 0; i < count; ++i) drop_first_point(r.points);
  r.bandwidth =
      detail::find_bandwidth(r.points, options, 0.0, detail::BandwidthKinds::beyond_memory);
  r.fits = detail::fit_candidates(r.points, options);
  return r;
}

// The output filter of a real sensor can be a cascade (an analog anti-
// alias filter, then a digital decimation filter) that none of the
// modelled kinds follows; the first taus then pull every term (a first-
// order low-pass of 2 samples behind a Butterworth at 0.3 fs: N 44 % low
// and a Gauss-Markov term). When the chosen model's dispersion is above
// kMisfit, the first one to four points are left out and everything
// refitted with a filter known beyond its memory (core/sensor_bandwidth.h:
// the white Allan variance N^2 / tau (1 - c tau0 / tau) for any filter
// shape, once tau is past the memory): the fewest that bring it to kMisfit
// or below, else those that lower it most, if below kGain of what it was
// (keeping eight points); counts whose first kept tau is still inside the
// memory (c wanted beyond a third of its samples) only when no other lowers it.
// N is then the white level above the filter. Before that term, the
// remaining taus were fitted with one of the modelled kinds, whose shape at
// the first kept taus is not the cascade's: a 3-sample average behind a
// first-order low-pass of one sample, 2 h at 100 Hz, N's 95 % interval held
// the truth in 45 of 60 records, missing by up to 0.8 % of N. With spectral lines too
// (which keep the factor found on all the taus): a cascade with a
// sinusoid had kept its first taus, and N came out 9-12.5 % low with an
// angle quantisation Q in the model; now within 1.6 %. (This had been
// left out when a broad line's skirts were not yet part of it, and its
// bumps further out were taken for Q.) The intervals are widened over the
// c the remaining taus do not tell apart (widen_over_bandwidths()). N's had
// spanned the fits with one and two taus more left out as well, for the
// single kind's bend at the first kept taus; with c that union changed no
// record's coverage (tactical grade, 60 seeds: 96 %) and only widened N's
// interval (a 3-sample average behind a 10 ms low-pass, 2 h at 100 Hz,
// seed 1: -3.8 / +2.3 % of N against +-1.1 % without it).
struct LeftOut {
  int count = 0;
  double first_tau_s = 0.0, last_tau_s = 0.0;  ///< [s] the first and the last left out
};

LeftOut leave_out_unfollowed_first_taus(detail::Points& p, detail::BandwidthSearch& bandwidth,
                                        std::vector<detail::SubsetFit>& fits,
                                        const NoiseFitOptions& options) {
  constexpr double kMisfit = 4.0;
  constexpr double kGain = 0.7;
  constexpr int kMostLeftOut = 4;
  LeftOut left_out;
  if (fits.empty() || !(dispersion_of(p, fits.front()) > kMisfit)) {
    return left_out;
  }
  std::optional<Refit> best;
  double best_dispersion = detail::kInf;
  bool best_inside_memory = true;
  int best_count = 0;
  for (int k = 1; k <= kMostLeftOut && p.y.size() > static_cast<std::size_t>(7 + k); ++k) {
    Refit trial = refit_without_first(p, k, options);
    if (trial.fits.empty()) break;
    const double d = dispersion_of(trial.points, trial.fits.front());
    const bool inside_memory = trial.bandwidth.estimate.at_search_bound;
    if (!best || std::pair{inside_memory, d} < std::pair{best_inside_memory, best_dispersion}) {
      best = std::move(trial), best_dispersion = d, best_count = k;
      best_inside_memory = inside_memory;
    }
    if (d <= kMisfit && !inside_memory) break;
  }
  if (!best || !(best_dispersion < kGain * dispersion_of(p, fits.front()))) return left_out;
  left_out = {best_count, p.tau.front(), p.tau[static_cast<std::size_t>(best_count) - 1]};
  p = std::move(best->points);
  bandwidth = std::move(best->bandwidth);
  fits = std::move(best->fits);
  return left_out;
}

// [samples] Where a filter's memory ends: kMemoryReach times its c. The
// fit that assumes no kind leaves out the taus inside; the bias
// instability is read beyond it (NoiseFitResult::filter_memory_end_tau_s).
double memory_reach_samples(const SensorBandwidth& b, double tau0) {
  return detail::kMemoryReach * detail::memory_constant_of(b, tau0);
}

// The modelled kinds (first-order, moving average, Butterworth) each bend
// the first taus in a shape of their own, and a real filter can be none of
// them. Where white noise rules only a few octaves before flicker does,
// that shape decides N: at 1 Hz over 24 h, a 3-sample average behind a 1 s
// low-pass (tactical grade, N 0.3) was taken for a Butterworth at 0.14 Hz
// that fitted every tau, and N came out 22 % low with an interval of
// -4 / +9 % (the Butterworths the taus do not tell apart). So each
// resolved coefficient's interval also spans the fit that assumes no kind:
// the taus inside the chosen filter's memory (m below kMemoryReach times
// its c) left out, the rest fitted with a filter known beyond its memory
// (one or two more left out when that c still wants the first kept tau),
// whose own interval spans the c they do not tell apart. Past the memory
// that fit holds for any filter (here N 0.33 [0.22, 0.34]). It costs
// width where the kind is right: a 4-sample average at 100 Hz, 2 h, N's
// interval -0.84 / +0.78 % where the kind's own was +-0.25 %. Returns how
// many taus it left out (-1: none was made: no bandwidth, or one known
// only beyond its memory).
int widen_over_filter_shape(const detail::Points& p, const detail::BandwidthSearch& bandwidth,
                            double known_white, std::span<const SpectralLine> lines,
                            const NoiseFitOptions& options, NoiseFitResult& r) {
  constexpr int kMoreLeftOut = 2;
  const SensorBandwidth& b = bandwidth.estimate.bandwidth;
  const double tau0 = p.sample_interval_s();
  if (!bandwidth.estimate.resolved || b.beyond_memory() || !(tau0 > 0.0)) return -1;
  const double reach = memory_reach_samples(b, tau0);
  const auto inside = static_cast<int>(
      std::count_if(p.tau.begin(), p.tau.end(), [&](double tau) { return tau / tau0 < reach; }));
  for (int k = inside; k <= inside + kMoreLeftOut && p.y.size() > static_cast<std::size_t>(7 + k);
       ++k) {
    Refit shape_free = refit_without_first(p, k, options);
    if (shape_free.fits.empty()) return -1;
    if (shape_free.bandwidth.estimate.at_search_bound) continue;
    const NoiseFitResult other = conclude(shape_free.points, shape_free.fits, shape_free.bandwidth,
                                          known_white, lines, options);
    if (other.N.status == TermStatus::resolved) r.shape_free_n = other.N.value;
    for (const NoiseParameter& parameter : kNoiseParameters) {
      ParameterEstimate& e = r.estimate(parameter);
      const ParameterEstimate& o = other.estimate(parameter);
      if (e.status != TermStatus::resolved || o.status != TermStatus::resolved) continue;
      if (std::isfinite(o.ci95_low)) e.ci95_low = std::min(e.ci95_low, o.ci95_low);
      if (!std::isnan(o.ci95_high)) e.ci95_high = std::max(e.ci95_high, o.ci95_high);
    }
    return k;
  }
  return -1;
}

NoiseFitResult fit_impl(std::span<const double> tau_s, std::span<const double> adev_deg_h,
                        std::span<const double> edf, std::span<const std::int64_t> factors,
                        std::span<const std::int64_t> segment_points,
                        std::span<const double> term_share, std::span<const double> edf_reduction,
                        const NoiseFitOptions& options, const DetrendFactors* detrend,
                        std::span<const SpectralLine> lines) {
  // 1. The points, the known Allan variance (output rounding, spectral
  // lines, their variance as the short taus show it) and the sensor
  // bandwidth they show.
  detail::Points p = detail::gather_points(tau_s, adev_deg_h, edf, factors, segment_points,
                                           term_share, edf_reduction, options, detrend);
  const double known_white = options.known_white_deg_h_sqrt_hz;
  add_known_allan_variance(p, known_white, lines);
  detail::BandwidthSearch bandwidth = find_bandwidth_and_line_scale(p, options);
  // 2. Every admissible subset, best first; the best is the chosen model.
  std::vector<detail::SubsetFit> fits = detail::fit_candidates(p, options);
  recheck_bandwidth(p, bandwidth, fits, options);
  const LeftOut left_out = leave_out_unfollowed_first_taus(p, bandwidth, fits, options);
  if (fits.empty()) return degenerate(p);
  // 3-6. The evidence and the intervals; then the ramp and the
  // Gauss-Markov rules.
  NoiseFitResult r = conclude(p, fits, bandwidth, known_white, lines, options);
  Message trimmed_why;
  if (left_out.count > 0) {
    trimmed_why = Message(Text::fit_first_taus_left_out, left_out.count, left_out.first_tau_s,
                          left_out.last_tau_s, p.tau.front());
  }
  auto mark = [&](NoiseFitResult& result) {
    result.first_taus_left_out = left_out.count;
    result.first_taus_left_out_why = trimmed_why;
    result.left_out_below_tau_s =
        left_out.count > 0 ? std::sqrt(left_out.last_tau_s * p.tau.front()) : 0.0;
  };
  mark(r);
  const Message ramp = set_aside_unsupported_ramp(fits, r, options);
  if (!ramp.empty()) {
    r = conclude(p, fits, bandwidth, known_white, lines, options);
    mark(r);
    r.ramp_set_aside = ramp;
  }
  if (Message why = set_aside_unresolved_gauss_markov(p, fits, r, options); !why.empty()) {
    r = conclude(p, fits, bandwidth, known_white, lines, options);
    mark(r);
    r.ramp_set_aside = ramp;
    r.gauss_markov_set_aside = why;
  }
  if (left_out.count == 0 && options.span_filter_shape) {
    r.shape_free_taus_left_out =
        widen_over_filter_shape(p, bandwidth, known_white, lines, options, r);
  }
  r.filter_memory_end_tau_s = r.left_out_below_tau_s;
  if (const double tau0 = p.sample_interval_s(); r.bandwidth.resolved && tau0 > 0.0) {
    r.filter_memory_end_tau_s = std::max(r.filter_memory_end_tau_s,
                                         memory_reach_samples(r.bandwidth.bandwidth, tau0) * tau0);
  }
  r.message = fit_sentence(r);
  return r;
}

}  // namespace

std::string_view to_string(TermStatus status) {
  switch (status) {
    case TermStatus::resolved:
      return "resolved";
    case TermStatus::upper_bound:
      return "upper_bound";
    case TermStatus::absent:
      return "absent";
  }
  return "?";
}

std::string_view to_string(FitStatus status) {
  switch (status) {
    case FitStatus::converged:
      return "converged";
    case FitStatus::iteration_limit:
      return "iteration_limit";
    case FitStatus::degenerate:
      return "degenerate";
  }
  return "?";
}

std::string fit_sentence(const NoiseFitResult& r, Language language) {
  std::string sentence = r.outcome.text(language);
  for (const Message* why :
       {&r.first_taus_left_out_why, &r.ramp_set_aside, &r.gauss_markov_set_aside}) {
    if (!why->empty()) sentence += "; " + why->text(language);
  }
  return sentence;
}

const ParameterEstimate& NoiseFitResult::estimate(const NoiseParameter& parameter) const {
  return const_cast<NoiseFitResult&>(*this).estimate(parameter);
}

ParameterEstimate& NoiseFitResult::estimate(const NoiseParameter& parameter) {
  const auto member = parameter.value;
  if (member == &NoiseModel::N) return N;
  if (member == &NoiseModel::B) return B;
  if (member == &NoiseModel::K) return K;
  if (member == &NoiseModel::R) return R;
  if (member == &NoiseModel::Q) return Q;
  if (member == &NoiseModel::gm_sigma) return gm_sigma;
  return gm_tc;
}

double fitted_allan_variance(const NoiseFitResult& fit, NoiseTerm term, double tau_s) {
  const double v = allan_variance(fit.model, term, tau_s);
  if (!fit.bandwidth.resolved) return v;
  const BandwidthEstimate& b = fit.bandwidth;
  if (term == NoiseTerm::white)
    return v * white_allan_factor(b.bandwidth, tau_s, b.sample_interval_s);
  if (term == NoiseTerm::flicker) {
    return v * flicker_allan_factor(b.bandwidth, tau_s, b.sample_interval_s);
  }
  return v;
}

double lines_allan_variance(const NoiseFitResult& fit, double tau_s) {
  double sum = 0.0;
  for (const SpectralLine& line : fit.lines) {
    if (line.removed_from_record) continue;
    sum += line_allan_variance(line, tau_s, fit.bandwidth.sample_interval_s);
  }
  return sum;
}

double fitted_allan_variance(const NoiseFitResult& fit, double tau_s) {
  double sum = lines_allan_variance(fit, tau_s) +
               fit.known_white_deg_h_sqrt_hz * fit.known_white_deg_h_sqrt_hz / tau_s;
  for (NoiseTerm t : kNoiseTerms) sum += fitted_allan_variance(fit, t, tau_s);
  return sum;
}

double slope_standard_deviation(const NoiseModel& model, double span_s) {
  const double t = span_s;
  double variance = 12.0 * model.N * model.N / (t * t * t) +
                    9.0 * model.B * model.B / (std::numbers::pi * t * t) +
                    1.2 * model.K * model.K / t;
  if (model.gm_sigma > 0.0 && model.gm_tc > 0.0) {
    // int_0^1 exp(-l x) r(x) dx with r(x) = 1/12 - x/4 + x^3/6, from the
    // moments e_n = int_0^1 x^n exp(-l x) dx: a series for small l, the
    // recurrence e_n = (n e_(n-1) - exp(-l)) / l otherwise.
    const double l = t / model.gm_tc;
    std::array<double, 4> e{};
    if (l < 1.0) {
      for (int n = 0; n < 4; ++n) {
        double term = 1.0, sum = 0.0;  // (-l)^k / k!
        for (int k = 0; k < 30; ++k) {
          sum += term / (n + k + 1);
          term *= -l / (k + 1);
        }
        e[static_cast<std::size_t>(n)] = sum;
      }
    } else {
      const double tail = std::exp(-l);
      e[0] = -std::expm1(-l) / l;
      for (int n = 1; n < 4; ++n) {
        e[static_cast<std::size_t>(n)] = (n * e[static_cast<std::size_t>(n - 1)] - tail) / l;
      }
    }
    const double integral = e[0] / 12.0 - e[1] / 4.0 + e[3] / 6.0;
    variance += 288.0 * model.gm_sigma * model.gm_sigma / (t * t) * std::max(0.0, integral);
  }
  return std::sqrt(variance);
}

double DetrendFactors::factor(NoiseTerm term, std::size_t index, double tc_s) const {
  if (term != NoiseTerm::gauss_markov) return linear[static_cast<std::size_t>(term)][index];
  if (gm_tc_s.empty()) return 1.0;
  if (tc_s <= gm_tc_s.front()) return gm.front()[index];
  if (tc_s >= gm_tc_s.back()) return gm.back()[index];
  const auto it = std::upper_bound(gm_tc_s.begin(), gm_tc_s.end(), tc_s);
  const std::size_t k = static_cast<std::size_t>(it - gm_tc_s.begin());
  const double w = std::log(tc_s / gm_tc_s[k - 1]) / std::log(gm_tc_s[k] / gm_tc_s[k - 1]);
  return (1.0 - w) * gm[k - 1][index] + w * gm[k][index];
}

NoiseFitResult fit_noise_model(std::span<const double> tau_s, std::span<const double> adev_deg_h,
                               std::span<const double> edf, const NoiseFitOptions& options,
                               const DetrendFactors* detrend) {
  return fit_impl(tau_s, adev_deg_h, edf, {}, {}, {}, {}, options, detrend, {});
}

NoiseFitResult fit_noise_model(const stats::AllanResult& allan, const NoiseFitOptions& options,
                               const DetrendFactors* detrend, std::span<const SpectralLine> lines) {
  if (allan.kind != stats::AllanKind::oadev || allan.m.size() != allan.dev.size()) {
    throw UsageError("noise-model fit: needs an overlapping Allan deviation (oadev) result");
  }
  // An AllanResult made before segment_points existed is one stretch.
  const std::vector<std::int64_t> segments = allan.segment_points.empty()
                                                 ? std::vector<std::int64_t>{allan.phase_points}
                                                 : allan.segment_points;
  // What the terms' own spread divided each edf by (none where no check ran).
  std::vector<double> reduction = allan.edf_reduction;
  if (!reduction.empty()) reduction.resize(allan.dev.size(), 1.0);
  // Without intervals the edf come from the models alone (white noise's
  // stand in until the first model is fitted).
  std::vector<double> edf = allan.edf;
  edf.resize(allan.dev.size(), kNaN);
  for (std::size_t i = 0; i < edf.size(); ++i) {
    if (!std::isfinite(edf[i])) {
      edf[i] = stats::pooled_edf(0, allan.m[i], segments) *
               (allan.term_share.empty() ? 1.0 : allan.term_share[i]) /
               (reduction.empty() ? 1.0 : reduction[i]);
    }
  }
  return fit_impl(allan.tau_s, allan.dev, edf, allan.m, segments, allan.term_share, reduction,
                  options, detrend, lines);
}

}  // namespace foglab::model
