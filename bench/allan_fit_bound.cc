// foglab — how precisely the octave Allan variances of a record can fix the
// noise terms (docs/validation.md, "what the record holds").
//
//   allan_fit_bound --N 0.3 --B 0.1 --K 0.02 --fs 100 --hours 2
//
// For the noise fit's points (octave averaging factors down to three
// clusters) and the exact covariance of their overlapping Allan variance
// estimates under the given model (src/model/allan_covariance.h), prints the
// standard deviation of ln(coefficient) of two linearised estimators:
// weighted least squares with each point's own variance as its weight (the
// independent-points fit foglab does, its edf standing in for that
// variance), and generalised least squares with the full covariance (the
// best any estimator of these points can do). Asymptotic: the record's
// actual spread over seeds, with model selection, comes on top.
#include <CLI/CLI.hpp>
#include <Eigen/Dense>
#include <cmath>
#include <cstdint>
#include <vector>

#include "../src/model/allan_covariance.h"
#include "fit_study_options.h"
#include "fmt/format.h"
#include "foglab/core/noise_model.h"

int main(int argc, char** argv) {
  using namespace foglab;
  bench::StudiedRecord record;
  CLI::App app{"linearised precision of the noise fit's Allan points"};
  bench::add_record_options(app, record);
  CLI11_PARSE(app, argc, argv);
  const NoiseModel& model = record.model;
  const double fs_hz = record.fs_hz, hours = record.hours;

  const auto phase_points = static_cast<std::int64_t>(fs_hz * hours * 3600.0) + 1;
  const double tau0_s = 1.0 / fs_hz;
  std::vector<std::int64_t> m;
  for (std::int64_t k = 1; (phase_points - 1) / k >= 3; k *= 2) m.push_back(k);
  const Eigen::MatrixXd covariance =
      model::detail::allan_variance_covariance(model, tau0_s, m, phase_points);

  std::vector<NoiseTerm> terms;
  for (NoiseTerm t : {NoiseTerm::white, NoiseTerm::flicker, NoiseTerm::random_walk}) {
    if (model.coefficient(t) > 0.0) terms.push_back(t);
  }
  // d(Allan variance)/d ln(coefficient^2) at each point: the term's share.
  Eigen::MatrixXd jacobian(static_cast<Eigen::Index>(m.size()),
                           static_cast<Eigen::Index>(terms.size()));
  for (std::size_t i = 0; i < m.size(); ++i) {
    for (std::size_t j = 0; j < terms.size(); ++j) {
      jacobian(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
          allan_variance(model, terms[j], static_cast<double>(m[i]) * tau0_s);
    }
  }
  const Eigen::MatrixXd weight = covariance.diagonal().cwiseInverse().asDiagonal();
  const Eigen::MatrixXd bread = (jacobian.transpose() * weight * jacobian).inverse();
  const Eigen::MatrixXd weighted =
      bread * jacobian.transpose() * weight * covariance * weight * jacobian * bread;
  const Eigen::MatrixXd generalised =
      (jacobian.transpose() * covariance.inverse() * jacobian).inverse();
  fmt::print("{} points, tau {} .. {} s\n", m.size(), tau0_s,
             static_cast<double>(m.back()) * tau0_s);
  for (std::size_t j = 0; j < terms.size(); ++j) {
    const auto jj = static_cast<Eigen::Index>(j);
    // ln(coefficient) = ln(coefficient^2) / 2
    fmt::print("{:<14} sd of ln: weighted {:6.2f} %, generalised {:6.2f} %\n", to_string(terms[j]),
               50.0 * std::sqrt(weighted(jj, jj)), 50.0 * std::sqrt(generalised(jj, jj)));
  }
}
