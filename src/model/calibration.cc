#include "foglab/model/calibration.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "foglab/core/error.h"
#include "foglab/core/numeric.h"
#include "foglab/core/output_model.h"
#include "foglab/model/noise_fit.h"
#include "foglab/stats/allan.h"

namespace foglab::model {
namespace {

constexpr std::int64_t kMinPlateauSamples = 10;
constexpr double kSameTemperatureC = 0.5;  // plateaus closer than this share a temperature
constexpr int kMaxNonlinearityDegree = 5;  // the automatic choice's highest

// Where each coefficient lives in the parameter vector:
// [S, s_1..s_ps, a_1..a_q, (A), u0, b_1..b_pb].
struct Layout {
  int ps = 0, q = 0, pb = 0;
  bool asymmetry = false;
  std::span<const double> known_s;  // S(T)'s polynomial when it is not fitted (ps = 0)
  int s(int k) const { return 1 + k; }
  int a(int k) const { return 1 + ps + k; }
  int A() const { return 1 + ps + q; }
  int u0() const { return 1 + ps + q + (asymmetry ? 1 : 0); }
  int b(int k) const { return u0() + 1 + k; }
  int size() const { return u0() + 1 + pb; }
};

struct Point {
  double w, dT;
};

// Eq. (10)'s terms as they lie in the parameter vector p.
OutputModelTerms terms_of(const Eigen::VectorXd& p, const Layout& l) {
  const double* v = p.data();
  return {
      p(0),
      l.ps > 0 ? std::span<const double>{v + l.s(0), static_cast<std::size_t>(l.ps)} : l.known_s,
      {v + l.a(0), static_cast<std::size_t>(l.q)},
      l.asymmetry ? p(l.A()) : 0.0,
      p(l.u0()),
      {v + l.b(0), static_cast<std::size_t>(l.pb)}};
}

// The model's derivatives with respect to p at one point.
Eigen::RowVectorXd model_gradient(const Eigen::VectorXd& p, const Layout& l, const Point& x) {
  const OutputModelTerms t = terms_of(p, l);
  const double relative = t.relative_scale_factor(x.dT);
  const double rate_part = (1.0 + t.nonlinearity_at(x.w)) * x.w;  // [1 + f(w)] w
  const double scale = p(0) * relative;
  Eigen::RowVectorXd g = Eigen::RowVectorXd::Zero(l.size());
  g(0) = relative * rate_part;
  double dTk = 1.0, wk = x.w;
  for (int k = 0; k < l.ps; ++k) {
    dTk *= x.dT;
    g(l.s(k)) = p(0) * dTk * rate_part;
  }
  for (int k = 0; k < l.q; ++k) {
    wk *= x.w;
    g(l.a(k)) = scale * wk;
  }
  if (l.asymmetry) g(l.A()) = 0.5 * scale * std::abs(x.w);
  g(l.u0()) = 1.0;
  dTk = 1.0;
  for (int k = 0; k < l.pb; ++k) {
    dTk *= x.dT;
    g(l.b(k)) = dTk;
  }
  return g;
}

// The distinct temperatures of the plateaus (sorted, merged within kSameTemperatureC).
std::vector<double> distinct_temperatures(const std::vector<CalibrationPlateau>& plateaus) {
  std::vector<double> t;
  for (const auto& p : plateaus) t.push_back(p.temperature_c);
  std::sort(t.begin(), t.end());
  std::vector<double> out;
  for (const double v : t) {
    if (out.empty() || v - out.back() > kSameTemperatureC) out.push_back(v);
  }
  return out;
}

// One plateau's point over samples [first, end): the output's mean and standard deviation,
// the temperature's and the rate column's means.
CalibrationPlateau plateau_over(const CalibrationRecord& r, const CalibrationOptions& o,
                                std::int64_t first, std::int64_t end) {
  CalibrationPlateau p;
  p.first_sample = first;
  p.samples = end - first;
  const auto used = static_cast<double>(p.samples);
  double sum = 0.0, temperature = 0.0, rate = 0.0;
  for (std::int64_t k = first; k < end; ++k) {
    sum += r.output_lsb[k];
    rate += r.rate_command_deg_s[k];
    if (!r.temperature_c.empty()) temperature += r.temperature_c[k];
  }
  p.rate_deg_s = rate / used;
  p.output_mean_lsb = sum / used;
  p.temperature_c = r.temperature_c.empty() ? o.reference_c : temperature / used;
  double squares = 0.0;
  for (std::int64_t k = first; k < end; ++k) {
    const double d = r.output_lsb[k] - p.output_mean_lsb;
    squares += d * d;
  }
  p.output_sd_lsb = std::sqrt(squares / (used - 1.0));
  return p;
}

// PlateauSource::output: the output's 1 s block means; a step between neighbours larger than
// kStepThreshold robust standard deviations of all steps (1.4826 MAD: the plateaus' own steps
// are most of them) ends a plateau, and the blocks in a transition (a run of large steps)
// belong to none. A plateau is a run of at least two quiet blocks; its first settle_s are left
// out as with a commanded rate (the output settles with the table, the temperature after it).
std::vector<CalibrationPlateau> plateaus_from_output(const CalibrationRecord& r,
                                                     const CalibrationOptions& o,
                                                     std::vector<Message>& notes) {
  constexpr double kStepThreshold = 8.0;
  const auto n = static_cast<std::int64_t>(r.output_lsb.size());
  const auto block = std::max<std::int64_t>(1, std::llround(r.sample_rate_hz));
  const std::int64_t blocks = n / block;
  std::vector<double> means(static_cast<std::size_t>(blocks));
  for (std::int64_t b = 0; b < blocks; ++b) {
    double sum = 0.0;
    for (std::int64_t k = b * block; k < (b + 1) * block; ++k) sum += r.output_lsb[k];
    means[b] = sum / static_cast<double>(block);
  }
  std::vector<double> steps;
  for (std::int64_t b = 1; b < blocks; ++b) steps.push_back(std::abs(means[b] - means[b - 1]));
  if (steps.size() < 3) return {};
  std::vector<double> sorted = steps;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  // |step| of a normal step: its median is 0.6745 sd.
  const double sd = sorted[sorted.size() / 2] / 0.6745;
  const double threshold = kStepThreshold * sd;
  // Block b is quiet when the steps into and out of it are small.
  const auto quiet = [&](std::int64_t b) {
    return (b == 0 || steps[b - 1] <= threshold) && (b + 1 >= blocks || steps[b] <= threshold);
  };
  const auto settle = static_cast<std::int64_t>(std::ceil(o.settle_s * r.sample_rate_hz));
  std::vector<CalibrationPlateau> plateaus;
  std::int64_t left_out = 0;
  for (std::int64_t b = 0; b < blocks;) {
    if (!quiet(b)) {
      ++b;
      continue;
    }
    std::int64_t e = b;
    while (e < blocks && quiet(e) && (e == b || steps[e - 1] <= threshold)) ++e;
    // Blocks [b, e) are one level: its samples from b's start plus the settle time (the
    // temperature settles after the output) to e's start.
    const std::int64_t first = b * block + settle;
    const std::int64_t end = e == blocks ? n : e * block;
    if (e - b >= 2 && end - first >= kMinPlateauSamples) {
      plateaus.push_back(plateau_over(r, o, first, end));
    } else {
      ++left_out;
    }
    b = e;
  }
  if (left_out > 0) {
    notes.emplace_back(Text::cal_note_stretches_left_out, left_out, o.settle_s, kMinPlateauSamples);
  }
  notes.emplace_back(Text::cal_note_plateaus_from_output, plateaus.size(), threshold);
  return plateaus;
}

std::vector<CalibrationPlateau> find_plateaus(const CalibrationRecord& r,
                                              const CalibrationOptions& o,
                                              std::vector<Message>& notes) {
  if (o.plateaus == PlateauSource::output) return plateaus_from_output(r, o, notes);
  const auto n = static_cast<std::int64_t>(r.output_lsb.size());
  const auto settle = static_cast<std::int64_t>(std::ceil(o.settle_s * r.sample_rate_hz));
  std::vector<CalibrationPlateau> plateaus;
  constexpr std::int64_t kNamedShortPlateaus = 5;
  std::int64_t left_out = 0;
  std::int64_t start = 0;
  for (std::int64_t i = 1; i <= n; ++i) {
    if (i < n && r.rate_command_deg_s[i] == r.rate_command_deg_s[start]) continue;
    const std::int64_t first = start + settle;
    const std::int64_t used = i - first;
    if (used < kMinPlateauSamples) {
      // A few by name; a commanded rate that changes every sample (a measured rate, not a
      // command) would otherwise make a note a sample.
      if (++left_out <= kNamedShortPlateaus) {
        notes.emplace_back(Text::cal_note_plateau_left_out, r.rate_command_deg_s[start], start + 1,
                           i - start, o.settle_s, kMinPlateauSamples);
      }
    } else {
      plateaus.push_back(plateau_over(r, o, first, i));
    }
    start = i;
  }
  if (left_out > kNamedShortPlateaus) {
    notes.emplace_back(Text::cal_note_more_left_out, left_out - kNamedShortPlateaus, left_out);
  }
  return plateaus;
}

// The model linearised at p in the metric W^T W: the whitened Jacobian A = W J and
// residual W (u - model(p)), the raw residual, and (A^T A)^-1 (columns scaled to unit norm
// for conditioning), the covariance before the residuals' scale.
struct Linearised {
  Eigen::MatrixXd a;
  Eigen::VectorXd whitened_residual, residual;
  Eigen::MatrixXd unscaled_covariance;
  double chi2() const { return whitened_residual.squaredNorm(); }
};

Linearised linearise(const Eigen::VectorXd& p, const Layout& l, const std::vector<Point>& x,
                     const Eigen::VectorXd& u, const Eigen::MatrixXd& whiten) {
  const int points = static_cast<int>(x.size());
  Eigen::MatrixXd J(points, l.size());
  Linearised lin;
  lin.residual.resize(points);
  const OutputModelTerms t = terms_of(p, l);
  for (int i = 0; i < points; ++i) {
    J.row(i) = model_gradient(p, l, x[i]);
    lin.residual(i) = u(i) - t.output(x[i].w, x[i].dT);
  }
  lin.a = whiten * J;
  lin.whitened_residual = whiten * lin.residual;
  const Eigen::VectorXd norms = lin.a.colwise().norm().transpose();
  const Eigen::MatrixXd scaled = lin.a * norms.cwiseInverse().asDiagonal();
  lin.unscaled_covariance = norms.cwiseInverse().asDiagonal() *
                            (scaled.transpose() * scaled).inverse() *
                            norms.cwiseInverse().asDiagonal();
  return lin;
}

// One Gauss-Newton solve of the model to the plateau means u, in the metric W^T W (W = the
// identity: ordinary least squares; W = L^-1 with V = L L^T: generalised least squares).
void gauss_newton(Eigen::VectorXd& p, const Layout& l, const std::vector<Point>& x,
                  const Eigen::VectorXd& u, const Eigen::MatrixXd& whiten) {
  for (int iteration = 0; iteration < 20; ++iteration) {
    const Linearised lin = linearise(p, l, x, u, whiten);
    // By QR of the column-scaled A, not the normal equations (their condition is squared).
    const Eigen::VectorXd norms = lin.a.colwise().norm().transpose();
    const Eigen::VectorXd step = (lin.a * norms.cwiseInverse().asDiagonal())
                                     .colPivHouseholderQr()
                                     .solve(lin.whitened_residual)
                                     .cwiseQuotient(norms);
    p += step;
    if ((step.cwiseAbs().array() <= 1e-13 * (p.cwiseAbs().array() + 1e-300)).all()) break;
  }
}

// Start values: the linearised model (cross terms of nonlinearity and temperature dropped)
// by linear least squares. Throws DataError when a coefficient has no plateau that shows it.
Eigen::VectorXd start_values(const Layout& l, const std::vector<Point>& x,
                             const Eigen::VectorXd& u) {
  const int points = static_cast<int>(x.size());
  const int parameters = l.size();
  Eigen::MatrixXd design(points, parameters);
  for (int i = 0; i < points; ++i) {
    const double w = x[i].w, dT = x[i].dT;
    design(i, 0) = w * (1.0 + power_series(l.known_s, dT));
    for (int k = 0; k < l.ps; ++k) design(i, l.s(k)) = w * std::pow(dT, k + 1);
    for (int k = 0; k < l.q; ++k) design(i, l.a(k)) = std::pow(w, k + 2);
    if (l.asymmetry) design(i, l.A()) = 0.5 * std::abs(w);
    design(i, l.u0()) = 1.0;
    for (int k = 0; k < l.pb; ++k) design(i, l.b(k)) = std::pow(dT, k + 1);
  }
  // Columns scaled to unit norm for conditioning.
  const Eigen::VectorXd norms = design.colwise().norm().transpose();
  for (int j = 0; j < parameters; ++j) {
    if (norms(j) == 0.0) {
      throw DataError("calibrate: a coefficient of the model has no plateau that shows it");
    }
  }
  const Eigen::MatrixXd scaled = design * norms.cwiseInverse().asDiagonal();
  const Eigen::VectorXd beta = scaled.colPivHouseholderQr().solve(u).cwiseQuotient(norms);
  Eigen::VectorXd p = beta;
  const double S = beta(0);
  for (int k = 0; k < l.ps; ++k) p(l.s(k)) = beta(l.s(k)) / S;
  for (int k = 0; k < l.q; ++k) p(l.a(k)) = beta(l.a(k)) / S;
  if (l.asymmetry) p(l.A()) = beta(l.A()) / S;
  return p;
}

// The t value of coefficient j at the fit p in the metric W^T W: |p_j| over its standard
// error, from (J^T W^T W J)^-1 times the residuals' chi-square per degree of freedom (W the
// identity: ordinary least squares) or times max(1, it) (W from a noise model's covariance,
// as calibrate() states its intervals).
double t_value(const Eigen::VectorXd& p, const Layout& l, const std::vector<Point>& x,
               const Eigen::VectorXd& u, int j, const Eigen::MatrixXd& whiten,
               bool noise_covariance) {
  const Linearised lin = linearise(p, l, x, u, whiten);
  const double chi2_per_dof = lin.chi2() / static_cast<double>(x.size() - l.size());
  const double scale = noise_covariance ? std::max(1.0, chi2_per_dof) : chi2_per_dof;
  const double sd = std::sqrt(lin.unscaled_covariance(j, j) * scale);
  return std::abs(p(j)) / sd;
}

// The covariance of the plateau means, from the noise model identified on the run's own
// residual record (core/noise_model.h), for generalised least squares.
struct PlateauCovariance {
  Eigen::MatrixXd cov_lsb2;             // the plateau means' (generalised) covariance [LSB^2]
  Eigen::MatrixXd stationary_cov_lsb2;  // its white, Gauss-Markov and quantisation part
  Eigen::MatrixXd whiten;               // L^-1 of V = cov + common 1 1^T = L L^T [1/LSB]
  NoiseModel noise;                     // [deg/h units] identified on the residual record
};

// The samples the plateaus use, less the fitted model, joined into one rate record [deg/h]
// (the settle times between them left out, not marked as gaps: a gap-aware Allan deviation
// would stop at the plateau's length, below the taus where a wander shows; the settle times,
// 5 s of 60 by default, shorten its time axis by as much); its Allan deviation and the
// noise model fitted to it (model/noise_fit.h) give the covariance of any two plateau means
// by Greenhall's structure function of the angle (core/noise_model.h), at their true times:
//
//   cov(m_i, m_j) = -1/2 sum_{x in {a_i, b_i}} sum_{y in {a_j, b_j}} s_x s_y D(|x - y|) / (L_i L_j)
//
// with [a, b] a plateau's window, L = b - a, s = +1 at b and -1 at a. The flicker and random-
// walk terms' D hold an arbitrary constant level (their variance has no finite value); it is
// common to all plateaus and absorbed by the bias u0: every other coefficient's estimate and
// covariance are the same whatever it is (a constant added to V to make it positive definite
// changes nothing but u0's variance). For them the bias is therefore the run's own level:
// u0's error is taken against the mean of the random part over the samples used, a
// combination of plateau means whose weights sum to zero, which the structure function does
// determine; the level's spread from run to run is the bias instability (B, K), reported as
// such. The stationary terms (white, Gauss-Markov, quantisation) have a mean, and their part
// of the run's level is added to u0's variance: u0 is the gyro's bias less the wander alone.
std::optional<PlateauCovariance> plateau_covariance(const CalibrationRecord& r,
                                                    const std::vector<CalibrationPlateau>& plateaus,
                                                    const OutputModelTerms& fitted,
                                                    double rate_unit_lsb_per_deg_s,
                                                    double reference_c,
                                                    std::vector<Message>& notes) {
  const double deg_h_per_lsb = 3600.0 / rate_unit_lsb_per_deg_s;
  std::vector<double> residual_deg_h;
  for (const CalibrationPlateau& plateau : plateaus) {
    for (std::int64_t k = plateau.first_sample; k < plateau.first_sample + plateau.samples; ++k) {
      const double dT = r.temperature_c.empty() ? 0.0 : r.temperature_c[k] - reference_c;
      residual_deg_h.push_back((r.output_lsb[k] - fitted.output(plateau.rate_deg_s, dT)) *
                               deg_h_per_lsb);
    }
  }
  NoiseFitResult fit;
  stats::AllanResult allan;
  try {
    allan = stats::allan_deviation_in_place(residual_deg_h, r.sample_rate_hz, InputKind::rate,
                                            stats::AllanOptions{});
    fit = fit_noise_model(allan);
  } catch (const std::exception& e) {  // UsageError or DataError: too short for the statistic
    notes.emplace_back(Text::cal_note_alike_no_fit, Message::verbatim(e.what()));
    return std::nullopt;
  }
  if (fit.status == FitStatus::degenerate) {
    notes.emplace_back(Text::cal_note_alike_no_fit, fit.outcome);
    return std::nullopt;
  }

  PlateauCovariance v;
  v.noise = fit.model;
  // The wander terms, flicker and random walk, correlate the plateaus of a temperature block
  // and are what the bias's temperature terms can mistake for a law. One record of an hour
  // or two shows them poorly under the white noise: the fit leaves one out as not worth its
  // parameter, or takes the rise at the last taus for a ramp (a deterministic trend, no
  // correlation at all). For the covariance a wander taken too small costs the intervals
  // their honesty, one taken too large only some width: each enters one standard error above
  // its estimate (the estimate plus a 1.96th of its 95 % interval's upper half when resolved;
  // a 1.645th of the one-sided 95 % bound when left out: the 84 % bound of either), and the
  // ramp not at all. (At the 95 % bounds, 99-100 % of the intervals held the truth and were
  // twice as wide as they need be; at the estimates alone, 91-92 %: docs/validation.md.)
  v.noise.R = 0.0;
  const auto plausible = [](const ParameterEstimate& e) {
    const double bound = e.status == TermStatus::absent ? e.upper_95 / 1.645
                                                        : e.value + (e.ci95_high - e.value) / 1.96;
    return std::isfinite(bound) ? std::max(bound, 0.0) : 0.0;
  };
  // Neither may exceed what the record's own Allan deviation allows at any tau (its 95 %
  // upper end there): a bound of a term left out can be absurd on a short record.
  double cap_b = std::numeric_limits<double>::infinity(), cap_k = cap_b;
  for (std::size_t i = 0; i < allan.tau_s.size(); ++i) {
    const double high = allan.ci95_high[i];
    if (!std::isfinite(high)) continue;
    cap_b =
        std::min(cap_b, high / std::sqrt(unit_allan_variance(NoiseTerm::flicker, allan.tau_s[i])));
    cap_k = std::min(cap_k,
                     high / std::sqrt(unit_allan_variance(NoiseTerm::random_walk, allan.tau_s[i])));
  }
  v.noise.B = std::min(std::max(v.noise.B, plausible(fit.B)), cap_b);
  v.noise.K = std::min(std::max(v.noise.K, plausible(fit.K)), cap_k);
  const NoiseTermSet terms = v.noise.terms();
  const auto n = static_cast<int>(plateaus.size());
  const auto window = [&](int i) {
    const double a = static_cast<double>(plateaus[i].first_sample) / r.sample_rate_hz;
    return std::pair{a, a + static_cast<double>(plateaus[i].samples) / r.sample_rate_hz};
  };
  const double lsb2_per_deg_h2 = 1.0 / (deg_h_per_lsb * deg_h_per_lsb);
  // The covariance of the plateau means under the terms of `set` [LSB^2].
  const auto covariance_of = [&](NoiseTermSet set) {
    const auto structure = [&](double lag_s) {
      double d = 0.0;
      for (const NoiseTerm term : kNoiseTerms) {
        if (set.contains(term)) d += angle_structure_function(v.noise, term, lag_s);
      }
      return d;
    };
    Eigen::MatrixXd cov(n, n);
    for (int i = 0; i < n; ++i) {
      const auto [ai, bi] = window(i);
      for (int j = 0; j <= i; ++j) {
        const auto [aj, bj] = window(j);
        const double sum = structure(std::abs(bi - bj)) - structure(std::abs(bi - aj)) -
                           structure(std::abs(ai - bj)) + structure(std::abs(ai - aj));
        cov(i, j) = cov(j, i) = -0.5 * sum / ((bi - ai) * (bj - aj)) * lsb2_per_deg_h2;
      }
    }
    return cov;
  };
  Eigen::MatrixXd cov = covariance_of(terms);
  NoiseTermSet stationary;  // the terms with a mean
  for (const NoiseTerm term :
       {NoiseTerm::white, NoiseTerm::gauss_markov, NoiseTerm::quantisation}) {
    if (terms.contains(term)) stationary = stationary.with(term);
  }
  v.stationary_cov_lsb2 = covariance_of(stationary);
  double common = 10.0 * cov.cwiseAbs().maxCoeff();
  for (int attempt = 0; attempt < 4; ++attempt, common *= 100.0) {
    const Eigen::LLT<Eigen::MatrixXd> llt(cov.array() + common);
    if (llt.info() != Eigen::Success) continue;
    v.whiten = llt.matrixL().solve(Eigen::MatrixXd::Identity(n, n));
    v.cov_lsb2 = std::move(cov);
    return v;
  }
  notes.emplace_back(Text::cal_note_alike_not_pd);
  return std::nullopt;
}

CalibratedValue with_interval(double value, double variance, double t95) {
  const double sd = std::sqrt(std::max(variance, 0.0));
  return {value, sd, value - t95 * sd, value + t95 * sd};
}

}  // namespace

namespace {

// The fitted coefficients' values, in the arrays OutputModelTerms views.
struct FittedTerms {
  std::vector<double> s, a, b;
  OutputModelTerms terms;
  explicit FittedTerms(const Calibration& c) {
    for (const auto& v : c.scale_factor_temp) s.push_back(v.value);
    for (const auto& v : c.nonlinearity) a.push_back(v.value);
    for (const auto& v : c.bias_temp) b.push_back(v.value);
    terms = {c.scale_factor.value, s, a, std::isfinite(c.asymmetry.value) ? c.asymmetry.value : 0.0,
             c.bias.value,         b};
  }
  FittedTerms(const FittedTerms&) = delete;
  FittedTerms& operator=(const FittedTerms&) = delete;
};

}  // namespace

double calibrated_output_lsb(const Calibration& c, double rate_deg_s, double temperature_c) {
  return FittedTerms(c).terms.output(rate_deg_s, temperature_c - c.reference_c);
}

double corrected_rate_deg_s(const Calibration& c, double output_lsb, double temperature_c) {
  const FittedTerms fitted(c);
  const OutputModelTerms& t = fitted.terms;
  const double dT = temperature_c - c.reference_c;
  const double net = output_lsb - t.bias_at(dT);  // S(T) [1 + f(w)] w
  const double scale = t.scale_factor * t.relative_scale_factor(dT);
  double w = net / scale;
  for (int step = 0; step < 8 && w != 0.0; ++step) {
    const double slope = scale * (1.0 + t.nonlinearity_at(w));  // net / w at this w
    if (slope == 0.0) break;
    w = net / slope;
  }
  return w;
}

Calibration calibrate(const CalibrationRecord& r, const CalibrationOptions& o) {
  const std::size_t n = r.output_lsb.size();
  if (r.rate_command_deg_s.size() != n ||
      (!r.temperature_c.empty() && r.temperature_c.size() != n)) {
    throw DataError(
        fmt::format("calibrate: the columns differ in length ({} commanded rates, {} "
                    "outputs, {} temperatures)",
                    r.rate_command_deg_s.size(), n, r.temperature_c.size()));
  }
  if (!(r.sample_rate_hz > 0.0) || !std::isfinite(r.sample_rate_hz)) {
    throw UsageError(
        fmt::format("calibrate: the sample rate must be > 0 Hz, got {}", r.sample_rate_hz));
  }
  Calibration c;
  c.reference_c = o.reference_c;
  c.plateaus = find_plateaus(r, o, c.notes);
  if (c.plateaus.empty()) {
    throw DataError(fmt::format(
        "calibrate: every plateau is shorter than the settle time ({} s) plus {} samples: "
        "nothing to fit{}",
        o.settle_s, kMinPlateauSamples, c.notes.empty() ? "" : " (" + c.notes.back().text() + ")"));
  }
  c.temperatures_c = distinct_temperatures(c.plateaus);
  std::vector<double> rates;
  bool positive = false, negative = false;
  for (const auto& p : c.plateaus) {
    rates.push_back(p.rate_deg_s);
    positive = positive || p.rate_deg_s > 0.0;
    negative = negative || p.rate_deg_s < 0.0;
    c.full_scale_deg_s = std::max(c.full_scale_deg_s, std::abs(p.rate_deg_s));
  }
  std::sort(rates.begin(), rates.end());
  rates.erase(std::unique(rates.begin(), rates.end()), rates.end());
  if (c.full_scale_deg_s == 0.0) {
    throw DataError("calibrate: no plateau at a non-zero rate: the scale factor cannot be found");
  }

  const int temperatures = static_cast<int>(c.temperatures_c.size());
  const int auto_degree = std::min(2, temperatures - 1);
  Layout l;
  l.pb = o.bias_temperature_degree < 0 ? auto_degree
                                       : std::min(o.bias_temperature_degree, temperatures - 1);
  l.ps = o.scale_factor_temperature_degree < 0
             ? auto_degree
             : std::min(o.scale_factor_temperature_degree, temperatures - 1);
  if (!o.known_scale_factor_temp.empty()) {
    l.ps = 0;
    l.known_s = o.known_scale_factor_temp;
  }
  l.asymmetry = o.asymmetry && positive && negative;
  if (o.asymmetry && !l.asymmetry) {
    c.notes.emplace_back(Text::cal_note_no_asymmetry);
  }
  // At one temperature the rates must outnumber the rate terms (S, a_k, A) and the bias.
  const int distinct_rates = static_cast<int>(rates.size());
  const int rate_limit = std::max(0, distinct_rates - 2 - (l.asymmetry ? 1 : 0));
  const int points = static_cast<int>(c.plateaus.size());
  std::vector<Point> x;
  Eigen::VectorXd u(points);
  for (int i = 0; i < points; ++i) {
    x.push_back({c.plateaus[i].rate_deg_s, c.plateaus[i].temperature_c - o.reference_c});
    u(i) = c.plateaus[i].output_mean_lsb;
  }
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(points, points);
  const auto rate_unit = [&](const Eigen::VectorXd& q) {  // [LSB/(deg/s)]
    return o.rate_unit_lsb_per_deg_s > 0.0 ? o.rate_unit_lsb_per_deg_s : std::abs(q(0));
  };
  // The highest degree's plateau covariance, kept for the final fit when that degree is
  // chosen (the same fit, so the same noise).
  struct Kept {
    int degree = -1;
    std::optional<PlateauCovariance> cov;
    std::vector<Message> notes;
  } kept;
  if (o.nonlinearity_degree >= 0) {
    l.q = std::min(o.nonlinearity_degree, rate_limit);
    if (l.q < o.nonlinearity_degree) {
      c.notes.emplace_back(Text::cal_note_degree_limited, l.q, distinct_rates);
    }
  } else {
    // Chosen from the data: from the highest degree the run allows (at most
    // kMaxNonlinearityDegree, two residual degrees of freedom kept), the highest term is
    // dropped while its t value stays below the 99.5 % point (a term is kept only when the
    // plateaus show it beyond doubt). The t values are weighted as the intervals are: by the
    // plateau means' covariance from the highest degree's residual record (the wander hardly
    // depends on the degree); weighted alike, a wander's correlated errors passed for a
    // spurious a_3 on 1 run in 20.
    l.q = std::min(kMaxNonlinearityDegree, rate_limit);
    while (l.q > 0 && points < l.size() + 2) --l.q;
    Eigen::MatrixXd choice_whiten = identity;
    bool choice_noise = false;
    if (o.noise_covariance && l.q > 0) {
      Eigen::VectorXd highest = start_values(l, x, u);
      gauss_newton(highest, l, x, u, identity);
      kept.degree = l.q;
      kept.cov = plateau_covariance(r, c.plateaus, terms_of(highest, l), rate_unit(highest),
                                    o.reference_c, kept.notes);
      if (kept.cov) {
        choice_whiten = kept.cov->whiten;
        choice_noise = true;
      }
    }
    for (; l.q > 0; --l.q) {
      Eigen::VectorXd trial = start_values(l, x, u);
      gauss_newton(trial, l, x, u, identity);
      if (choice_noise) gauss_newton(trial, l, x, u, choice_whiten);
      const double t99 = boost::math::quantile(
          boost::math::students_t(static_cast<double>(points - l.size())), 0.995);
      if (t_value(trial, l, x, u, l.a(l.q - 1), choice_whiten, choice_noise) >= t99) break;
    }
  }
  c.nonlinearity_degree = l.q;
  const int parameters = l.size();
  if (points <= parameters) {
    throw DataError(
        fmt::format("calibrate: {} plateaus for {} coefficients: the model needs "
                    "more plateaus (more rates or temperatures) than coefficients",
                    points, parameters));
  }
  Eigen::VectorXd p = start_values(l, x, u);

  // Gauss-Newton on the full model: first with every plateau alike, then with the plateau
  // means' covariance from the noise identified on the residual record.
  gauss_newton(p, l, x, u, identity);
  c.noise_covariance = o.noise_covariance;
  Eigen::MatrixXd whiten = identity;  // W with W^T W = V^-1 (identity: ordinary least squares)
  Eigen::MatrixXd plateau_cov;        // the plateau means' covariance (empty: white, alike)
  Eigen::MatrixXd stationary_cov;     // its part from the terms with a mean
  if (o.noise_covariance) {
    std::optional<PlateauCovariance> v;
    if (kept.degree == l.q) {
      v = std::move(kept.cov);
      c.notes.insert(c.notes.end(), kept.notes.begin(), kept.notes.end());
    } else {
      v = plateau_covariance(r, c.plateaus, terms_of(p, l), rate_unit(p), o.reference_c, c.notes);
    }
    if (v) {
      whiten = v->whiten;
      plateau_cov = std::move(v->cov_lsb2);
      stationary_cov = std::move(v->stationary_cov_lsb2);
      c.noise = v->noise;
      gauss_newton(p, l, x, u, whiten);
    } else {
      c.noise_covariance = false;
    }
  }
  const Linearised lin = linearise(p, l, x, u, whiten);
  const Eigen::VectorXd& residual = lin.residual;
  for (int i = 0; i < points; ++i) c.plateaus[i].residual_lsb = residual(i);
  c.dof = points - parameters;
  c.residual_rms_lsb = std::sqrt(residual.squaredNorm() / points);
  Eigen::MatrixXd covariance = lin.unscaled_covariance;
  // The residuals' spread against the covariance's: ordinary least squares takes the variance
  // from them; the noise model's covariance is widened when they say it is too narrow (never
  // narrowed).
  const double chi2_per_dof = lin.chi2() / c.dof;
  c.dispersion = c.noise_covariance ? std::max(1.0, chi2_per_dof) : chi2_per_dof;
  if (plateau_cov.size() > 0) {
    // u0's error against the run's level (plateau_covariance()): its estimator's weights on
    // the plateau means (row u0 of (A^T A)^-1 A^T W, A = W J) less the samples' share of each
    // in the level; plus the stationary terms' part of the level.
    const Eigen::RowVectorXd weights = covariance.row(l.u0()) * lin.a.transpose() * whiten;
    double used = 0.0;
    for (const auto& plateau : c.plateaus) used += static_cast<double>(plateau.samples);
    Eigen::VectorXd share(points);
    for (int i = 0; i < points; ++i) {
      share(i) = static_cast<double>(c.plateaus[i].samples) / used;
    }
    const Eigen::VectorXd contrast = weights.transpose() - share;
    covariance(l.u0(), l.u0()) =
        contrast.dot(plateau_cov * contrast) + share.dot(stationary_cov * share);
  }
  covariance *= c.dispersion;
  const double t95 =
      boost::math::quantile(boost::math::students_t(static_cast<double>(c.dof)), 0.975);
  auto value = [&](int j) { return with_interval(p(j), covariance(j, j), t95); };
  c.scale_factor = value(0);
  for (int k = 0; k < l.ps; ++k) c.scale_factor_temp.push_back(value(l.s(k)));
  for (const double known : l.known_s) c.scale_factor_temp.push_back({known, 0.0, known, known});
  for (int k = 0; k < l.q; ++k) c.nonlinearity.push_back(value(l.a(k)));
  c.asymmetry = l.asymmetry ? value(l.A()) : CalibratedValue{kNaN, kNaN, kNaN, kNaN};
  c.bias = value(l.u0());
  for (int k = 0; k < l.pb; ++k) c.bias_temp.push_back(value(l.b(k)));
  {
    // u0 / S * 3600 by the delta method.
    Eigen::VectorXd g = Eigen::VectorXd::Zero(parameters);
    g(l.u0()) = 3600.0 / p(0);
    g(0) = -3600.0 * p(l.u0()) / (p(0) * p(0));
    c.bias_deg_h = with_interval(3600.0 * p(l.u0()) / p(0), g.dot(covariance * g), t95);
  }

  const OutputModelTerms fitted = terms_of(p, l);
  // IEEE Std 952 nonlinearity: the fitted curve at T_ref against its straight line.
  {
    constexpr int kGrid = 20001;  // the continuous least-squares line to 1e-4
    Eigen::MatrixXd line(kGrid, 2);
    Eigen::VectorXd y(kGrid);
    for (int j = 0; j < kGrid; ++j) {
      const double w = c.full_scale_deg_s * (2.0 * j / (kGrid - 1) - 1.0);
      line(j, 0) = 1.0;
      line(j, 1) = w;
      y(j) = fitted.output(w, 0.0);
    }
    const Eigen::VectorXd fit = line.colPivHouseholderQr().solve(y);
    const double worst = (y - line * fit).cwiseAbs().maxCoeff();
    c.nonlinearity_ieee_ppm_fs = worst / std::abs(p(0) * c.full_scale_deg_s) * 1e6;
  }
  // The lab manual's: the plateaus' scale factors at the temperature nearest T_ref.
  {
    double nearest = c.temperatures_c.front();
    for (const double t : c.temperatures_c) {
      if (std::abs(t - o.reference_c) < std::abs(nearest - o.reference_c)) nearest = t;
    }
    // The bias as the lab measures it, the output at rest: the zero-rate plateaus' mean there
    // (the fitted u0(T) when the run has none).
    double at_rest = 0.0, at_rest_samples = 0.0;
    for (const auto& plateau : c.plateaus) {
      if (plateau.rate_deg_s == 0.0 &&
          std::abs(plateau.temperature_c - nearest) <= kSameTemperatureC) {
        at_rest += plateau.output_mean_lsb * static_cast<double>(plateau.samples);
        at_rest_samples += static_cast<double>(plateau.samples);
      }
    }
    std::vector<double> factors;
    for (const auto& plateau : c.plateaus) {
      if (plateau.rate_deg_s == 0.0 ||
          std::abs(plateau.temperature_c - nearest) > kSameTemperatureC)
        continue;
      const double zero = at_rest_samples > 0.0
                              ? at_rest / at_rest_samples
                              : fitted.bias_at(plateau.temperature_c - o.reference_c);
      factors.push_back((plateau.output_mean_lsb - zero) / plateau.rate_deg_s);
    }
    if (factors.size() >= 2) {
      const auto [lo, hi] = std::minmax_element(factors.begin(), factors.end());
      double mean = 0.0;
      for (const double f : factors) mean += f;
      mean /= static_cast<double>(factors.size());
      c.nonlinearity_lab1_percent = (*hi - *lo) / std::abs(mean) * 100.0;
    } else {
      c.nonlinearity_lab1_percent = kNaN;
    }
  }
  // White noise from the samples' first differences (a slow wander barely enters them).
  {
    double squares = 0.0;
    std::int64_t count = 0;
    for (const auto& plateau : c.plateaus) {
      for (std::int64_t k = plateau.first_sample + 1; k < plateau.first_sample + plateau.samples;
           ++k) {
        const double d = r.output_lsb[k] - r.output_lsb[k - 1];
        squares += d * d;
        ++count;
      }
    }
    const double sigma_lsb = std::sqrt(squares / (2.0 * static_cast<double>(count)));
    c.white_noise_deg_h_rt_hz = sigma_lsb / rate_unit(p) * 3600.0 / std::sqrt(r.sample_rate_hz);
  }
  const double per_lsb_deg_h = 3600.0 / rate_unit(p);
  c.budget.bias_deg_h = 0.5 * (c.bias.ci95_high - c.bias.ci95_low) * per_lsb_deg_h;
  c.budget.scale_factor_deg_h = 0.5 * (c.scale_factor.ci95_high - c.scale_factor.ci95_low) /
                                std::abs(p(0)) * c.full_scale_deg_s * 3600.0;
  c.budget.nonlinearity_deg_h = residual.cwiseAbs().maxCoeff() * per_lsb_deg_h;
  c.budget.noise_1s_deg_h = c.white_noise_deg_h_rt_hz;
  return c;
}

TriadCalibration calibrate_triad(std::span<const TriadRecord, 3> mountings,
                                 const CalibrationOptions& options) {
  constexpr const auto& kAxis = kTriadAxes;
  const auto fit = [&](int gyro, int mounting, const CalibrationOptions& o) {
    const TriadRecord& m = mountings[mounting];
    try {
      return calibrate(
          {m.sample_rate_hz, m.rate_command_deg_s, m.output_lsb[gyro], m.temperature_c}, o);
    } catch (const DataError& e) {
      throw DataError(fmt::format("calibrate: gyro {} on the mounting about {}: {}", kAxis[gyro],
                                  kAxis[mounting], e.what()));
    }
  };
  TriadCalibration t;
  for (int i = 0; i < 3; ++i) t.axes[i] = fit(i, i, options);
  for (int i = 0; i < 3; ++i) {
    const Calibration& own = t.axes[i];
    CalibrationOptions cross = options;
    cross.nonlinearity_degree = 0;  // the cross-axis rate is m w, a thousandth of w
    cross.asymmetry = false;
    cross.known_scale_factor_temp.clear();
    for (const CalibratedValue& s : own.scale_factor_temp) {
      cross.known_scale_factor_temp.push_back(s.value);
    }
    // A zero polynomial still marks S(T) as known: no temperature term of the small cross
    // scale factor is fitted.
    if (cross.known_scale_factor_temp.empty()) cross.known_scale_factor_temp.push_back(0.0);
    cross.rate_unit_lsb_per_deg_s = std::abs(own.scale_factor.value);
    for (int j = 0; j < 3; ++j) {
      if (j == i) {
        t.misalignment_rad[i][j] = {kNaN, kNaN, kNaN, kNaN};
        continue;
      }
      t.cross[i][j] = fit(i, j, cross);
      const CalibratedValue& sij = t.cross[i][j].scale_factor;
      const double m = sij.value / own.scale_factor.value;
      // Delta method: var m = var S_ij / S_i^2 + m^2 var S_i / S_i^2 (independent runs).
      const double var = (sij.sd * sij.sd + m * m * own.scale_factor.sd * own.scale_factor.sd) /
                         (own.scale_factor.value * own.scale_factor.value);
      const double t95 = boost::math::quantile(
          boost::math::students_t(static_cast<double>(t.cross[i][j].dof)), 0.975);
      t.misalignment_rad[i][j] = with_interval(m, var, t95);
    }
  }
  return t;
}

}  // namespace foglab::model
