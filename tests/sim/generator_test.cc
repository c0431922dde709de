// The generator's contract: reproducibility (thread count, blocks, seeds and
// streams), the time axis, validation messages, temperature profiles and the
// temperature-dependent bias.
#include "foglab/sim/generator.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <omp.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/sim/error_model.h"
#include "support/files.h"

namespace foglab::sim {
namespace {

using ::testing::HasSubstr;

ErrorModel full_model() {
  ErrorModel m;
  m.noise.N = 0.3;
  m.noise.B = 0.05;
  m.noise.K = 0.01;
  m.noise.R = 1e-4;
  m.noise.Q = 0.02;
  m.noise.gm_sigma = 0.1;
  m.noise.gm_tc = 30.0;
  m.bias = 1.5;
  m.input_rate = 9.7;
  m.temp_coefs = {0.02, -0.001};
  return m;
}

TemperatureProfile ramp(double span_c, double start_c, double jitter_c = 0.0) {
  TemperatureProfile t;
  t.kind = TemperatureKind::ramp;
  t.span_c = span_c;
  t.start_c = start_c;
  t.jitter_c = jitter_c;
  return t;
}

GeneratorOptions options(double fs_hz, double samples, std::uint64_t seed = 7) {
  GeneratorOptions o;
  o.sample_rate_hz = fs_hz;
  o.duration_s = samples / fs_hz;
  o.seed = seed;
  return o;
}

// Runs `f` with the given OpenMP thread count, restoring the previous one.
template <typename F>
auto with_threads(int threads, F f) {
  const int previous = omp_get_max_threads();
  omp_set_num_threads(threads);
  auto result = f();
  omp_set_num_threads(previous);
  return result;
}

Recording collect_blocks(const ErrorModel& m, const TemperatureProfile& t, const GeneratorOptions& o,
                         std::vector<std::int64_t>* firsts = nullptr) {
  Recording r;
  r.sample_rate_hz = o.sample_rate_hz;
  generate(m, t, o, [&](const Block& b) {
    EXPECT_EQ(b.first_index, static_cast<std::int64_t>(r.rate_deg_h.size()));
    EXPECT_LE(b.rate_deg_h.size(), std::size_t{1} << 20);
    EXPECT_EQ(b.time_s.size(), b.rate_deg_h.size());
    EXPECT_EQ(b.temperature_c.size(), b.rate_deg_h.size());
    if (firsts != nullptr) firsts->push_back(b.first_index);
    r.time_s.insert(r.time_s.end(), b.time_s.begin(), b.time_s.end());
    r.rate_deg_h.insert(r.rate_deg_h.end(), b.rate_deg_h.begin(), b.rate_deg_h.end());
    r.temperature_c.insert(r.temperature_c.end(), b.temperature_c.begin(), b.temperature_c.end());
  });
  return r;
}

TEST(Generator, SameSeedGivesIdenticalBitsWhateverThreadsAndBlocks) {
  const ErrorModel m = full_model();
  const TemperatureProfile t = ramp(10.0, 20.0, 0.05);
  const GeneratorOptions o = options(100.0, 3e6);  // three blocks, the last partial
  const Recording two = with_threads(2, [&] { return generate(m, t, o); });
  ASSERT_EQ(two.rate_deg_h.size(), 3000000u);
  std::vector<std::int64_t> firsts;
  const Recording one_blocks = with_threads(1, [&] { return collect_blocks(m, t, o, &firsts); });
  EXPECT_EQ(firsts, (std::vector<std::int64_t>{0, 1 << 20, 2 << 20}));
  const Recording again = with_threads(2, [&] { return generate(m, t, o); });
  EXPECT_TRUE(two.rate_deg_h == one_blocks.rate_deg_h);
  EXPECT_TRUE(two.temperature_c == one_blocks.temperature_c);
  EXPECT_TRUE(two.time_s == one_blocks.time_s);
  EXPECT_TRUE(two.rate_deg_h == again.rate_deg_h);
  EXPECT_TRUE(two.temperature_c == again.temperature_c);
  // Nothing jumps at the block boundaries: the step there is like any other.
  for (const std::size_t b : {std::size_t{1} << 20, std::size_t{2} << 20}) {
    EXPECT_LT(std::fabs(two.rate_deg_h[b] - two.rate_deg_h[b - 1]), 10.0 * 0.3 * std::sqrt(100.0));
  }
}

TEST(Generator, SingleProcessesAreThreadIndependentToo) {
  // Each Markov process alone, so that its carry between sub-chunks is what
  // is compared.
  for (int which = 0; which < 3; ++which) {
    ErrorModel m;
    if (which == 0) m.noise.K = 1.0;
    if (which == 1) {
      m.noise.gm_sigma = 1.0;
      m.noise.gm_tc = 0.5;
    }
    if (which == 2) m.noise.B = 1.0;
    const GeneratorOptions o = options(10.0, 1.5e6);
    const Recording a = with_threads(1, [&] { return generate(m, TemperatureProfile{}, o); });
    const Recording b = with_threads(2, [&] { return generate(m, TemperatureProfile{}, o); });
    EXPECT_TRUE(a.rate_deg_h == b.rate_deg_h) << "process " << which;
  }
}

TEST(Generator, AnExceptionFromTheSinkStopsGenerationAndReachesTheCaller) {
  ErrorModel m;
  m.noise.N = 1.0;
  int calls = 0;
  try {
    generate(m, TemperatureProfile{}, options(10.0, 5e6), [&](const Block& b) {
      ++calls;
      if (b.first_index > 0) throw std::runtime_error("disk full");
    });
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "disk full");
  }
  EXPECT_EQ(calls, 2);
}

TEST(Generator, DifferentSeedsAndStreamsDiffer) {
  const ErrorModel m = full_model();
  const TemperatureProfile t = ramp(10.0, 20.0, 0.05);
  GeneratorOptions o = options(10.0, 1000);
  const Recording base = generate(m, t, o);
  o.seed = 8;
  const Recording other_seed = generate(m, t, o);
  o.seed = 7;
  o.stream = 1;
  const Recording other_stream = generate(m, t, o);
  for (const Recording* r : {&other_seed, &other_stream}) {
    int equal_rate = 0;
    int equal_temp = 0;
    for (std::size_t k = 0; k < base.rate_deg_h.size(); ++k) {
      equal_rate += base.rate_deg_h[k] == r->rate_deg_h[k];
      equal_temp += base.temperature_c[k] == r->temperature_c[k];
    }
    EXPECT_EQ(equal_rate, 0);
    EXPECT_EQ(equal_temp, 0);
  }
}

TEST(Generator, TimeAxisIsIndexOverSampleRate) {
  const Recording r = generate(ErrorModel{}, TemperatureProfile{}, options(3.0, 2.5e6));
  ASSERT_EQ(r.time_s.size(), 2500000u);
  EXPECT_EQ(r.sample_rate_hz, 3.0);
  for (std::size_t k = 0; k < r.time_s.size(); k += 997) {
    EXPECT_EQ(r.time_s[k], static_cast<double>(k) / 3.0);
  }
  EXPECT_EQ(r.time_s.back(), 2499999.0 / 3.0);
  // samples = round(duration * fs)
  GeneratorOptions o;
  o.sample_rate_hz = 10.0;
  o.duration_s = 1.04;
  EXPECT_EQ(generate(ErrorModel{}, TemperatureProfile{}, o).rate_deg_h.size(), 10u);
}

TEST(Generator, NoNoiseGivesTheSystematicPartExactly) {
  ErrorModel m;
  m.bias = 2.0;
  m.input_rate = 15.0;
  m.noise.R = 0.5;
  const Recording r = generate(m, TemperatureProfile{}, options(4.0, 100));
  for (std::size_t k = 0; k < r.rate_deg_h.size(); ++k) {
    // The interval average of R t over [t_k, t_k + tau0].
    EXPECT_NEAR(r.rate_deg_h[k], 17.0 + 0.5 * (static_cast<double>(k) + 0.5) / 4.0, 1e-12);
    EXPECT_EQ(r.temperature_c[k], 25.0);
  }
}

std::string error_message(const ErrorModel& m, const TemperatureProfile& t, const GeneratorOptions& o) {
  try {
    generate(m, t, o, [](const Block&) {});
  } catch (const UsageError& e) {
    return e.what();
  }
  return "no UsageError";
}

TEST(Generator, ValidatesOptionsAndModelNamingParameterAndValue) {
  const TemperatureProfile t;
  GeneratorOptions o = options(10.0, 100);
  o.sample_rate_hz = -2.0;
  EXPECT_THAT(error_message({}, t, o),
              HasSubstr("sample_rate_hz must be in [1e-06, 1e+09] Hz, got -2"));
  o = options(10.0, 100);
  o.duration_s = 0.0;
  EXPECT_THAT(error_message({}, t, o), HasSubstr("duration_s must be > 0 [s], got 0"));
  o.duration_s = 0.01;  // 0.1 sample
  EXPECT_THAT(error_message({}, t, o), HasSubstr("at least 1 sample"));
  o = options(10.0, 100);
  const auto bad = [&](auto set) {
    ErrorModel m;
    set(m);
    return error_message(m, t, o);
  };
  EXPECT_THAT(bad([](ErrorModel& m) { m.noise.N = -1.0; }), HasSubstr("N must be in [0, 1e+09]"));
  EXPECT_THAT(bad([](ErrorModel& m) { m.noise.N = -1.0; }), HasSubstr("got -1"));
  EXPECT_THAT(bad([](ErrorModel& m) { m.noise.B = -0.5; }),
              HasSubstr("B must be in [0, 1e+09] [deg/h], got -0.5"));
  EXPECT_THAT(bad([](ErrorModel& m) { m.noise.K = std::nan(""); }),
              HasSubstr("K must be in [0, 1e+09]"));
  EXPECT_THAT(bad([](ErrorModel& m) { m.noise.R = -3.0; }), HasSubstr("R must be"));
  EXPECT_THAT(bad([](ErrorModel& m) { m.noise.Q = INFINITY; }),
              HasSubstr("Q must be in [0, 1e+09] [deg/h*s], got inf"));
  EXPECT_THAT(bad([](ErrorModel& m) { m.noise.gm_sigma = -1.0; }), HasSubstr("gm_sigma must be"));
  EXPECT_THAT(bad([](ErrorModel& m) { m.noise.gm_sigma = 1.0; }),
              HasSubstr("gm_tc must be > 0 [s] when gm_sigma > 0 (gm_sigma = 1), got 0"));
  EXPECT_THAT(bad([](ErrorModel& m) { m.bias = NAN; }), HasSubstr("bias must be finite"));
  EXPECT_THAT(bad([](ErrorModel& m) {
                m.temp_coefs = {1.0, INFINITY};
              }),
              HasSubstr("temp_coefs[1] must be finite and at most 1e+09 in magnitude, got inf"));
  TemperatureProfile jittery;
  jittery.jitter_c = -0.1;
  EXPECT_THAT(error_message({}, jittery, o), HasSubstr("jitter_c must be in [0, 1e+09]"));
  TemperatureProfile file;
  file.kind = TemperatureKind::file;
  file.profile_time_s = {0.0, 0.0};
  file.profile_temperature_c = {1.0, 2.0};
  EXPECT_THAT(error_message({}, file, o), HasSubstr("time[1] = 0 s is not after time[0] = 0 s"));
  file.profile_time_s = {0.0};
  EXPECT_THAT(error_message({}, file, o), HasSubstr("equally many"));
  // The in-memory overload validates too.
  ErrorModel m;
  m.noise.N = -1.0;
  EXPECT_THROW(generate(m, t, o), UsageError);
}

TEST(Temperature, ConstantProfileWithJitterHasItsMeanAndSpread) {
  TemperatureProfile t;
  t.start_c = 30.0;
  t.jitter_c = 0.2;
  const Recording r = generate(ErrorModel{}, t, options(10.0, 2e5));
  double sum = 0.0;
  double sum2 = 0.0;
  for (const double v : r.temperature_c) {
    sum += v - 30.0;
    sum2 += (v - 30.0) * (v - 30.0);
  }
  const double n = static_cast<double>(r.temperature_c.size());
  EXPECT_NEAR(sum / n, 0.0, 4.0 * 0.2 / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.2, 0.2 * 4.0 / std::sqrt(2.0 * n));
  EXPECT_EQ(t.reference_c(100.0), 30.0);
  // Without jitter: exactly the set point.
  t.jitter_c = 0.0;
  for (const double v : generate(ErrorModel{}, t, options(10.0, 100)).temperature_c) EXPECT_EQ(v, 30.0);
}

TEST(Temperature, RampRunsLinearlyFromStartOverTheRun) {
  const TemperatureProfile t = ramp(10.0, 20.0);
  const GeneratorOptions o = options(2.0, 7200);  // one hour
  const Recording r = generate(ErrorModel{}, t, o);
  EXPECT_EQ(r.temperature_c.front(), 20.0);
  EXPECT_NEAR(r.temperature_c[3600], 25.0, 1e-12);
  EXPECT_NEAR(r.temperature_c.back(), 20.0 + 10.0 * 7199.0 / 7200.0, 1e-12);  // t = duration - tau0
  EXPECT_DOUBLE_EQ(t.reference_c(o.duration_s), 25.0);
  const TemperatureProfile down = ramp(-4.0, 10.0);
  EXPECT_DOUBLE_EQ(down.reference_c(1.0), 8.0);
}

TEST(Temperature, FileProfileInterpolatesAndHoldsItsEnds) {
  TemperatureProfile t;
  t.kind = TemperatureKind::file;
  t.profile_time_s = {10.0, 20.0, 40.0};
  t.profile_temperature_c = {1.0, 3.0, -1.0};
  const Recording r = generate(ErrorModel{}, t, options(10.0, 600));  // 0 .. 59.9 s
  EXPECT_EQ(r.temperature_c[0], 1.0);      // held before the first point
  EXPECT_EQ(r.temperature_c[50], 1.0);     // t = 5 s
  EXPECT_EQ(r.temperature_c[100], 1.0);    // t = 10 s
  EXPECT_NEAR(r.temperature_c[150], 2.0, 1e-12);   // t = 15 s
  EXPECT_NEAR(r.temperature_c[200], 3.0, 1e-12);   // t = 20 s
  EXPECT_NEAR(r.temperature_c[300], 1.0, 1e-12);   // t = 30 s
  EXPECT_NEAR(r.temperature_c[350], 0.0, 1e-12);   // t = 35 s
  EXPECT_EQ(r.temperature_c[500], -1.0);   // held after the last point
  // Time-weighted mean over [0, 60 s]: 10*1 + 10*2 + 20*1 + 20*(-1) = 30 -> 0.5 degC.
  EXPECT_NEAR(t.reference_c(60.0), 0.5, 1e-12);
  // Over [0, 15 s]: 10*1 + 5*1.5 = 17.5 -> 7/6.
  EXPECT_NEAR(t.reference_c(15.0), 17.5 / 15.0, 1e-12);
}

// Solves the 3x3 normal equations of a degree-2 least-squares fit y(x).
std::array<double, 3> quadratic_fit(const std::vector<double>& x, const std::vector<double>& y) {
  double a[3][4] = {};
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double p[3] = {1.0, x[k], x[k] * x[k]};
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) a[i][j] += p[i] * p[j];
      a[i][3] += p[i] * y[k];
    }
  }
  for (int c = 0; c < 3; ++c) {  // Gauss-Jordan with partial pivoting
    int pivot = c;
    for (int r = c + 1; r < 3; ++r) {
      if (std::fabs(a[r][c]) > std::fabs(a[pivot][c])) pivot = r;
    }
    for (int j = 0; j < 4; ++j) std::swap(a[c][j], a[pivot][j]);
    for (int r = 0; r < 3; ++r) {
      if (r == c) continue;
      const double f = a[r][c] / a[c][c];
      for (int j = c; j < 4; ++j) a[r][j] -= f * a[c][j];
    }
  }
  return {a[0][3] / a[0][0], a[1][3] / a[1][1], a[2][3] / a[2][2]};
}

TEST(Temperature, PolynomialFitOfRateAgainstTemperatureRecoversTheCoefficients) {
  ErrorModel m;
  m.bias = 1.25;
  m.temp_coefs = {0.5, -0.02};
  for (const double jitter : {0.0, 0.3}) {  // the jittered reading drives the bias
    const TemperatureProfile t = ramp(10.0, 20.0, jitter);
    const GeneratorOptions o = options(1.0, 3600);
    const Recording r = generate(m, t, o);
    const double t_ref = t.reference_c(o.duration_s);
    EXPECT_DOUBLE_EQ(t_ref, 25.0);
    std::vector<double> d(r.temperature_c.size());
    for (std::size_t k = 0; k < d.size(); ++k) d[k] = r.temperature_c[k] - t_ref;
    const auto c = quadratic_fit(d, r.rate_deg_h);
    EXPECT_NEAR(c[0], 1.25, 1e-9);
    EXPECT_NEAR(c[1], 0.5, 1e-9);
    EXPECT_NEAR(c[2], -0.02, 1e-9);
  }
}

TEST(ParseTemperature, AcceptsEachForm) {
  TemperatureProfile t = parse_temperature("const");
  EXPECT_EQ(t.kind, TemperatureKind::constant);
  EXPECT_EQ(t.start_c, 25.0);
  t = parse_temperature("const:31.5");
  EXPECT_EQ(t.kind, TemperatureKind::constant);
  EXPECT_EQ(t.start_c, 31.5);
  t = parse_temperature("ramp:10");
  EXPECT_EQ(t.kind, TemperatureKind::ramp);
  EXPECT_EQ(t.span_c, 10.0);
  EXPECT_EQ(t.start_c, 25.0);
  t = parse_temperature("ramp:-5@20");
  EXPECT_EQ(t.span_c, -5.0);
  EXPECT_EQ(t.start_c, 20.0);
  EXPECT_DOUBLE_EQ(t.reference_c(3600.0), 17.5);
}

TEST(ParseTemperature, ReadsAProfileFile) {
  test::TempDir dir;
  const auto path = dir.path() / "profile.txt";
  std::ofstream(path) << "# time_s temperature_c\n0 20.0\n\n100, 22.5  # warming\n300\t22.5\n";
  const TemperatureProfile t = parse_temperature("file:" + path.string());
  EXPECT_EQ(t.kind, TemperatureKind::file);
  EXPECT_EQ(t.profile_time_s, (std::vector<double>{0.0, 100.0, 300.0}));
  EXPECT_EQ(t.profile_temperature_c, (std::vector<double>{20.0, 22.5, 22.5}));
  EXPECT_NEAR(t.reference_c(300.0), (100 * 21.25 + 200 * 22.5) / 300.0, 1e-12);
}

TEST(ParseTemperature, RejectsBadSyntaxWithUsageError) {
  for (const char* text : {"", "const:", "const:x", "const:25C", "ramp", "ramp:", "ramp:x",
                           "ramp:10@", "ramp:10@y", "file:", "sine:3", "CONST"}) {
    try {
      parse_temperature(text);
      ADD_FAILURE() << "accepted '" << text << "'";
    } catch (const UsageError& e) {
      EXPECT_THAT(e.what(), HasSubstr("expected 'const', 'const:T', 'ramp:SPAN'")) << text;
      EXPECT_THAT(e.what(), HasSubstr(std::string("got '") + text + "'"));
    }
  }
}

TEST(ParseTemperature, RejectsBadFilesWithDataErrorNamingFileAndLine) {
  test::TempDir dir;
  const auto message = [&](const std::string& name, const std::string& content) -> std::string {
    const auto path = dir.path() / name;
    std::ofstream(path) << content;
    try {
      parse_temperature("file:" + path.string());
    } catch (const DataError& e) {
      return e.what();
    }
    return "no DataError";
  };
  EXPECT_THAT(message("a.txt", "0 20\n1 x\n"),
              HasSubstr("a.txt:2: expected two finite numbers 'time_s temperature_c', got '1 x'"));
  EXPECT_THAT(message("b.txt", "# header\n0 20 3\n"), HasSubstr("b.txt:2: expected two finite numbers"));
  EXPECT_THAT(message("c.txt", "0 20\n5 21\n5 22\n"), HasSubstr("c.txt:3: time 5 s is not after the previous time 5 s"));
  EXPECT_THAT(message("d.txt", "# nothing\n\n"), HasSubstr("d.txt: no (time_s, temperature_c) rows"));
  EXPECT_THAT(message("e.txt", "0 nan\n"), HasSubstr("e.txt:1:"));
  try {
    parse_temperature("file:" + (dir.path() / "missing.txt").string());
    ADD_FAILURE();
  } catch (const DataError& e) {
    EXPECT_THAT(e.what(), HasSubstr("missing.txt: cannot open"));
  }
}

}  // namespace
}  // namespace foglab::sim
