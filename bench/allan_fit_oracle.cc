// foglab — the noise fit against estimators that know more than it does
// (docs/validation.md, "what the record holds").
//
//   allan_fit_oracle --N 0.3 --B 0.1 --K 0.02 --fs 100 --hours 2 --from 1 --to 40
//
// For each seed, generates the record (the generator's noise only, as
// `foglab generate --seed S` does), computes the noise fit's points (octave
// OADEV down to three clusters) and estimates the true model's coefficients
// three ways:
//   fit     foglab's noise fit, choosing its model (model::fit_noise_model);
//   gls     generalised least squares on the true model's terms with the
//           exact covariance of the points (src/model/allan_covariance.h),
//           iterated from the fit's values (a practical estimator);
//   oracle  the same, one step with the covariance of the true model (the
//           best linear unbiased estimator of the squared coefficients, which
//           no estimator of these points can know).
// Prints, per term and estimator, the mean and standard deviation of
// ln(estimate / truth) and the median absolute relative error over all
// seeds and over the first ten; --rows adds one line per seed.
#include <CLI/CLI.hpp>
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "../src/model/allan_covariance.h"
#include "fit_study_options.h"
#include "fmt/format.h"
#include "foglab/core/noise_model.h"
#include "foglab/model/noise_fit.h"
#include "foglab/sim/generator.h"
#include "foglab/stats/allan.h"

namespace {

using namespace foglab;

constexpr int kEstimators = 3;
constexpr const char* kEstimatorNames[kEstimators] = {"fit", "gls", "oracle"};

// The squared coefficients of `terms` as a model.
NoiseModel model_of(const std::vector<NoiseTerm>& terms, const Eigen::VectorXd& squared) {
  NoiseModel m;
  for (std::size_t j = 0; j < terms.size(); ++j) {
    m.set_coefficient(terms[j], std::sqrt(std::max(squared(static_cast<Eigen::Index>(j)), 1e-30)));
  }
  return m;
}

// One generalised-least-squares step: the squared coefficients minimising
// (y - X c)' S^-1 (y - X c), S the covariance under `model`.
Eigen::VectorXd gls_step(const Eigen::MatrixXd& x, const Eigen::VectorXd& y,
                         const NoiseModel& model, const stats::AllanResult& a) {
  const Eigen::MatrixXd s =
      model::detail::allan_variance_covariance(model, 1.0 / a.sample_rate_hz, a.m, a.phase_points);
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(s);
  const Eigen::MatrixXd sx = ldlt.solve(x);
  return (x.transpose() * sx).ldlt().solve(sx.transpose() * y);
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t h = v.size() / 2;
  return v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]);
}

struct Summary {
  double mean = 0.0, sd = 0.0, median_all = 0.0, median_first_ten = 0.0;
  std::size_t count = 0;
};

// ln errors, NaN where the estimator had no value.
Summary summarise(const std::vector<double>& ln_errors) {
  Summary s;
  std::vector<double> kept, abs_all, abs_ten;
  for (std::size_t i = 0; i < ln_errors.size(); ++i) {
    if (!std::isfinite(ln_errors[i])) continue;
    kept.push_back(ln_errors[i]);
    abs_all.push_back(std::abs(std::expm1(ln_errors[i])));
    if (i < 10) abs_ten.push_back(abs_all.back());
  }
  s.count = kept.size();
  for (double e : kept) s.mean += e / static_cast<double>(kept.size());
  for (double e : kept) s.sd += (e - s.mean) * (e - s.mean);
  s.sd = kept.size() > 1 ? std::sqrt(s.sd / static_cast<double>(kept.size() - 1)) : NAN;
  s.median_all = median(abs_all);
  s.median_first_ten = median(abs_ten);
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  bench::StudiedRecord record;
  int first_seed = 1, last_seed = 40, iterations = 8;
  bool rows = false;
  CLI::App app{"the noise fit against generalised least squares and an oracle, over seeds"};
  bench::add_record_options(app, record);
  app.add_option("--from", first_seed, "first seed");
  app.add_option("--to", last_seed, "last seed");
  app.add_option("--iterations", iterations, "GLS iterations");
  app.add_flag("--rows", rows, "one line per seed");
  CLI11_PARSE(app, argc, argv);
  const NoiseModel& truth = record.model;
  const double fs_hz = record.fs_hz, hours = record.hours;

  std::vector<NoiseTerm> terms;
  for (NoiseTerm t : {NoiseTerm::white, NoiseTerm::flicker, NoiseTerm::random_walk}) {
    if (truth.coefficient(t) > 0.0) terms.push_back(t);
  }
  const auto term_count = static_cast<Eigen::Index>(terms.size());
  Eigen::VectorXd true_squared(term_count);
  for (Eigen::Index j = 0; j < term_count; ++j) {
    true_squared(j) = std::pow(truth.coefficient(terms[static_cast<std::size_t>(j)]), 2);
  }
  // errors[estimator][term][seed]: ln(estimate / truth)
  std::vector<std::vector<std::vector<double>>> errors(
      kEstimators, std::vector<std::vector<double>>(terms.size()));
  for (int seed = first_seed; seed <= last_seed; ++seed) {
    sim::ErrorModel error_model;
    error_model.noise = truth;
    sim::GeneratorOptions generator;
    generator.sample_rate_hz = fs_hz;
    generator.duration_s = hours * 3600.0;
    generator.seed = static_cast<std::uint64_t>(seed);
    const sim::Recording recording =
        sim::generate(error_model, sim::TemperatureProfile{}, generator);
    stats::AllanOptions allan_options;
    allan_options.grid.min_clusters = 3;
    const stats::AllanResult a =
        stats::allan_deviation(recording.rate_deg_h, fs_hz, InputKind::rate, allan_options);
    const model::NoiseFitResult fit = model::fit_noise_model(a);

    const auto points = static_cast<Eigen::Index>(a.m.size());
    Eigen::VectorXd y(points);
    Eigen::MatrixXd x(points, term_count);
    NoiseModel unit;
    for (NoiseTerm t : terms) unit.set_coefficient(t, 1.0);
    for (Eigen::Index i = 0; i < points; ++i) {
      const auto k = static_cast<std::size_t>(i);
      y(i) = a.dev[k] * a.dev[k];
      for (Eigen::Index j = 0; j < term_count; ++j) {
        x(i, j) = allan_variance(unit, terms[static_cast<std::size_t>(j)], a.tau_s[k]);
      }
    }
    Eigen::VectorXd estimates[kEstimators];
    estimates[0] = Eigen::VectorXd(term_count);
    for (Eigen::Index j = 0; j < term_count; ++j) {
      const double v = fit.model.coefficient(terms[static_cast<std::size_t>(j)]);
      // A term the fit left out starts the GLS at the truth and counts as missing.
      estimates[0](j) = v > 0.0 ? v * v : NAN;
    }
    Eigen::VectorXd c = estimates[0];
    for (Eigen::Index j = 0; j < term_count; ++j) {
      if (!std::isfinite(c(j))) c(j) = true_squared(j);
    }
    for (int it = 0; it < iterations; ++it) c = gls_step(x, y, model_of(terms, c), a);
    estimates[1] = c;
    estimates[2] = gls_step(x, y, truth, a);
    if (rows) fmt::print("seed {:4d}", seed);
    for (int e = 0; e < kEstimators; ++e) {
      for (Eigen::Index j = 0; j < term_count; ++j) {
        const double ln_error = 0.5 * std::log(estimates[e](j) / true_squared(j));
        errors[static_cast<std::size_t>(e)][static_cast<std::size_t>(j)].push_back(ln_error);
        if (rows) {
          fmt::print(" {}:{}={:+.4f}", kEstimatorNames[e],
                     to_string(terms[static_cast<std::size_t>(j)]), ln_error);
        }
      }
    }
    if (rows) fmt::print("\n");
  }
  fmt::print("seeds {}-{}, {} h at {} Hz; ln(estimate/truth) in %\n", first_seed, last_seed, hours,
             fs_hz);
  fmt::print("{:<14} {:<7} {:>7} {:>7} {:>14} {:>16} {:>6}\n", "term", "method", "mean", "sd",
             "median |error|", "first ten seeds", "count");
  for (std::size_t j = 0; j < terms.size(); ++j) {
    for (int e = 0; e < kEstimators; ++e) {
      const Summary s = summarise(errors[static_cast<std::size_t>(e)][j]);
      fmt::print("{:<14} {:<7} {:7.2f} {:7.2f} {:14.2f} {:16.2f} {:6}\n", to_string(terms[j]),
                 kEstimatorNames[e], 100 * s.mean, 100 * s.sd, 100 * s.median_all,
                 100 * s.median_first_ten, s.count);
    }
  }
}
