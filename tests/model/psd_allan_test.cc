// The manual's eq. (17) (model/psd_allan.h): the Allan variance of each term's PSD against
// its closed form, the bandwidth's power response against the generator's filter, and the
// fitted PSD's Allan deviation against the measured one on generated records.
#include "foglab/model/psd_allan.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/core/sensor_bandwidth.h"
#include "foglab/model/analysis.h"
#include "foglab/sim/generator.h"
#include "foglab/sim/sensor_output.h"

namespace foglab::model {
namespace {

constexpr double kTau0 = 0.01;       // 100 Hz
constexpr double kFarBelow = 1e-12;  // [Hz] the band's lower end: no cut

double from_psd(const NoiseFitResult& fit, double tau, double f_low = kFarBelow) {
  return allan_variance_from_psd([&](double f) { return fitted_rate_psd(fit, f, kTau0); }, tau,
                                 kTau0, f_low);
}

NoiseFitResult fit_of(const NoiseModel& m) {
  NoiseFitResult fit;
  fit.model = m;
  return fit;
}

TEST(PsdAllan, WhiteNoiseAndQuantisationAreExactForSampledData) {
  // The m-sample average's kernel makes N^2 / tau and 3 Q^2 / tau^2 exact at every m,
  // including m = 1 where the sinc of eq. (17) would not be.
  for (const double tau : {kTau0, 3 * kTau0, 1.0, 100.0}) {
    EXPECT_NEAR(from_psd(fit_of({.N = 2.0}), tau) / (4.0 / tau), 1.0, 1e-6) << tau;
    EXPECT_NEAR(from_psd(fit_of({.Q = 0.3}), tau) / (3.0 * 0.09 / (tau * tau)), 1.0, 1e-6) << tau;
  }
}

TEST(PsdAllan, FlickerRandomWalkAndGaussMarkovFollowTheirClosedForms) {
  // Away from the band's ends (tau >> tau0; tau << 1 / f_low) eq. (17) is IEEE Std 952's
  // closed form; the Nyquist cut leaves flicker's plateau short by O(1/m).
  const NoiseModel m{.B = 0.5, .K = 0.02, .gm_sigma = 1.5, .gm_tc = 40.0};
  for (const double tau : {10.0, 100.0, 1000.0}) {
    EXPECT_NEAR(from_psd(fit_of({.B = m.B}), tau) / allan_variance(m, NoiseTerm::flicker, tau), 1.0,
                0.01)
        << tau;
    EXPECT_NEAR(from_psd(fit_of({.K = m.K}), tau) / allan_variance(m, NoiseTerm::random_walk, tau),
                1.0, 1e-4)
        << tau;
    EXPECT_NEAR(from_psd(fit_of({.gm_sigma = m.gm_sigma, .gm_tc = m.gm_tc}), tau) /
                    allan_variance(m, NoiseTerm::gauss_markov, tau),
                1.0, 1e-3)
        << tau;
  }
  // At T/3 of a record a random walk's Allan variance still needs the frequencies below
  // 1/T: the check's f_low = 1e-6 / T keeps it; a cut at 1/T would lose more than half.
  const double tau = 1200.0, record = 3600.0;
  const double expected = allan_variance(m, NoiseTerm::random_walk, tau);
  EXPECT_NEAR(from_psd(fit_of({.K = m.K}), tau, 1e-6 / record) / expected, 1.0, 1e-4);
  EXPECT_LT(from_psd(fit_of({.K = m.K}), tau, 1.0 / record), 0.5 * expected);
}

TEST(PsdAllan, TheBandwidthsPowerResponseIsTheGeneratorsFilterAndGivesItsAllanFactor) {
  // core's power response against sim's filter gain (written apart), and eq. (17) on the
  // filtered white noise against the exact Allan factor of sensor_bandwidth.h.
  struct Case {
    SensorBandwidth bandwidth;
    sim::SensorOutput output;
  };
  std::vector<Case> cases(3);
  cases[0].bandwidth = {.filtered_fraction = 1.0, .time_constant_s = 0.05};
  cases[0].output.filter_time_constant_s = 0.05;
  cases[1].bandwidth = {.filtered_fraction = 1.0, .moving_average_samples = 8};
  cases[1].output.moving_average_samples = 8;
  cases[2].bandwidth = {.filtered_fraction = 1.0, .butterworth_cutoff_hz = 12.0};
  cases[2].output.butterworth_cutoff_hz = 12.0;
  for (const Case& c : cases) {
    for (const double f : {0.1, 3.0, 11.0, 27.0, 49.9}) {
      EXPECT_NEAR(power_response(c.bandwidth, f, kTau0),
                  std::pow(sim::output_filter_gain(c.output, f, 1.0 / kTau0), 2), 1e-12)
          << f;
    }
    NoiseFitResult fit = fit_of({.N = 3.0});
    fit.bandwidth.resolved = true;
    fit.bandwidth.bandwidth = c.bandwidth;
    fit.bandwidth.sample_interval_s = kTau0;
    for (const int m : {1, 2, 5, 30, 400}) {
      const double tau = m * kTau0;
      EXPECT_NEAR(from_psd(fit, tau) / fitted_allan_variance(fit, NoiseTerm::white, tau), 1.0, 1e-5)
          << "m = " << m;
    }
  }
  // Part of the noise filtered: the response's floor is 1 - phi.
  const SensorBandwidth half{.filtered_fraction = 0.4, .time_constant_s = 0.05};
  EXPECT_NEAR(
      power_response(half, 49.9, kTau0),
      0.6 + 0.4 * power_response({.filtered_fraction = 1.0, .time_constant_s = 0.05}, 49.9, kTau0),
      1e-12);
  EXPECT_EQ(power_response({}, 10.0, kTau0), 1.0);
}

TEST(PsdAllan, BadArgumentsAreUsageErrors) {
  const auto psd = [](double) { return 1.0; };
  EXPECT_THROW(allan_variance_from_psd(psd, 0.0, kTau0, 1e-3), UsageError);
  EXPECT_THROW(allan_variance_from_psd(psd, 1.0, -kTau0, 1e-3), UsageError);
  EXPECT_THROW(allan_variance_from_psd(psd, 1.0, kTau0, 0.0), UsageError);
  // A degenerate fit compares nothing.
  NoiseFitResult degenerate;
  degenerate.status = FitStatus::degenerate;
  stats::AllanResult allan;
  allan.tau_s = {1.0};
  allan.dev = {1.0};
  allan.ci95_low = {0.9};
  allan.ci95_high = {1.1};
  const PsdAllanCheck c = check_allan_against_psd(degenerate, allan, kTau0, 100.0);
  EXPECT_EQ(c.compared, 0);
  EXPECT_TRUE(c.tau_s.empty());
}

TEST(PsdAllan, TheFittedPsdsAllanDeviationMeetsTheMeasuredOneOnGeneratedRecords) {
  // Issue 23's done-when: eq. (17) on the fitted PSD agrees with the measured Allan
  // deviation within its 95 % intervals. Five models (flicker and a random walk; a
  // Gauss-Markov bias; quantisation; a sensor bandwidth; a rate ramp), one seed each.
  struct Record {
    std::string name;
    sim::ErrorModel model;
    double rate_hz, hours;
  };
  std::vector<Record> records(5);
  records[0] = {"N+B+K", {}, 10.0, 2.0};
  records[0].model.noise = {.N = 0.5, .B = 0.05, .K = 0.005};
  records[1] = {"N+GM", {}, 10.0, 2.0};
  records[1].model.noise = {.N = 0.5, .gm_sigma = 0.3, .gm_tc = 60.0};
  records[2] = {"N+B+Q", {}, 10.0, 1.0};
  records[2].model.noise = {.N = 0.2, .B = 0.05, .Q = 0.3};
  records[3] = {"N+B, first-order filter", {}, 100.0, 1.0};
  records[3].model.noise = {.N = 150.0, .B = 5.0};
  records[3].model.output.filter_time_constant_s = 0.03;
  records[4] = {"N+K+R", {}, 10.0, 2.0};
  records[4].model.noise = {.N = 0.5, .K = 0.01, .R = 2e-4};
  int compared = 0, inside = 0;
  for (std::size_t k = 0; k < records.size(); ++k) {
    const Record& rec = records[k];
    sim::GeneratorOptions g;
    g.sample_rate_hz = rec.rate_hz;
    g.duration_s = rec.hours * 3600.0;
    g.seed = 100 + k;
    sim::Recording data = sim::generate(rec.model, sim::TemperatureProfile{}, g);
    const AnalysisResult r = analyze(data.rate_deg_h, data.temperature_c, data.sample_rate_hz);
    const PsdAllanCheck& c = r.psd_allan;
    ASSERT_EQ(c.tau_s.size(), r.allan.tau_s.size()) << rec.name;
    EXPECT_GE(c.compared, 10) << rec.name;
    EXPECT_GE(c.inside_95, c.compared - 3)
        << rec.name << ": worst " << c.worst_ratio << " at " << c.worst_tau_s << " s";
    EXPECT_LT(c.worst_half_widths, 2.0) << rec.name << " at " << c.worst_tau_s << " s";
    compared += c.compared;
    inside += c.inside_95;
    // The same model through the time domain: eq. (17) departs from its closed forms only
    // by flicker's Nyquist cut at the shortest taus.
    for (std::size_t i = 0; i < c.tau_s.size(); ++i) {
      EXPECT_NEAR(c.adev_deg_h[i] / std::sqrt(fitted_allan_variance(r.noise, c.tau_s[i])), 1.0,
                  0.02)
          << rec.name << " at " << c.tau_s[i] << " s";
    }
  }
  // Over all records the 95 % intervals hold eq. (17) at least as often as they should.
  EXPECT_GE(inside, 0.9 * compared) << inside << " of " << compared;
}

}  // namespace
}  // namespace foglab::model
