#include "foglab/model/analysis.h"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <future>
#include <limits>
#include <span>
#include <thread>
#include <utility>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/core/numeric.h"
#include "foglab/model/psd_allan.h"
#include "foglab/model/spectral_lines.h"

namespace foglab::model {
namespace {

// The fewest samples analyze() takes, in a row where the record has gaps.
constexpr std::size_t kMinAnalysisSamples = 64;

// Least-squares slope of ln y against ln x.
double log_slope(std::span<const double> x, std::span<const double> y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!(x[i] > 0) || !(y[i] > 0)) continue;
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
    ++n;
  }
  if (n < 2) return kNaN;
  const double den = n * sxx - sx * sx;
  return den > 0 ? (n * sxy - sx * sy) / den : kNaN;
}

// The points of `all` the reported grid keeps: at least grid.min_clusters
// clusters, floor((N - 1)/m) with N angle points (tau_grid.h); an explicit
// list is kept whole.
stats::AllanResult reported_part(const stats::AllanResult& all, const stats::TauGrid& grid) {
  if (grid.kind == stats::TauGridKind::list) return all;
  stats::AllanResult r = all;
  std::size_t keep = 0;
  while (keep < all.m.size() && (all.phase_points - 1) / all.m[keep] >= grid.min_clusters) ++keep;
  auto cut = [keep](auto& v) {
    if (v.size() > keep) v.resize(keep);
  };
  cut(r.m);
  cut(r.tau_s);
  cut(r.dev);
  cut(r.n);
  cut(r.alpha);
  cut(r.alpha_method);
  cut(r.edf);
  cut(r.edf_reduction);
  cut(r.ci68_low);
  cut(r.ci68_high);
  cut(r.ci95_low);
  cut(r.ci95_high);
  cut(r.term_share);
  cut(r.gap_spanning_terms);
  return r;
}

// The OADEV the noise fit uses: the octave grid whatever grid is reported,
// extended to the long taus the lab's ten-cluster rule leaves out (down to
// `fit_min_clusters`): their few degrees of freedom are weighted as such, and
// they show where a random walk turns into a Gauss-Markov hump. The fit
// weighs its points as independent, and its intervals and model choice were
// validated on octave spacing (docs/validation.md): neighbouring taus of a
// denser grid share most of their data and would count it several times
// over, and a list of a few taus cannot hold the model.
stats::AllanOptions fit_allan_options(const AnalysisOptions& options, bool confidence) {
  stats::AllanOptions allan;
  allan.kind = stats::AllanKind::oadev;
  allan.grid.kind = stats::TauGridKind::octave;
  allan.grid.min_clusters = std::min(options.grid.min_clusters, options.fit_min_clusters);
  allan.confidence = confidence;
  allan.term_spread_check = true;
  allan.max_missing_share = options.max_missing_share;
  allan.unbridged_gaps = options.unbridged_gaps;
  return allan;
}

// Whether the reported OADEV is a part of the fit's (the octave grid).
bool reported_within_fit(const AnalysisOptions& options) {
  return options.grid.kind == stats::TauGridKind::octave;
}

// The reported OADEV with intervals when its grid is not the fit's, from the
// residual (not consumed); empty when it is.
stats::AllanResult other_grid_allan(std::span<const double> residual, double fs,
                                    const AnalysisOptions& options, std::span<const Gap> gaps) {
  if (reported_within_fit(options)) return {};
  stats::AllanOptions allan;
  allan.kind = stats::AllanKind::oadev;
  allan.grid = options.grid;
  allan.confidence = true;
  allan.term_spread_check = true;
  allan.max_missing_share = options.max_missing_share;
  allan.unbridged_gaps = options.unbridged_gaps;
  return stats::allan_deviation(residual, fs, InputKind::rate, allan, gaps);
}

// other_grid_allan() of the final residual `rate` of a temperature fit,
// less the sinusoids taken out of the record (remove_sinusoids(); `rate`
// is consumed): the statistics' own residual had them taken out already,
// and nothing else reads `rate`, so they are taken out only when that OADEV
// is made.
stats::AllanResult other_grid_allan_less_lines(std::vector<double>& rate, double fs,
                                               const AnalysisOptions& options,
                                               std::span<const Gap> gaps,
                                               std::span<const SpectralLine> lines) {
  if (reported_within_fit(options)) return {};
  remove_sinusoids(rate, fs, gaps, lines);
  return other_grid_allan(rate, fs, options, gaps);
}

struct Statistics {
  stats::PsdResult psd, smoothed;
  stats::AllanResult allan;
  NoiseFitResult noise;
};

// Welch PSD of the residual and its log-smoothed form.
void add_psd(Statistics& s, std::span<const double> residual, double fs,
             const AnalysisOptions& options, std::span<const Gap> gaps) {
  stats::WelchOptions welch;
  welch.segment_length = options.psd_segment;
  s.psd = stats::welch_psd(residual, fs, welch, gaps);
  s.smoothed = stats::log_smooth(s.psd, options.psd_bins_per_decade);
}

// The OADEV with intervals at all the fit's taus of a residual (consumed: it
// becomes the angle record).
stats::AllanResult residual_allan(std::vector<double>& residual, double fs,
                                  const AnalysisOptions& options, std::span<const Gap> gaps) {
  return stats::allan_deviation_in_place(residual, fs, InputKind::rate,
                                         fit_allan_options(options, true), gaps);
}

// The reported OADEV: the part of the fit's OADEV `all` on the octave grid,
// else `other` (other_grid_allan()); the noise model needs 3 points of it.
void add_reported_allan(Statistics& s, const stats::AllanResult& all, stats::AllanResult other,
                        double fs, const AnalysisOptions& options) {
  s.allan = reported_within_fit(options) ? reported_part(all, options.grid) : std::move(other);
  if (s.allan.tau_s.size() < 3) {
    throw DataError(fmt::format(
        "the record ({} samples at {} Hz) gives only {} Allan-deviation point(s) with at least "
        "{} clusters; the noise model needs 3 or more (a few hundred samples)",
        all.phase_points, fs, s.allan.tau_s.size(), options.grid.min_clusters));
  }
}

// A deviation of 0 is no noise at that tau: the fit (log deviations) cannot
// take it, and it is a property of the data, not of the options.
void require_noise(const stats::AllanResult& all) {
  for (std::size_t k = 0; k < all.tau_s.size(); ++k) {
    if (!(all.dev[k] > 0.0)) {
      throw DataError(fmt::format(
          "the Allan deviation is 0 at tau {:g} s: the record (less its temperature part) "
          "repeats exactly over that time, so there is no noise to model",
          all.tau_s[k]));
    }
  }
}

// The noise model of a residual from its OADEV `all`. `record` and `degree`
// (> 0) give the polynomial in temperature removed from it: the fit then
// allows for what removing it did to each term (detrend_factors).
NoiseFitResult residual_noise_model(const stats::AllanResult& all, const AnalysisOptions& options,
                                    const TemperatureRecord* record, int degree,
                                    std::span<const SpectralLine> lines) {
  require_noise(all);
  if (record && degree > 0) {
    const DetrendFactors factors = detrend_factors(*record, degree, all.tau_s);
    return fit_noise_model(all, options.noise_fit, &factors, lines);
  }
  return fit_noise_model(all, options.noise_fit, nullptr, lines);
}

// The options with the record's least-squares slope against time and its
// span [s] (the gaps' missing samples counted in the time), which the fit
// checks a rate ramp against (NoiseFitOptions::record_slope_deg_h_s). Only
// for a residual from which nothing but the mean was removed (`degree` 0,
// or no temperature): a polynomial in a moving temperature takes trends.
AnalysisOptions with_record_trend(const AnalysisOptions& options, std::span<const double> residual,
                                  double fs, std::span<const Gap> gaps, int degree) {
  AnalysisOptions o = options;
  if (degree > 0 || residual.size() < 3) return o;
  auto time_s = [&](auto&& visit) {  // visit(t, y) for every sample
    std::int64_t missing = 0;
    std::size_t g = 0;
    for (std::size_t i = 0; i < residual.size(); ++i) {
      while (g < gaps.size() && gaps[g].before_sample <= static_cast<std::int64_t>(i)) {
        missing += gaps[g++].missing_samples;
      }
      visit(static_cast<double>(static_cast<std::int64_t>(i) + missing) / fs, residual[i]);
    }
  };
  double st = 0.0, sy = 0.0;
  time_s([&](double t, double y) { st += t, sy += y; });
  const double n = static_cast<double>(residual.size());
  const double mt = st / n, my = sy / n;
  double stt = 0.0, sty = 0.0;
  time_s([&](double t, double y) { stt += (t - mt) * (t - mt), sty += (t - mt) * (y - my); });
  o.noise_fit.record_slope_deg_h_s = sty / stt;
  o.noise_fit.record_span_s =
      static_cast<double>(static_cast<std::int64_t>(residual.size()) + missing_samples(gaps)) / fs;
  return o;
}

// PSD, OADEV and the noise fit of the residual (consumed: it becomes the
// angle record), one after the other.
Statistics statistics(std::vector<double>& residual, double fs, const AnalysisOptions& given,
                      std::span<const Gap> gaps, const TemperatureRecord* record, int degree) {
  const AnalysisOptions options = with_record_trend(given, residual, fs, gaps, record ? degree : 0);
  Statistics s;
  add_psd(s, residual, fs, options, gaps);
  const std::vector<SpectralLine> lines = find_spectral_lines(residual, fs, s.psd, gaps);
  remove_sinusoids(residual, fs, gaps, lines);  // the PSD keeps them
  stats::AllanResult other = other_grid_allan(residual, fs, options, gaps);
  const stats::AllanResult all = residual_allan(residual, fs, options, gaps);
  add_reported_allan(s, all, std::move(other), fs, options);
  s.noise = residual_noise_model(all, options, record, degree, lines);
  return s;
}

// The OADEV `all` as the quick look sees it: deviations only (the fit then
// takes each point's edf from its candidate models).
stats::AllanResult without_intervals(stats::AllanResult all) {
  all.edf.assign(all.edf.size(), kNaN);
  return all;
}

// The systematic part with the degree chosen by the criterion, and the
// statistics of its residual; `rate` is consumed (it ends as the residual).
// The degree needs the noise model, the noise model a residual: the residual
// of the highest degree (the cubic), in a second array (the record stays),
// gives its PSD (whose spectral lines every fit takes as known, or that
// are taken out of the record first: remove_sinusoids()) and its OADEV with
// intervals, and from its deviations alone a quick first noise model for
// the degree criterion. Whenever the criterion keeps the cubic,
// that PSD and OADEV are the final ones and its full noise fit the final model,
// so that fit runs on a second thread alongside the quick one. Otherwise the
// second array takes the final residual for its OADEV, and the noise fit runs
// alongside the Welch PSD. The results do not depend on the threads.
Statistics auto_degree_statistics(SystematicFit& fit, const TemperatureRecord& record,
                                  std::vector<double>& rate, std::span<const double> temperature,
                                  double fs, const AnalysisOptions& options,
                                  std::span<const Gap> gaps) {
  const int cubic_degree = fit.degree;
  std::vector<double> residual = temperature_fit_residual(fit, rate, temperature);
  // The cubic residual's PSD, before its OADEV consumes it: the spectral
  // lines the noise fits need, and the final PSD when the cubic stays.
  Statistics s;
  add_psd(s, residual, fs, options, gaps);
  const std::vector<SpectralLine> lines = find_spectral_lines(residual, fs, s.psd, gaps);
  remove_sinusoids(residual, fs, gaps, lines);  // the PSD keeps them
  const stats::AllanResult cubic_allan = residual_allan(residual, fs, options, gaps);
  if (cubic_allan.tau_s.size() < 3) {
    throw DataError(fmt::format(
        "the record ({} samples at {} Hz) gives only {} Allan-deviation point(s); the noise "
        "model needs 3 or more (a few hundred samples)",
        rate.size(), fs, cubic_allan.tau_s.size()));
  }
  require_noise(cubic_allan);
  const DetrendFactors cubic_factors = detrend_factors(record, cubic_degree, cubic_allan.tau_s);
  std::future<NoiseFitResult> cubic_noise = std::async(std::launch::async, [&] {
    return fit_noise_model(cubic_allan, options.noise_fit, &cubic_factors, lines);
  });
  NoiseFitOptions look_options = options.noise_fit;
  look_options.span_filter_shape = false;  // its model alone is used
  const NoiseFitResult look =
      fit_noise_model(without_intervals(cubic_allan), look_options, &cubic_factors, lines);
  fit = choose_temperature_degree(fit, record, look.model, options.systematic);
  subtract_temperature_fit(fit, rate, temperature);
  // `rate` is the final residual now, whichever degree was kept: the
  // reported grid's OADEV, when it is not the fit's, is taken from it.

  if (fit.degree == cubic_degree) {
    residual = {};  // the second array is not needed any more (peak memory)
    add_reported_allan(s, cubic_allan, other_grid_allan_less_lines(rate, fs, options, gaps, lines),
                       fs, options);
    s.noise = cubic_noise.get();
    return s;
  }
  residual.assign(rate.begin(), rate.end());  // the capacity (n + 1) stays
  remove_sinusoids(residual, fs, gaps, lines);
  const stats::AllanResult all = residual_allan(residual, fs, options, gaps);
  residual = {};
  const AnalysisOptions final_options = with_record_trend(options, rate, fs, gaps, fit.degree);
  std::future<NoiseFitResult> noise = std::async(std::launch::async, [&] {
    return residual_noise_model(all, final_options, &record, fit.degree, lines);
  });
  add_psd(s, rate, fs, options, gaps);  // the final residual's, with its lines
  add_reported_allan(s, all, other_grid_allan_less_lines(rate, fs, options, gaps, lines), fs,
                     options);
  s.noise = noise.get();
  return s;
}

// How far a random drift can pass for a temperature law depends on the
// random bias: a Wiener process's wanders without limit, a Gauss-Markov
// process's stay within sigma. On a ramp run the two are often hard to tell
// apart (the polynomial takes the record's own trend with it), and a
// Wiener bias taken for a Gauss-Markov one made c1's interval several times
// too short (on the lab-2 variants, c1 10 standard errors from the key).
// So while the best Wiener candidate is within the interval window of the
// best candidate, each coefficient's standard error is the larger of the
// two models', and the criterion's verdict beside a forced degree (under
// `chosen`) the lower of the two models' degrees: a term stands out only if
// it does under both. The same holds for every candidate within the window
// (as the noise terms' intervals are unions over them): a flicker term left
// out beneath a Gauss-Markov hump is not resolvable, yet over the hours a
// slope is fitted across it carries as much variance as the hump's tail. On
// the lab's FOG2_5 (Tc 38-80 s, B = 1.7 deg/h) c1's errors had spread 1.46
// times its standard errors over 40 seeds, 8 of 40 outside the 95 %
// interval; with the near candidates 1.26 and 6 (bench/lab2_score.py
// --c1-spread; docs/validation.md). That rule takes the slopes only: the
// intercept's error counts the stationary terms alone (coefficient_
// covariance()), which a Wiener model and a slow Gauss-Markov one that
// mimics it split differently (a near N+B+GM beside a chosen N+B+K had made
// it 170 times larger on a 28 h record).
void finish_temperature_errors(SystematicFit& fit, const TemperatureRecord& record,
                               const NoiseFitResult& noise, const NoiseModel& chosen,
                               const AnalysisOptions& options) {
  set_criterion_verdict(fit, record, chosen, options.systematic);
  auto within_window = [&](const CandidateModel& c) {
    return !noise.candidates.empty() &&
           c.criterion - noise.candidates.front().criterion <= options.noise_fit.interval_window;
  };
  // The best Wiener candidate's errors, all of them, beside a chosen model
  // without a random walk (below); the near candidates' loop leaves it out.
  const bool wiener_rule = noise.random_bias_process != RandomBiasProcess::wiener &&
                           noise.has_wiener_candidate && within_window(noise.best_wiener);
  for (std::size_t k = 1; k < noise.candidates.size(); ++k) {
    const CandidateModel& near = noise.candidates[k];
    if (!within_window(near)) break;  // best first
    if (wiener_rule && near.terms == noise.best_wiener.terms) continue;
    SystematicFit other = fit;
    set_standard_errors(other, record, near.model);
    for (std::size_t j = 1; j < fit.standard_errors.size(); ++j) {
      fit.standard_errors[j] = std::fmax(fit.standard_errors[j], other.standard_errors[j]);
    }
  }
  if (!wiener_rule) return;
  SystematicFit wiener = fit;
  set_standard_errors(wiener, record, noise.best_wiener.model);
  set_criterion_verdict(wiener, record, noise.best_wiener.model, options.systematic);
  for (std::size_t j = 0; j < fit.standard_errors.size(); ++j) {
    fit.standard_errors[j] = std::fmax(fit.standard_errors[j], wiener.standard_errors[j]);
  }
  if (wiener.criterion_degree >= 0 && wiener.criterion_degree < fit.criterion_degree) {
    fit.criterion = wiener.criterion;
    fit.criterion_degree = wiener.criterion_degree;
  }
}

RandomBiasEvidence evidence_of(const Statistics& s) {
  RandomBiasEvidence e;
  const NoiseFitResult& n = s.noise;
  auto dev = [](bool have, const CandidateModel& c) { return have ? c.deviance : kNaN; };
  auto crit = [](bool have, const CandidateModel& c) { return have ? c.criterion : kNaN; };
  e.deviance_none = dev(n.has_candidate_without_random_bias, n.best_without_random_bias);
  e.criterion_none = crit(n.has_candidate_without_random_bias, n.best_without_random_bias);
  e.deviance_wiener = dev(n.has_wiener_candidate, n.best_wiener);
  e.criterion_wiener = crit(n.has_wiener_candidate, n.best_wiener);
  e.deviance_gauss_markov = dev(n.has_gauss_markov_candidate, n.best_gauss_markov);
  e.criterion_gauss_markov = crit(n.has_gauss_markov_candidate, n.best_gauss_markov);

  const std::size_t m = s.allan.tau_s.size();
  const std::size_t first = m >= 3 ? m - 3 : 0;
  e.adev_end_slope =
      log_slope(std::span(s.allan.tau_s).subspan(first), std::span(s.allan.dev).subspan(first));
  // The lowest decade of the raw PSD.
  const auto& f = s.psd.frequency_hz;
  std::size_t end = 0;
  while (end < f.size() && f[end] <= 10.0 * f.front()) ++end;
  e.psd_low_frequency_slope = log_slope(std::span(f).first(end), std::span(s.psd.psd).first(end));

  // "-" where no candidate of that kind was fitted (a record of a few
  // hundred samples can leave only one)
  auto criterion = [](double c) { return std::isfinite(c) ? fmt::format("{:.1f}", c) : "-"; };
  const Message fits(Text::ev_criteria, criterion(e.criterion_none), criterion(e.criterion_wiener),
                     criterion(e.criterion_gauss_markov));
  switch (n.random_bias_process) {
    case RandomBiasProcess::wiener:
      e.summary = Message(Text::ev_wiener, e.adev_end_slope,
                          n.gauss_markov_set_aside.empty()
                              ? Message(Text::ev_rw_best)
                              : Message(Text::ev_rw_explains, n.gauss_markov_set_aside),
                          fits);
      break;
    case RandomBiasProcess::gauss_markov:
      e.summary = Message(Text::ev_gauss_markov, n.model.gm_tc, e.adev_end_slope,
                          e.psd_low_frequency_slope, fits);
      break;
    case RandomBiasProcess::none:
      e.summary = Message(Text::ev_none, e.adev_end_slope, fits);
      break;
  }
  return e;
}

// What the analysis did with the gaps of a record of `samples` present
// samples, which they cut into `stretches`.
Message gap_note(std::size_t samples, std::span<const Gap> gaps, std::span<const Stretch> stretches,
                 double fs) {
  const std::int64_t missing = missing_samples(gaps);
  const std::int64_t longest = longest_stretch(stretches);
  return Message(Text::note_gaps, gaps.size(), missing, static_cast<double>(missing) / fs,
                 100.0 * static_cast<double>(missing) /
                     static_cast<double>(missing + static_cast<std::int64_t>(samples)),
                 stretches.size(), static_cast<double>(longest) / fs);
}

// What was done with the bias steps found: the note's last part.
Message steps_treatment(const BiasSteps& steps) {
  using AsNoise = BiasSteps::AsNoise;
  switch (steps.left_as_noise_because) {
    case AsNoise::beyond_limit:
      return Message(Text::note_steps_as_noise,
                     Message(Text::note_steps_beyond_limit, steps.indices.size()));
    case AsNoise::wander:
      return Message(Text::note_steps_as_noise, Message(Text::note_steps_wander));
    case AsNoise::two_levels:
      return Message(Text::note_steps_as_noise, Message(Text::note_steps_two_levels));
    case AsNoise::none:
      break;
  }
  return Message(steps.removed ? Text::note_steps_levelled : Text::note_steps_kept);
}

// A turn of the temperature: where its rate of change changes sign.
struct TemperatureTurn {
  std::int64_t sample = 0;  ///< about where
  int rate_change = 0;      ///< the sign of the change of dT/dt there
};

// The temperature's turns: its means over 256 blocks, the slope of those over +-2 blocks, and
// a turn where that slope changes sign between two ramps, each of at least 4 blocks whose
// slope is beyond a quarter of the largest and beyond 8 times its noise (the block means'
// second differences: a thermostat's jitter or hunting has no ramps). Nothing when the block
// means span less than `min_span_c`.
std::vector<TemperatureTurn> temperature_turns(std::span<const double> temperature_c,
                                               double min_span_c) {
  constexpr std::size_t kBlocks = 256;
  constexpr std::size_t kShortestRamp = 4;
  std::vector<TemperatureTurn> turns;
  const std::size_t n = temperature_c.size();
  if (n < 16 * kBlocks) return turns;
  std::vector<double> means(kBlocks, 0.0);
  for (std::size_t b = 0; b < kBlocks; ++b) {
    const std::size_t first = b * n / kBlocks;
    const std::size_t end = (b + 1) * n / kBlocks;
    for (std::size_t k = first; k < end; ++k) means[b] += temperature_c[k];
    means[b] /= static_cast<double>(end - first);
  }
  if (const auto [lowest, highest] = std::ranges::minmax(means); highest - lowest < min_span_c) {
    return turns;
  }
  // the block means' noise sd, robustly from their second differences (var 6 sigma^2)
  std::vector<double> curvature;
  for (std::size_t b = 1; b + 1 < kBlocks; ++b) {
    curvature.push_back(std::abs(means[b + 1] - 2.0 * means[b] + means[b - 1]));
  }
  const auto middle = curvature.begin() + static_cast<std::ptrdiff_t>(curvature.size() / 2);
  std::nth_element(curvature.begin(), middle, curvature.end());
  const double noise = 1.4826 * *middle / std::sqrt(6.0);
  std::vector<double> slope(kBlocks, 0.0);
  double largest = 0.0;
  for (std::size_t b = 2; b + 2 < kBlocks; ++b) {
    slope[b] = means[b + 2] - means[b - 2];
    largest = std::max(largest, std::abs(slope[b]));
  }
  const double least = std::max(0.25 * largest, 8.0 * std::sqrt(2.0) * noise);
  if (!(largest > least)) return turns;
  // ramps: runs of one sign among the blocks beyond `least` (others between them ignored)
  struct Ramp {
    int sign;
    std::size_t count, first, last;
  };
  std::vector<Ramp> ramps;
  for (std::size_t b = 2; b + 2 < kBlocks; ++b) {
    if (std::abs(slope[b]) < least) continue;
    const int s = slope[b] > 0.0 ? 1 : -1;
    if (ramps.empty() || ramps.back().sign != s) ramps.push_back({s, 0, b, b});
    ++ramps.back().count;
    ramps.back().last = b;
  }
  std::erase_if(ramps, [](const Ramp& r) { return r.count < kShortestRamp; });
  for (std::size_t i = 1; i < ramps.size(); ++i) {
    if (ramps[i].sign == ramps[i - 1].sign) continue;
    const std::size_t between = (ramps[i - 1].last + ramps[i].first + 1) / 2;
    turns.push_back({static_cast<std::int64_t>(between * n / kBlocks),
                     ramps[i].sign - ramps[i - 1].sign > 0 ? 1 : -1});
  }
  return turns;
}

// Whether two or more steps each lie within 3 blocks of 256 of a temperature turn, and each
// against that turn's change of dT/dt the same way (BiasSteps::at_temperature_turns).
bool steps_at_turns(const BiasSteps& steps, const std::vector<TemperatureTurn>& turns,
                    std::size_t samples) {
  if (steps.indices.size() < 2 || turns.empty()) return false;
  const auto tolerance = static_cast<std::int64_t>(3 * samples / 256);
  int way = 0;
  for (std::size_t i = 0; i < steps.indices.size(); ++i) {
    const auto nearest = std::ranges::min_element(
        turns, {}, [&](const TemperatureTurn& t) { return std::abs(t.sample - steps.indices[i]); });
    if (std::abs(nearest->sample - steps.indices[i]) > tolerance) return false;
    const int w = (steps.sizes_deg_h[i] > 0.0 ? 1 : -1) * nearest->rate_change;
    if (way != 0 && w != way) return false;
    way = w;
  }
  return true;
}

// N rests on the white noise's sample variance, whose relative variance is
// (2 + g) / n for n samples of excess kurtosis g; the fit's interval counts
// the Gaussian 2 / n. Under heavy-tailed noise (spikes.h) the rest, g / n,
// is added in quadrature: N's relative scatter grows by sqrt(g / n) / 2.
// (Student's t with 3 to 5 degrees of freedom: with the Gaussian interval
// N's held the truth in 2-6 of 10 records; its error follows the sample
// variance's.)
void widen_n_for_heavy_tail(AnalysisResult& r) {
  ParameterEstimate& n = r.noise.N;
  if (!r.spikes.heavy_tailed || n.status != TermStatus::resolved || !(r.samples > 0)) return;
  const double extra =
      kZ95 * n.value * 0.5 * std::sqrt(r.spikes.excess_kurtosis / static_cast<double>(r.samples));
  n.ci95_low = std::max(0.0, n.value - std::hypot(n.value - n.ci95_low, extra));
  n.ci95_high = n.value + std::hypot(n.ci95_high - n.value, extra);
}

}  // namespace

AnalysisResult analyze(std::vector<double>& rate_deg_h, std::span<const double> temperature_c,
                       double sample_rate_hz, const AnalysisOptions& options,
                       std::span<const Gap> gaps) {
  if (!(sample_rate_hz > 0) || !std::isfinite(sample_rate_hz)) {
    throw UsageError(fmt::format("sample rate {} Hz must be positive", sample_rate_hz));
  }
  if (!temperature_c.empty() && temperature_c.size() != rate_deg_h.size()) {
    throw DataError(fmt::format(
        "the rate has {} samples but the temperature {}; they must pair sample by sample",
        rate_deg_h.size(), temperature_c.size()));
  }
  if (rate_deg_h.size() < kMinAnalysisSamples) {
    throw DataError(fmt::format(
        "the record has {} samples; the analysis needs at least {} (a few hundred for a "
        "meaningful noise model)",
        rate_deg_h.size(), kMinAnalysisSamples));
  }
  require_varying(rate_deg_h);
  check_gaps(gaps, static_cast<std::int64_t>(rate_deg_h.size()), "analyze");
  const std::vector<Stretch> stretches =
      contiguous_stretches(static_cast<std::int64_t>(rate_deg_h.size()), gaps);
  if (const std::int64_t longest = longest_stretch(stretches);
      longest < static_cast<std::int64_t>(kMinAnalysisSamples)) {
    // Each statistic keeps to the stretches (conventions.md §9): a record
    // cut into short pieces (a sample lost every few) holds no long tau.
    throw DataError(fmt::format(
        "the gaps cut the record's {} samples into {} stretches, the longest {} samples; the "
        "analysis needs at least {} in a row",
        rate_deg_h.size(), stretches.size(), longest, kMinAnalysisSamples));
  }
  AnalysisResult r;
  r.gaps.assign(gaps.begin(), gaps.end());
  if (!gaps.empty()) {
    r.notes.push_back(gap_note(rate_deg_h.size(), gaps, stretches, sample_rate_hz));
  }
  std::vector<double> between_steps;  // a quantised temperature channel's temperature
  if (!temperature_c.empty()) {
    r.temperature_quantisation = find_temperature_quantisation(temperature_c, sample_rate_hz);
    if (const TemperatureQuantisation& t = r.temperature_quantisation; t.detected) {
      between_steps = reconstruct_quantised_temperature(temperature_c, t.lsb_c);
      temperature_c = between_steps;
      r.notes.emplace_back(Text::note_temperature_quantised, t.lsb_c, t.distinct_values, t.changes,
                           t.mean_hold_s);
    }
    // A channel in kelvin reads 200-400 for a test at -73 to +127 degC; no
    // gyro is tested above 200 degC. Said, not converted: the law's
    // coefficients about the mean temperature hold either way.
    constexpr double kHottestTestC = 200.0;
    if (const auto [lowest, highest] = std::ranges::minmax(temperature_c); lowest > kHottestTestC) {
      r.notes.emplace_back(Text::note_temperature_kelvin, lowest, highest);
    }
  }
  r.output_quantisation = find_output_quantisation(rate_deg_h, sample_rate_hz);
  const OutputQuantisation& word = r.output_quantisation;
  const double lsb = word.detected ? word.lsb_deg_h : 0.0;
  r.spikes = find_spikes(rate_deg_h, options.spikes, lsb);
  std::vector<TemperatureTurn> turns;  // of a thermal cycle
  {
    // The steps are looked for on top of the temperature law (a first
    // least-squares fit; the spikes are out, the steps are still in, and a
    // polynomial cannot follow a jump): a law with curvature would widen
    // the spread of D or pass for steps, and a step levelled out of a
    // temperature ramp takes part of the law with it.
    std::vector<double> law;  // none where it is a constant (the mean is taken out anyway)
    if (!temperature_c.empty()) {
      const SystematicFit first =
          fit_temperature(rate_deg_h, temperature_c, sample_rate_hz, options.systematic);
      if (!first.constant_fallback && first.degree > 0) law = temperature_law(first, temperature_c);
    }
    // and on top of a periodic disturbance, whose edges would pass for steps
    if (const std::vector<SpectralLine> periodic =
            find_periodic_disturbances(rate_deg_h, sample_rate_hz, gaps);
        !periodic.empty()) {
      if (law.empty()) law.assign(rate_deg_h.size(), 0.0);
      add_sinusoids(law, sample_rate_hz, gaps, periodic);
    }
    // Heavy-tailed noise keeps its outliers (spikes.h); the search for
    // steps pulls them in to where the Gaussian bulk ends.
    StepOptions step_options = options.steps;
    if (r.spikes.heavy_tailed) {
      step_options.outlier_clip_deg_h = kGaussianBulkEnd * r.spikes.robust_sd_deg_h;
    }
    r.steps = find_steps(rate_deg_h, step_options, word.detected && !word.noise_like ? lsb : 0.0,
                         gaps, law);
    // Jumps at the temperature's turns are the temperature's rate, not a random process:
    // levelled (in a cycle of ramps dT/dt is a square wave, and so is the bias it drives).
    if (!temperature_c.empty()) {
      turns = temperature_turns(temperature_c, options.systematic.min_span_c);
      r.steps.at_temperature_turns = steps_at_turns(r.steps, turns, rate_deg_h.size());
      // (all of them: not when more lie beyond the search's limit)
      if (r.steps.at_temperature_turns && r.steps.left_as_noise() &&
          r.steps.left_as_noise_because != BiasSteps::AsNoise::beyond_limit &&
          options.steps.remove) {
        level_steps(rate_deg_h, r.steps);
        r.steps.left_as_noise_because = BiasSteps::AsNoise::none;
        r.steps.removed = true;
      }
    }
  }
  if (!r.steps.indices.empty()) {
    std::vector<Message> list;
    for (std::size_t i = 0; i < r.steps.indices.size(); ++i) {
      list.emplace_back(Text::note_step_item, r.steps.sizes_deg_h[i],
                        elapsed_s(r.steps.indices[i], gaps, sample_rate_hz));
    }
    r.notes.emplace_back(Text::note_steps, r.steps.indices.size(), std::move(list),
                         options.steps.threshold, steps_treatment(r.steps));
    if (r.steps.at_temperature_turns) {
      r.notes.emplace_back(Text::note_steps_at_temperature_turns, r.steps.indices.size(),
                           turns.size());
    }
  }
  if (std::ranges::any_of(r.steps.across_gaps, &GapJump::significant)) {
    std::vector<Message> list;
    for (const GapJump& j : r.steps.across_gaps) {
      if (!j.significant) continue;
      list.emplace_back(Text::note_gap_jump_item, j.size_deg_h,
                        elapsed_s(j.before_sample, gaps, sample_rate_hz), j.significance);
    }
    const std::size_t count = list.size();
    r.notes.emplace_back(Text::note_gap_jumps, count, std::move(list), options.steps.threshold);
  }
  if (r.spikes.heavy_tailed) {
    r.notes.emplace_back(Text::note_heavy_tail, r.spikes.shoulder_count, r.spikes.shoulder_expected,
                         r.spikes.tail_index, r.spikes.threshold_deg_h, r.spikes.excess_kurtosis);
  }
  if (r.spikes.count > 0) {
    r.notes.emplace_back(Text::note_spikes, r.spikes.count, r.spikes.threshold_deg_h,
                         r.spikes.threshold_deg_h / r.spikes.robust_sd_deg_h,
                         r.spikes.removed ? Text::note_spikes_replaced : Text::note_spikes_kept);
  }
  // The output word's rounding, when noise-like (a step of at most two
  // sample-to-sample spreads, output_quantisation.h), is white noise of a
  // known level: the fit takes it as known, so that N is the sensor's own.
  AnalysisOptions with_known = options;  // as given, but for the fit's known white noise
  if (const OutputQuantisation& q = r.output_quantisation; q.detected && q.noise_like) {
    with_known.noise_fit.known_white_deg_h_sqrt_hz = q.white_level_deg_h_sqrt_hz;
  }
  // and for the gaps across which the bias jumps: no Allan term spans them
  for (const GapJump& j : r.steps.across_gaps) {
    if (j.significant) with_known.unbridged_gaps.push_back(j.before_sample);
  }
  // Before the statistics, which consume the record; the temperature law
  // is still in, and adds nothing measurable at these taus.
  r.allan_drift = stats::allan_drift(rate_deg_h, 1.0 / sample_rate_hz, gaps, options.drift);
  if (const stats::AllanDriftCalls c = r.allan_drift.calls(); !c.tau_s.empty()) {
    std::vector<Message> taus;
    for (const double tau : c.tau_s) taus.emplace_back(Text::one_of, tau);
    r.notes.emplace_back(Text::note_allan_drift, std::move(taus), r.allan_drift.blocks,
                         range_message(c.z_low, c.z_high), r.allan_drift.z_threshold,
                         range_message(c.ratio_low, c.ratio_high));
  }
  r.sample_rate_hz = sample_rate_hz;
  r.samples = static_cast<std::int64_t>(rate_deg_h.size());
  r.duration_s = static_cast<double>(r.samples + missing_samples(gaps)) / sample_rate_hz;

  std::optional<TemperatureRecord> record;
  std::optional<SystematicFit> fit;
  Statistics s;
  if (!temperature_c.empty()) {
    record.emplace(rate_deg_h, temperature_c, sample_rate_hz, options.systematic.blocks,
                   options.detrend_blocks);
    fit = fit_temperature(*record, options.systematic);
    if (fit->degree_chosen) {
      s = auto_degree_statistics(*fit, *record, rate_deg_h, temperature_c, sample_rate_hz,
                                 with_known, gaps);
    } else {
      subtract_temperature_fit(*fit, rate_deg_h, temperature_c);
      s = statistics(rate_deg_h, sample_rate_hz, with_known, gaps, &*record, fit->degree);
    }
  } else {
    r.notes.emplace_back(Text::note_no_temperature);
    s = statistics(rate_deg_h, sample_rate_hz, with_known, gaps, nullptr, 0);
  }
  if (fit) {
    // Standard errors with the noise model of the final residual. A random
    // walk the record cannot resolve is confounded with a temperature ramp
    // (the polynomial absorbs it), so it enters at its 95 % upper bound: the
    // errors are then conservative rather than several times too small.
    NoiseModel for_errors = s.noise.model;
    if (s.noise.K.status != TermStatus::resolved && std::isfinite(s.noise.K.upper_95) &&
        s.noise.random_bias_process != RandomBiasProcess::gauss_markov) {
      for_errors.K = s.noise.K.upper_95;
    }
    set_standard_errors(*fit, *record, for_errors);
    finish_temperature_errors(*fit, *record, s.noise, for_errors, options);
    r.notes.push_back(fit->note);
    r.systematic = std::move(fit);
  }
  if (const OutputQuantisation& q = r.output_quantisation;
      q.detected && q.noise_like && s.noise.N.status == TermStatus::resolved) {
    // The rounding's share is known to within its departure from q^2 / 12
    // (output_quantisation.h); N's interval takes it in.
    const double spread =
        q.white_variance_departure * std::pow(q.step_sd_deg_h, 2) / sample_rate_hz;
    s.noise.N.ci95_low = std::sqrt(std::max(0.0, std::pow(s.noise.N.ci95_low, 2) - spread));
    s.noise.N.ci95_high = std::sqrt(std::pow(s.noise.N.ci95_high, 2) + spread);
  }
  if (const OutputQuantisation& q = r.output_quantisation; q.detected) {
    const double n = s.noise.model.N;
    const Text how = q.noise_like ? Text::note_quantised_known : Text::note_quantised_distorting;
    if (n > 0.0) {
      r.notes.emplace_back(Text::note_quantised, q.lsb_deg_h, q.distinct_values, q.samples_examined,
                           q.white_level_deg_h_sqrt_hz,
                           100.0 * std::pow(q.white_level_deg_h_sqrt_hz / n, 2), how);
    } else {
      r.notes.emplace_back(Text::note_quantised_without_white, q.lsb_deg_h, q.distinct_values,
                           q.samples_examined, q.white_level_deg_h_sqrt_hz, how);
    }
  }
  r.evidence = evidence_of(s);
  r.psd = std::move(s.psd);
  r.psd_smoothed = std::move(s.smoothed);
  r.allan = std::move(s.allan);
  r.noise = std::move(s.noise);
  // The taus where clusters missing a few samples entered (stats/allan.h).
  const auto spans = [](std::int64_t terms) { return terms > 0; };
  if (const auto& spanning = r.allan.gap_spanning_terms; std::ranges::any_of(spanning, spans)) {
    const auto first =
        static_cast<std::size_t>(std::ranges::find_if(spanning, spans) - spanning.begin());
    r.notes.emplace_back(Text::note_gap_clusters, std::ranges::count_if(spanning, spans),
                         r.allan.tau_s[first], r.allan.tau_s.back(),
                         100.0 * options.max_missing_share);
  }
  // The taus whose edf the terms' own spread divided (stats/allan.h).
  if (const auto& reduction = r.allan.edf_reduction;
      std::ranges::any_of(reduction, [](double x) { return x > 1.0; })) {
    std::vector<Message> taus;
    double low = std::numeric_limits<double>::infinity(), high = 0.0;
    for (std::size_t k = 0; k < reduction.size(); ++k) {
      if (!(reduction[k] > 1.0)) continue;
      taus.emplace_back(Text::one_of, r.allan.tau_s[k]);
      low = std::min(low, reduction[k]), high = std::max(high, reduction[k]);
    }
    r.notes.emplace_back(Text::note_allan_terms_spread, std::move(taus), range_message(low, high));
  }

  r.adev_readings = read_adev(r.allan.tau_s, r.allan.dev, r.noise.filter_memory_end_tau_s);
  r.psd_readings = read_psd(r.psd_smoothed.frequency_hz, r.psd_smoothed.psd);
  r.bias_instability_deg_h = r.adev_readings.bias_instability_deg_h;
  r.bias_instability_tau_s = r.adev_readings.bias_instability_tau_s;
  r.bias_instability_at_edge = r.adev_readings.minimum_at_edge;
  r.bias_instability_from_tau_s = r.adev_readings.from_tau_s;
  if (Message note = minimum_inside_filter_note(r.adev_readings); !note.empty()) {
    r.notes.push_back(std::move(note));
  }
  if (r.bias_instability_at_edge) {
    r.notes.emplace_back(
        Text::note_minimum_at_edge,
        r.bias_instability_tau_s == r.allan.tau_s.back() ? Text::word_end : Text::word_start,
        r.bias_instability_tau_s);
  }
  widen_n_for_heavy_tail(r);
  r.arw_deg_sqrt_h = arw_deg_sqrt_h(r.noise.model.N);
  if (r.noise.status == FitStatus::degenerate) {
    r.notes.emplace_back(Text::note_fit_degenerate, r.noise.outcome);
    r.arw_deg_sqrt_h = kNaN;
  } else if (r.noise.N.status != TermStatus::resolved) {
    r.notes.emplace_back(Text::note_no_white);
    if (std::isfinite(r.noise.N.upper_95)) r.arw_deg_sqrt_h = arw_deg_sqrt_h(r.noise.N.upper_95);
  }
  if (!r.noise.ramp_set_aside.empty()) r.notes.emplace_back(Text::note_fit, r.noise.ramp_set_aside);
  if (!r.noise.first_taus_left_out_why.empty()) {
    r.notes.emplace_back(Text::note_fit, r.noise.first_taus_left_out_why);
  }
  if (r.noise.status == FitStatus::iteration_limit) {
    r.notes.emplace_back(Text::note_fit, r.noise.outcome);
  }
  r.verdict = classify(r.bias_instability_deg_h, r.arw_deg_sqrt_h);
  r.psd_allan = check_allan_against_psd(r.noise, r.allan, 1.0 / r.sample_rate_hz, r.duration_s);
  return r;
}

std::vector<std::exception_ptr> run_work_queue(std::size_t count,
                                               const std::function<void(std::size_t)>& job,
                                               unsigned workers, OnFailure on_failure) {
  std::vector<std::exception_ptr> errors(count);
  if (count == 0) return errors;
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  if (workers == 0) workers = cores;
  workers = static_cast<unsigned>(std::min<std::size_t>(workers, count));
  // Each worker's OpenMP teams get its share of the cores (at least one).
  const int team = static_cast<int>(std::max(1u, cores / workers));

  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  auto work = [&] {
    const int before = omp_get_max_threads();
    omp_set_num_threads(team);  // this thread's teams only
    for (std::size_t k = next++; k < count; k = next++) {
      if (failed && on_failure == OnFailure::stop) break;
      try {
        job(k);
      } catch (...) {
        errors[k] = std::current_exception();
        failed = true;
      }
    }
    omp_set_num_threads(before);  // the calling thread is one of the workers
  };
  std::vector<std::thread> threads;
  for (unsigned w = 1; w < workers; ++w) threads.emplace_back(work);
  work();
  for (std::thread& t : threads) t.join();
  return errors;
}

std::vector<AnalysisResult> analyze_records(std::size_t count,
                                            const std::function<RecordToAnalyse(std::size_t)>& load,
                                            const AnalysisOptions& options, unsigned workers,
                                            const std::function<void(std::size_t)>& done,
                                            const std::function<std::string(std::size_t)>& label) {
  std::vector<AnalysisResult> results(count);
  auto job = [&](std::size_t k) {
    try {
      RecordToAnalyse record = load(k);
      results[k] = analyze(record.rate_deg_h, record.temperature_c, record.sample_rate_hz, options,
                           record.gaps);
    } catch (const UsageError& e) {
      if (label) throw UsageError(label(k) + ": " + e.what());
      throw;
    } catch (const DataError& e) {
      if (label) throw DataError(label(k) + ": " + e.what());
      throw;
    }
    if (done) done(k);
  };
  for (const std::exception_ptr& e : run_work_queue(count, job, workers, OnFailure::stop)) {
    if (e) std::rethrow_exception(e);
  }
  return results;
}

}  // namespace foglab::model
