// simulate -> identify round trips of the whole analysis (lab 2).
#include "foglab/model/analysis.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/sim/generator.h"
#include "foglab/sim/lab2_variants.h"
#include "foglab/sim/presets.h"
#include "foglab/sim/sensor_output.h"
#include "foglab/stats/tau_grid.h"
#include "support/expect.h"

namespace foglab::model {
namespace {

bool contains(const std::vector<Message>& notes, const std::string& text) {
  for (const Message& m : notes) {
    const std::string n = m.text();
    if (n.find(text) != std::string::npos) return true;
  }
  return false;
}

struct Lab2Case {
  sim::Lab2Gyro gyro;
  sim::Lab2Run run;
  AnalysisResult result;
  std::vector<double> result_temperature;  // the record's temperature [degC]
};

Lab2Case analyse_lab2(int variant, int gyro, int run, std::uint64_t seed,
                      const AnalysisOptions& options = {}) {
  sim::Lab2Options o;
  o.seed = seed;
  const sim::Lab2Variant v = sim::lab2_variant(variant, o);
  Lab2Case c{v.gyros[gyro], v.gyros[gyro].runs[run], {}, {}};
  sim::Recording rec = sim::generate(c.gyro.model, c.run.temperature, c.run.generator);
  c.result_temperature = rec.temperature_c;
  c.result = analyze(rec.rate_deg_h, rec.temperature_c, rec.sample_rate_hz, options);
  return c;
}

TEST(Analysis, Lab2RampRunRoundTrips) {
  AnalysisOptions lab;
  lab.systematic.degree = 2;  // the lab's polyfit(T, Y, 2)
  for (std::uint64_t seed : {11u, 12u, 13u}) {
    const Lab2Case c = analyse_lab2(1, 0, 1, seed, lab);  // FOG1_1, Y2: 10 degC ramp
    const AnalysisResult& r = c.result;
    ASSERT_TRUE(r.systematic.has_value());
    const SystematicFit& s = *r.systematic;
    EXPECT_EQ(s.degree, 2) << "seed " << seed;
    // The lab's number against the key, within the errors of the terms it sums.
    const double t = s.t_ref_c;
    EXPECT_NEAR(s.lab_constant_term_deg_h, c.run.lab_constant_term_deg_h,
                4.0 * (s.standard_errors[0] + s.standard_errors[1] * t +
                       s.standard_errors[2] * t * t))
        << "seed " << seed;
    EXPECT_FALSE(s.constant_fallback);
    EXPECT_NEAR(s.temperature_span_c, 10.0, 0.2);
    // The coefficients against the truth within 4 standard errors of the
    // true noise model, and the reported errors (from the estimated model)
    // against those.
    const sim::ErrorModel& g = c.gyro.model;
    const std::vector<double> cov =
        coefficient_covariance(c.result_temperature, c.run.generator.sample_rate_hz, s.t_ref_c, 2,
                               {.N = g.noise.N,
                                .B = g.noise.B,
                                .K = g.noise.K,
                                .gm_sigma = g.noise.gm_sigma,
                                .gm_tc = g.noise.gm_tc});
    for (int j = 1; j <= 2; ++j) {
      const double se = std::sqrt(cov[static_cast<std::size_t>(j * 3 + j)]);
      EXPECT_NEAR(s.coefficients[static_cast<std::size_t>(j)],
                  g.temp_coefs[static_cast<std::size_t>(j - 1)], 4.0 * se)
          << "c" << j << " seed " << seed;
      // Never overconfident; conservative (up to the random walk's 95 %
      // bound, analysis.h) when the record cannot resolve the random walk.
      EXPECT_GT(s.standard_errors[static_cast<std::size_t>(j)] / se, 0.6)
          << "c" << j << " seed " << seed;
      EXPECT_LT(s.standard_errors[static_cast<std::size_t>(j)] / se, 2.5)
          << "c" << j << " seed " << seed;
    }
    EXPECT_NEAR(r.noise.model.N, c.gyro.model.noise.N, 0.03 * c.gyro.model.noise.N)
        << "seed " << seed;
    EXPECT_EQ(r.noise.N.status, TermStatus::resolved);
    // The ADEV-minimum bias instability against the key's theoretical one.
    EXPECT_NEAR(r.bias_instability_deg_h / c.run.bias_instability.adev_deg_h, 1.0, 0.3)
        << "seed " << seed;
    EXPECT_GT(r.allan.tau_s.size(), 8u);
    EXPECT_EQ(r.allan.tau_s.size(), r.allan.ci95_low.size());
    // Ten clusters at least in what is reported.
    EXPECT_LE(r.allan.tau_s.back(), r.duration_s / 10.0);
  }
}

// The temperature coefficients' standard errors are the largest over the
// candidate noise models within the interval window, as the noise terms'
// intervals are unions over them. On the lab's FOG2_5 ramp run (seed 1) the
// fit chooses N+GM, leaving out the flicker term B = 1.7 deg/h that the
// Gauss-Markov hump hides, and N+B+GM is within the window: over the hours
// a slope is fitted across, the flicker carries as much variance as the
// hump's tail, and errors under N+GM alone were 13 % below the true model's
// (c1 spread 1.46 times them over 40 seeds, docs/validation.md).
TEST(Analysis, TemperatureErrorsAreTheLargestOverTheNearModels) {
  AnalysisOptions lab;
  lab.systematic.degree = 2;
  const Lab2Case c = analyse_lab2(5, 1, 1, 1, lab);  // FOG2_5, Y2: 10 degC ramp
  ASSERT_TRUE(c.result.systematic.has_value());
  const SystematicFit& s = *c.result.systematic;
  const NoiseFitResult& noise = c.result.noise;
  ASSERT_FALSE(noise.candidates.empty());
  const double window = lab.noise_fit.interval_window;
  auto c1_error = [&](const NoiseModel& model) {
    const std::vector<double> cov = coefficient_covariance(
        c.result_temperature, c.run.generator.sample_rate_hz, s.t_ref_c, 2, model);
    return std::sqrt(cov[4]);
  };
  double largest = c1_error(noise.model);
  bool near_holds_b = false;
  for (const CandidateModel& near : noise.candidates) {
    if (!(near.criterion - noise.candidates.front().criterion <= window)) break;
    largest = std::max(largest, c1_error(near.model));
    near_holds_b |= near.terms.contains(NoiseTerm::flicker);
  }
  // The case the rule is for: the chosen model leaves B out, a near one holds it.
  ASSERT_FALSE(noise.terms.contains(NoiseTerm::flicker)) << to_string(noise.terms);
  ASSERT_TRUE(near_holds_b);
  EXPECT_GT(largest, 1.05 * c1_error(noise.model));
  EXPECT_NEAR(s.standard_errors[1], largest, 1e-6 * largest);
  // And against the truth's: no longer below it by the flicker's share.
  const sim::ErrorModel& g = c.gyro.model;
  const double truth = c1_error(
      {.N = g.noise.N, .B = g.noise.B, .gm_sigma = g.noise.gm_sigma, .gm_tc = g.noise.gm_tc});
  EXPECT_GT(s.standard_errors[1] / truth, 0.9);
}

TEST(Analysis, WienerRandomBiasIsNamedWithEvidence) {
  // The validation's Wiener scenario (docs/validation.md): the random walk
  // meets the flicker plateau at a sixteenth of the usable tau range's end.
  sim::ErrorModel m = sim::find_preset("class-tactical").model;
  const double duration = 12 * 3600.0;
  const double plateau = 2.0 * std::log(2.0) / M_PI * m.noise.B * m.noise.B;
  m.noise.K = std::sqrt(3.0 * plateau / (duration / 10.0 / 16.0));
  int wiener = 0, covered = 0;
  for (std::uint64_t seed : {21u, 22u, 23u, 24u, 25u, 26u}) {
    sim::GeneratorOptions o;
    o.sample_rate_hz = 10.0;
    o.duration_s = duration;
    o.seed = seed;
    sim::Recording rec = sim::generate(m, sim::parse_temperature("const:25"), o);
    const AnalysisResult r = analyze(rec.rate_deg_h, rec.temperature_c, 10.0);
    covered += r.noise.K.ci95_low <= m.noise.K && m.noise.K <= r.noise.K.ci95_high;
    if (r.noise.random_bias_process == RandomBiasProcess::wiener) {
      ++wiener;
      EXPECT_LT(r.evidence.criterion_wiener, r.evidence.criterion_none);
      EXPECT_NE(r.evidence.summary.text().find("Wiener"), std::string::npos);
    }
    EXPECT_TRUE(r.systematic->constant_fallback);
    EXPECT_TRUE(contains(r.notes, "too little"));
  }
  // Right, and covered, in >= 90 % of such records; 3 of 6 or fewer would
  // have a probability below 2 %.
  EXPECT_GE(wiener, 4);
  EXPECT_GE(covered, 4);
}

TEST(Analysis, GaussMarkovRandomBiasIsNamedWithItsCorrelationTime) {
  sim::ErrorModel m = sim::find_preset("class-intermediate").model;
  const double duration = 12 * 3600.0;
  m.noise.gm_tc = duration / 200.0;
  m.noise.gm_sigma = std::sqrt(3.0 * 2.0 * std::log(2.0) / M_PI * m.noise.B * m.noise.B / 0.433);
  int named = 0, covered = 0;
  for (std::uint64_t seed : {31u, 32u, 33u, 34u}) {
    sim::GeneratorOptions o;
    o.sample_rate_hz = 10.0;
    o.duration_s = duration;
    o.seed = seed;
    sim::Recording rec = sim::generate(m, sim::parse_temperature("const:25"), o);
    const AnalysisResult r = analyze(rec.rate_deg_h, rec.temperature_c, 10.0);
    if (r.noise.random_bias_process != RandomBiasProcess::gauss_markov) continue;
    ++named;
    covered += r.noise.gm_tc.ci95_low <= m.noise.gm_tc && m.noise.gm_tc <= r.noise.gm_tc.ci95_high;
    EXPECT_LT(r.evidence.adev_end_slope, 0.5);
  }
  EXPECT_GE(named, 3);
  EXPECT_GE(covered, named - 1);
}

// A Gauss-Markov bias of 100 s on a 1 Hz record (24 h; N 0.2, B 0.01,
// sigma 0.1 deg/h), through the output chain `output`.
AnalysisResult one_hertz_gauss_markov(std::uint64_t seed, const sim::SensorOutput& output = {}) {
  sim::ErrorModel m;
  m.noise.N = 0.2;
  m.noise.B = 0.01;
  m.noise.gm_sigma = 0.1;
  m.noise.gm_tc = 100.0;
  sim::Recording rec =
      sim::generate(m, {}, {.sample_rate_hz = 1.0, .duration_s = 86400.0, .seed = seed});
  if (output.any()) {
    sim::OutputChain chain(output, 1.0, seed, 0);
    chain.apply(0, rec.rate_deg_h.data(), rec.rate_deg_h.size());
  }
  return analyze(rec.rate_deg_h, {}, 1.0);
}

TEST(Analysis, AHundredSampleGaussMarkovProcessIsNoBandwidth) {
  // The bandwidth search's reference has no random bias; the process's
  // hump had passed for a 108-sample moving average over 95 % of N^2 (in
  // the effects study at 1 Hz, one record of three), and a recheck against
  // the Tc fitted beside that filter (306 s) kept it: N 0.91 instead of
  // 0.2. The Tc fitted without any filter drops it.
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const AnalysisResult r = one_hertz_gauss_markov(seed);
    EXPECT_FALSE(r.noise.bandwidth.resolved) << seed;
    EXPECT_NEAR(r.noise.model.N, 0.2, 0.006) << seed;
    EXPECT_NEAR(r.noise.model.gm_tc, 100.0, 25.0) << seed;
    EXPECT_NEAR(r.noise.model.gm_sigma, 0.1, 0.02) << seed;
  }
}

TEST(Analysis, AFilterBesideAHundredSampleGaussMarkovProcessIsFound) {
  // A 0.54 s low-pass on such records: against a reference without the
  // process no bandwidth stood out (in the effects study at 1 Hz, on 2 of
  // 3 records: the first taus were left out instead, N 6-7 % low; the third
  // took a 69-sample moving average, N +70 %). Searched against the
  // process, a bandwidth is found on each (at 1 Hz two taus hold it: the
  // kind is not told apart, and N stays within 8 %; docs/validation.md).
  sim::SensorOutput low_pass;
  low_pass.filter_time_constant_s = 0.54;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const AnalysisResult r = one_hertz_gauss_markov(seed, low_pass);
    EXPECT_TRUE(r.noise.bandwidth.resolved) << seed;
    EXPECT_NEAR(r.noise.model.N, 0.2, 0.016) << seed;
    EXPECT_NEAR(r.noise.model.gm_tc, 100.0, 25.0) << seed;
  }
}

TEST(Analysis, AFilterFoundAgainBesideTheProcessReplacesTheFirst) {
  // A 4-sample moving average on such records: found without the process
  // as a 3-sample one that no candidate follows (every candidate's
  // deviance about 500 on 14 points); the first taus were then left out
  // and no bandwidth kept, N 13-16 % low (the effects study at 1 Hz).
  // Rechecked beside the process the search finds the 4 samples, and that
  // filter now replaces the first.
  sim::SensorOutput average;
  average.moving_average_samples = 4;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const AnalysisResult r = one_hertz_gauss_markov(seed, average);
    ASSERT_TRUE(r.noise.bandwidth.resolved) << seed;
    EXPECT_EQ(r.noise.bandwidth.bandwidth.moving_average_samples, 4) << seed;
    EXPECT_EQ(r.noise.first_taus_left_out, 0) << seed;
    EXPECT_NEAR(r.noise.model.N, 0.2, 0.006) << seed;
    EXPECT_NEAR(r.noise.model.gm_tc, 100.0, 25.0) << seed;
  }
}

TEST(Analysis, OutputRoundingUpToTwoSampleSpreadsIsTakenOutOfN) {
  // An output word of 1.8 sample sd: the rounding (LSB^2/12, 27 % of the
  // sensor's white variance) was counted in N (+12 %) when the rule was a
  // step below the samples' sd. Its share departs from LSB^2/12 by up to
  // 0.9 % as the mean sits on a code or half-way between two (Sheppard's
  // cross term); N's interval takes that in.
  const double n_true = 0.3, fs = 100.0, sd = n_true * std::sqrt(fs), lsb = 1.8 * sd;
  for (const double offset : {0.0, 0.25, 0.5}) {
    sim::ErrorModel m;
    m.noise.N = n_true;
    m.bias = offset * lsb;
    sim::Recording rec =
        sim::generate(m, {}, {.sample_rate_hz = fs, .duration_s = 3600.0, .seed = 7});
    sim::SensorOutput output;
    output.lsb_deg_h = lsb;
    sim::OutputChain chain(output, fs, 7, 0);
    chain.apply(0, rec.rate_deg_h.data(), rec.rate_deg_h.size());
    const AnalysisResult r = analyze(rec.rate_deg_h, {}, rec.sample_rate_hz);
    ASSERT_TRUE(r.output_quantisation.detected) << offset;
    EXPECT_TRUE(r.output_quantisation.noise_like) << offset;
    EXPECT_GT(r.noise.known_white_deg_h_sqrt_hz, 0.0) << offset;
    EXPECT_NEAR(r.noise.model.N, n_true, 0.01 * n_true) << offset;
    EXPECT_LE(r.noise.N.ci95_low, n_true) << offset;
    EXPECT_GE(r.noise.N.ci95_high, n_true) << offset;
  }
}

TEST(Analysis, AResonanceWidensTheFirstTausIntervalsAndSaysSo) {
  // White noise (N 0.3 deg/h/sqrt(Hz), 100 Hz, 1 h) with a second-order
  // resonance at 20 Hz (pole radius 0.97, not in foglab's generator): its
  // terms stay correlated over about 33 samples, and the Allan points it
  // rules vary more than the noise type's edf says (stats/allan.h). The
  // same record without it: no division, no note.
  const double fs = 100.0, r = 0.97, f = 20.0 / fs;
  const double a1 = 2.0 * r * std::cos(2.0 * M_PI * f), a2 = -r * r;
  sim::ErrorModel m;
  m.noise.N = 0.3;
  sim::Recording rec =
      sim::generate(m, {}, {.sample_rate_hz = fs, .duration_s = 3600.0, .seed = 5});
  std::vector<double> resonant = rec.rate_deg_h;
  std::mt19937_64 engine(5);
  std::normal_distribution<double> drive(0.0, 0.25 * 0.3 * std::sqrt(fs));
  double y1 = 0.0, y2 = 0.0;
  for (double& v : resonant) {
    const double y = a1 * y1 + a2 * y2 + drive(engine);
    y2 = y1, y1 = y;
    v += y;
  }
  const AnalysisResult with = analyze(resonant, {}, fs);
  const AnalysisResult without = analyze(rec.rate_deg_h, {}, fs);
  EXPECT_GT(with.allan.edf_reduction[0] * with.allan.edf_reduction[1], 2.0);
  EXPECT_TRUE(contains(with.notes, "Allan terms spread"));
  for (const double x : without.allan.edf_reduction) EXPECT_EQ(x, 1.0);
  EXPECT_FALSE(contains(without.notes, "Allan terms spread"));
}

TEST(Analysis, ATelegraphBiasIsAGaussMarkovProcessNotSteps) {
  // A random telegraph (popcorn) bias of +-0.5 deg/h switching every 100 s
  // on average (not in foglab's generator) on 2 h of N 0.3, B 0.1 at 100
  // Hz: its autocorrelation is 0.25 exp(-|t| / 50 s), a Gauss-Markov
  // process's. The steps' search had levelled 18-20 of its 70 jumps, and
  // the rest, left as a walk, came out as a Wiener bias (K 0.07); now the
  // jumps are left in as the process they are, and said so.
  const double fs = 100.0;
  sim::ErrorModel m;
  m.noise.N = 0.3;
  m.noise.B = 0.1;
  int tc_covered = 0;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    sim::Recording rec =
        sim::generate(m, {}, {.sample_rate_hz = fs, .duration_s = 7200.0, .seed = seed});
    std::mt19937_64 engine(seed);
    std::bernoulli_distribution flip(1.0 / (100.0 * fs));
    double level = 0.5;
    for (double& v : rec.rate_deg_h) {
      if (flip(engine)) level = -level;
      v += level;
    }
    const AnalysisResult r = analyze(rec.rate_deg_h, {}, fs);
    EXPECT_TRUE(r.steps.left_as_noise()) << seed;
    EXPECT_FALSE(r.steps.removed) << seed;
    EXPECT_TRUE(contains(r.notes, "random telegraph")) << seed;
    EXPECT_EQ(r.noise.random_bias_process, RandomBiasProcess::gauss_markov) << seed;
    EXPECT_NEAR(r.noise.model.gm_sigma, 0.5, 0.075) << seed;
    EXPECT_NEAR(r.noise.model.N, 0.3, 0.006) << seed;
    tc_covered += r.noise.gm_tc.ci95_low <= 50.0 && 50.0 <= r.noise.gm_tc.ci95_high;
  }
  EXPECT_GE(tc_covered, 2);  // 95 % intervals: all three hold 50 s in 86 % of runs
}

// A thermal cycle (not a ramp): 20 -> 60 degC at 1 degC/min, then between 60 and -20 degC,
// 8 h; its rate of change is +-1 degC/min, turning at 2400 s and every 4800 s after.
sim::TemperatureProfile thermal_cycle() {
  sim::TemperatureProfile t;
  t.kind = sim::TemperatureKind::file;
  t.profile_time_s = {0.0, 2400.0};
  t.profile_temperature_c = {20.0, 60.0};
  while (t.profile_time_s.back() < 8.0 * 3600.0) {
    t.profile_time_s.push_back(t.profile_time_s.back() + 4800.0);
    t.profile_temperature_c.push_back(t.profile_temperature_c.back() > 0.0 ? -20.0 : 60.0);
  }
  return t;
}

TEST(Analysis, ABiasThatFollowsTheTemperaturesRateIsSaidToAtItsTurns) {
  // A navigation-grade FOG in a thermal cycle whose bias also follows dT/dt (the Shupe
  // effect; not in foglab's generator or its temperature law) by 0.05 deg/h per degC/min:
  // a jump of 0.1 deg/h at every turn of the temperature. The jumps had been taken for a
  // random telegraph noise and left in (K doubled); they are said to be the temperature's
  // rate and levelled, which leaves the noise model of the same record without them.
  const double fs = 10.0;
  sim::ErrorModel m;
  m.noise.N = 0.01;
  m.noise.B = 0.004;
  m.noise.K = 0.0004;
  m.temp_coefs = {0.01};
  const sim::TemperatureProfile cycle = thermal_cycle();
  for (std::uint64_t seed = 1; seed <= 2; ++seed) {
    sim::Recording rec =
        sim::generate(m, cycle, {.sample_rate_hz = fs, .duration_s = 8.0 * 3600.0, .seed = seed});
    const std::vector<double> rec_without = rec.rate_deg_h;
    for (std::size_t k = 0; k < rec.rate_deg_h.size(); ++k) {
      const double t = rec.time_s[k];
      const double rising = t < 2400.0 || static_cast<int>((t - 2400.0) / 4800.0) % 2 == 1;
      rec.rate_deg_h[k] += 0.05 * (rising ? 1.0 : -1.0);  // deg/h per degC/min x +-1 degC/min
    }
    std::vector<double> without = rec_without;
    const AnalysisResult r = analyze(rec.rate_deg_h, rec.temperature_c, fs);
    EXPECT_GE(r.steps.indices.size(), 4u) << seed;
    EXPECT_TRUE(r.steps.at_temperature_turns) << seed;
    EXPECT_TRUE(r.steps.removed) << seed;
    EXPECT_TRUE(contains(r.notes, "dT/dt")) << seed;
    // levelled, the jumps leave the noise model of the record without them
    const AnalysisResult base = analyze(without, rec.temperature_c, fs);
    EXPECT_NEAR(r.noise.model.K / base.noise.model.K, 1.0, 0.1) << seed;
    EXPECT_NEAR(r.noise.model.B / base.noise.model.B, 1.0, 0.05) << seed;
  }
  // The same record with jumps of the same size between the turns: no such note
  sim::Recording rec =
      sim::generate(m, cycle, {.sample_rate_hz = fs, .duration_s = 8.0 * 3600.0, .seed = 3});
  for (std::size_t k = 0; k < rec.rate_deg_h.size(); ++k) {
    const double t = rec.time_s[k];
    rec.rate_deg_h[k] += (t > 4000.0 && t < 9000.0) || (t > 15000.0 && t < 21000.0) ? 0.1 : 0.0;
  }
  const AnalysisResult r = analyze(rec.rate_deg_h, rec.temperature_c, fs);
  EXPECT_GE(r.steps.indices.size(), 2u);
  EXPECT_FALSE(r.steps.at_temperature_turns);
  EXPECT_FALSE(contains(r.notes, "dT/dt"));
  // and a thermostat whose reading jitters by 0.2 degC has no turns for two steps to lie at
  sim::TemperatureProfile thermostat;
  thermostat.jitter_c = 0.2;
  rec = sim::generate(m, thermostat, {.sample_rate_hz = fs, .duration_s = 8.0 * 3600.0, .seed = 4});
  for (std::size_t k = 0; k < rec.rate_deg_h.size(); ++k) {
    rec.rate_deg_h[k] += rec.time_s[k] > 10000.0 && rec.time_s[k] < 20000.0 ? 0.1 : 0.0;
  }
  const AnalysisResult held = analyze(rec.rate_deg_h, rec.temperature_c, fs);
  EXPECT_EQ(held.steps.indices.size(), 2u);
  EXPECT_FALSE(held.steps.at_temperature_turns);
}

TEST(Analysis, AHeavyTailedWhiteNoiseKeepsItsLevel) {
  // White noise drawn from Student's t with 3 degrees of freedom (unit
  // variance kept; not in foglab's generator), N 0.3 deg/h/sqrt(Hz) at
  // 100 Hz for 2 h, with the generator's flicker and random walk: its
  // outliers had been taken for about 750 spikes and N came out 9 % low,
  // and once they were kept, for up to 20 bias steps.
  const double n_true = 0.3, fs = 100.0, dof = 3.0;
  for (std::uint64_t seed = 1; seed <= 2; ++seed) {
    sim::ErrorModel m;
    m.noise.B = 0.1;
    m.noise.K = 0.02;
    sim::Recording rec =
        sim::generate(m, {}, {.sample_rate_hz = fs, .duration_s = 7200.0, .seed = seed});
    std::mt19937_64 engine(seed);
    std::student_t_distribution<double> t(dof);
    const double scale = n_true * std::sqrt(fs) * std::sqrt((dof - 2.0) / dof);
    for (double& v : rec.rate_deg_h) v += scale * t(engine);
    const AnalysisResult r = analyze(rec.rate_deg_h, {}, fs);
    EXPECT_TRUE(r.spikes.heavy_tailed) << seed;
    EXPECT_EQ(r.spikes.count, 0) << seed;
    EXPECT_TRUE(r.steps.indices.empty()) << seed;
    EXPECT_NEAR(r.noise.model.N, n_true, 0.03 * n_true) << seed;
    EXPECT_TRUE(contains(r.notes, "heavy-tailed")) << seed;
    // N's interval takes in the sample variance's scatter under such a
    // noise: t with 3 has no fourth moment, and its sample's excess
    // kurtosis is large (about 300 in 7.2 x 10^5 samples); the Gaussian
    // interval (0.17 % either side) held the truth in 2 of 10 records of
    // bench/heavy_tail_study.py.
    EXPECT_GT(r.spikes.excess_kurtosis, 20.0) << seed;
    EXPECT_GT(r.noise.N.ci95_high - r.noise.N.ci95_low, 0.01 * n_true) << seed;
    EXPECT_LE(r.noise.N.ci95_low, n_true) << seed;
    EXPECT_GE(r.noise.N.ci95_high, n_true) << seed;
  }
}

TEST(Analysis, EveryCandidateModelConverges) {
  // Tactical-grade noise, 2 h at 100 Hz. Candidates far from the data (no
  // white term, say) had swung between two states, or in and out of
  // positive means, until the 200-iteration limit: 3, 2 and 1 of 27, 25
  // and 22 candidates on these records as `foglab generate` makes them,
  // 1 to 4 on every ADIS16405 channel. With the step halved whenever it
  // raises the deviance or leaves the positive means, every candidate
  // converges.
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    sim::ErrorModel m;
    m.noise = {.N = 0.3, .B = 0.1, .K = 0.02};
    sim::Recording rec =
        sim::generate(m, {}, {.sample_rate_hz = 100.0, .duration_s = 7200.0, .seed = seed});
    const AnalysisResult r = analyze(rec.rate_deg_h, {}, 100.0);
    EXPECT_EQ(r.noise.status, FitStatus::converged) << seed;
    EXPECT_GE(r.noise.candidates.size(), 15u) << seed;
    for (const CandidateModel& c : r.noise.candidates) {
      EXPECT_EQ(to_string(c.status), "converged") << seed << " " << to_string(c.terms);
      EXPECT_LT(c.iterations, NoiseFitOptions{}.max_iterations)
          << seed << " " << to_string(c.terms);
    }
    EXPECT_NE(r.noise.message.find("every candidate converged"), std::string::npos)
        << seed << ": " << r.noise.message;
  }
}

TEST(Analysis, WithoutTemperatureTheSystematicStepIsSkippedWithANote) {
  sim::ErrorModel m;
  m.noise.N = 0.3;
  m.noise.B = 0.02;
  sim::GeneratorOptions o;
  o.sample_rate_hz = 10.0;
  o.duration_s = 3600.0;
  sim::Recording rec = sim::generate(m, sim::TemperatureProfile{}, o);
  const AnalysisResult r = analyze(rec.rate_deg_h, {}, 10.0);
  EXPECT_FALSE(r.systematic.has_value());
  EXPECT_TRUE(contains(r.notes, "no temperature"));
  EXPECT_NEAR(r.arw_deg_sqrt_h, 0.3 / 60.0, 0.03 * 0.3 / 60.0);
  // Table 1 from the ADEV minimum and the ARW; the worse class wins.
  EXPECT_EQ(r.verdict.accuracy_class,
            classify(r.bias_instability_deg_h, r.arw_deg_sqrt_h).accuracy_class);
}

// A temperature channel in kelvin is said, not converted: the law's
// coefficients about the mean temperature are the same as in degC (the
// polynomial is in T - T_ref), T_ref and the lab's constant term are not.
TEST(Analysis, ATemperatureInKelvinIsNotedAndTheLawAboutItsMeanHolds) {
  sim::Lab2Options o;
  o.seed = 11;
  const sim::Lab2Variant v = sim::lab2_variant(1, o);
  const sim::Lab2Gyro& gyro = v.gyros[0];
  const sim::Lab2Run& run = gyro.runs[1];  // FOG1's 10 degC ramp
  sim::Recording rec = sim::generate(gyro.model, run.temperature, run.generator);
  std::vector<double> rate = rec.rate_deg_h;
  std::vector<double> kelvin = rec.temperature_c;
  for (double& t : kelvin) t += 273.15;
  const AnalysisResult c = analyze(rec.rate_deg_h, rec.temperature_c, rec.sample_rate_hz);
  const AnalysisResult k = analyze(rate, kelvin, rec.sample_rate_hz);
  EXPECT_FALSE(contains(c.notes, "kelvin"));
  EXPECT_TRUE(contains(k.notes, "likely in kelvin"));
  ASSERT_TRUE(c.systematic && k.systematic);
  ASSERT_EQ(c.systematic->degree, k.systematic->degree);
  for (std::size_t j = 0; j < c.systematic->coefficients.size(); ++j) {
    const double cj = c.systematic->coefficients[j];
    EXPECT_NEAR(k.systematic->coefficients[j], cj, 1e-6 * (std::abs(cj) + 1e-3)) << "c" << j;
  }
  EXPECT_NEAR(k.systematic->t_ref_c - c.systematic->t_ref_c, 273.15, 1e-6);
  EXPECT_NEAR(k.noise.model.N, c.noise.model.N, 1e-6 * c.noise.model.N);
}

// The reported grid (--taus) changes the Allan table, not the model: the
// fit always uses the octave grid. Before, a dense grid counted the same data
// many times over in the fit (and `all` ran for minutes), and a list of three
// taus was all the fit had. Both the path without temperature and the ramp
// run's (the degree chosen on the cubic residual) are checked.
TEST(Analysis, TheReportedGridChangesTheTableNotTheModel) {
  sim::ErrorModel m;
  m.noise = {.N = 0.3, .B = 0.02, .K = 0.004};
  sim::GeneratorOptions o;
  o.sample_rate_hz = 2.0;  // 7,200 samples: `all` reports 720 taus (31 s under ASan at 1,800)
  o.duration_s = 3600.0;
  o.seed = 5;
  const sim::Recording rec = sim::generate(m, sim::TemperatureProfile{}, o);
  std::vector<double> rate = rec.rate_deg_h;  // analyze() consumes its record
  const AnalysisResult octave = analyze(rate, {}, o.sample_rate_hz);
  for (const char* grid : {"decade", "20-per-decade", "all", "1,10,100"}) {
    AnalysisOptions options;
    options.grid = stats::parse_tau_grid(grid);
    rate = rec.rate_deg_h;
    const AnalysisResult r = analyze(rate, {}, o.sample_rate_hz, options);
    EXPECT_EQ(r.noise.terms, octave.noise.terms) << grid;
    EXPECT_EQ(r.noise.model.N, octave.noise.model.N) << grid;
    EXPECT_EQ(r.noise.model.B, octave.noise.model.B) << grid;
    EXPECT_EQ(r.noise.model.K, octave.noise.model.K) << grid;
    EXPECT_EQ(r.noise.points, octave.noise.points) << grid;
    EXPECT_EQ(r.verdict.accuracy_class, octave.verdict.accuracy_class) << grid;
    ASSERT_EQ(r.allan.tau_s.size(), r.allan.ci95_low.size()) << grid;
    if (std::string(grid) == "all") {
      for (std::size_t k = 0; k < r.allan.m.size(); ++k)
        ASSERT_EQ(r.allan.m[k], static_cast<std::int64_t>(k + 1)) << k;
      EXPECT_GT(r.allan.tau_s.size(), 500u);
    } else if (std::string(grid) == "1,10,100") {
      EXPECT_EQ(r.allan.tau_s, (std::vector<double>{1.0, 10.0, 100.0}));
    } else {
      EXPECT_NE(r.allan.tau_s, octave.allan.tau_s) << grid;
    }
    // The table's OADEV is the statistic on its own grid: where a tau is on
    // both grids the deviations agree.
    for (std::size_t k = 0; k < r.allan.tau_s.size(); ++k) {
      const auto at =
          std::find(octave.allan.tau_s.begin(), octave.allan.tau_s.end(), r.allan.tau_s[k]);
      if (at != octave.allan.tau_s.end()) {
        EXPECT_DOUBLE_EQ(r.allan.dev[k], octave.allan.dev[at - octave.allan.tau_s.begin()])
            << grid << " tau " << r.allan.tau_s[k];
      }
    }
  }
  AnalysisOptions decade;
  decade.grid = stats::parse_tau_grid("decade");
  const Lab2Case ramp_octave = analyse_lab2(1, 0, 1, 3);
  const Lab2Case ramp_decade = analyse_lab2(1, 0, 1, 3, decade);
  EXPECT_EQ(ramp_decade.result.noise.terms, ramp_octave.result.noise.terms);
  EXPECT_EQ(ramp_decade.result.noise.model.N, ramp_octave.result.noise.model.N);
  ASSERT_TRUE(ramp_octave.result.systematic.has_value());
  EXPECT_EQ(ramp_decade.result.systematic->degree, ramp_octave.result.systematic->degree);
  EXPECT_NE(ramp_decade.result.allan.tau_s, ramp_octave.result.allan.tau_s);
}

TEST(Analysis, TooShortARecordIsADataErrorThatSaysHowMany) {
  std::vector<double> rate(40, 1.0);
  EXPECT_NE(test::message_of<DataError>([&] { analyze(rate, {}, 10.0); }).find("40 samples"),
            std::string::npos);
}

// A logger that loses every tenth sample leaves 1000 samples in stretches
// of 9: no statistic can be taken over 64 in a row, and the error says why
// (not the PSD's 16, which a caller of analyze() never asked for).
TEST(Analysis, GapsThatLeaveNo64SamplesInARowAreADataErrorThatSaysSo) {
  sim::ErrorModel m;
  m.noise.N = 1.0;
  const std::vector<double> rate =
      sim::generate(m, {}, {.sample_rate_hz = 10.0, .duration_s = 100.0, .seed = 3}).rate_deg_h;
  ASSERT_EQ(rate.size(), 1000u);
  std::vector<Gap> gaps;
  for (std::int64_t k = 9; k < 1000; k += 9) gaps.push_back({k, 1});
  std::vector<double> copy = rate;
  const std::string why = test::message_of<DataError>([&] { analyze(copy, {}, 10.0, {}, gaps); });
  EXPECT_NE(why.find("into 112 stretches, the longest 9 samples"), std::string::npos) << why;
  EXPECT_NE(why.find("at least 64 in a row"), std::string::npos) << why;
  // One long stretch is enough to go on (the first 50 gaps, then 550 samples).
  gaps.resize(50);
  copy = rate;
  EXPECT_NO_THROW(analyze(copy, {}, 10.0, {}, gaps));
}

TEST(WorkQueue, KeepGoingRunsEveryJobAndReturnsEachFailure) {
  std::vector<std::atomic<int>> runs(40);
  auto job = [&](std::size_t k) {
    ++runs[k];
    if (k % 7 == 3) throw DataError("job " + std::to_string(k));
  };
  const auto errors = run_work_queue(runs.size(), job, 3, OnFailure::keep_going);
  ASSERT_EQ(errors.size(), runs.size());
  for (std::size_t k = 0; k < runs.size(); ++k) {
    EXPECT_EQ(runs[k], 1) << k;  // each job once
    EXPECT_EQ(errors[k] != nullptr, k % 7 == 3) << k;
  }
  try {
    std::rethrow_exception(errors[10]);
  } catch (const DataError& e) {
    EXPECT_STREQ(e.what(), "job 10");
  }
}

TEST(WorkQueue, StopStartsNoJobAfterAFailure) {
  std::vector<int> runs(10, 0);
  auto job = [&](std::size_t k) {
    ++runs[k];
    if (k == 2) throw UsageError("bad");
  };
  const auto errors = run_work_queue(runs.size(), job, 1, OnFailure::stop);
  EXPECT_EQ(runs, (std::vector<int>{1, 1, 1, 0, 0, 0, 0, 0, 0, 0}));  // one worker: in order
  EXPECT_NE(errors[2], nullptr);
  EXPECT_EQ(std::count(errors.begin(), errors.end(), nullptr), 9);
}

TEST(WorkQueue, AnalyzeRecordsNamesTheRecordThatFailed) {
  auto load = [](std::size_t k) {
    RecordToAnalyse r;
    r.rate_deg_h.assign(k == 1 ? 5 : 4000, 1.0);  // record 1 is too short
    for (std::size_t i = 0; i < r.rate_deg_h.size(); ++i) r.rate_deg_h[i] += std::sin(i * 1.7);
    r.sample_rate_hz = 10.0;
    return r;
  };
  try {
    analyze_records(3, load, {}, 2, {},
                    [](std::size_t k) { return "record " + std::to_string(k); });
    FAIL() << "record 1 is too short";
  } catch (const DataError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("record 1: ", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace foglab::model
