// foglab — the synthetic static-gyro recording (generator.h).
//
// Work is organised in blocks of 2^20 samples handed to the sink, each split
// into sub-chunks of kChunkSamples (a fixed split, so results do not depend
// on the number of threads). Within a block:
//   pass 1 (parallel over sub-chunks): time, temperature, the i.i.d. terms,
//          and every per-sample Markov process (random walk, Gauss-Markov,
//          the fast flicker components) started from ZERO state at the
//          sub-chunk's start; each sub-chunk's end states are kept;
//   carry  (sequential, a few operations per sub-chunk): the true state at
//          each sub-chunk's start, from the carried state of the block;
//   pass 2 (parallel): each Markov process's response to its true start
//          state (constant for the random walk, decaying for the OU
//          processes) is added;
//   slow flicker components (first, parallel over components): exact OU
//          steps at their own interval 2^level samples, summed on a dyadic
//          pyramid; pass 1 adds them interpolated linearly to the sample
//          mid-points.
// Every random number is a pure function of (seed, stream, process, index)
// (generator_internal.h).
#include "foglab/sim/generator.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <exception>
#include <limits>
#include <numbers>
#include <string_view>
#include <thread>

#include "foglab/core/error.h"
#include "foglab/core/numeric.h"
#include "foglab/core/units.h"
#include "generator_internal.h"

namespace foglab::sim {

// ============================================================================
// The generator
// ============================================================================
namespace {

using detail::normal_at;
using detail::normal_of;
using detail::word_at;

constexpr std::size_t kBlockSamples = std::size_t{1} << 20;
constexpr std::size_t kChunk = kChunkSamples;  // 2^16: 16 sub-chunks per block
static_assert(kBlockSamples % kChunk == 0);
static_assert((kBlockSamples >> detail::kFlickerMaxLevel) << detail::kFlickerMaxLevel == kBlockSamples);
constexpr std::size_t kMaxFast = 16;
// Decaying start-state responses are added until rho^k falls below this.
constexpr double kDecayCutoff = 1e-20;

// Process ids of the counter-based generator (never reuse or renumber: the
// bits of every existing seed depend on them).
enum Process : std::uint64_t {
  kWhite = 1,  // the merged per-sample innovation (white noise and more)
  kRandomWalkStep = 2,
  kMarkovStep = 4,
  kMarkovStart = 6,
  kQuantisation = 7,
  kJitter = 8,
  kFlickerComponent = 1000,  // + component index: steps (per sample or per node)
  kFlickerStart = 2000,      // + component index: the stationary start
};

// The largest magnitude of a model coefficient, a bias or a temperature in
// its unit: far beyond any gyro (a navigation FOG's N is 1e-3 deg/h/sqrt(Hz),
// a MEMS one's 1e2), small enough that no sample of a run can overflow.
constexpr double kMaxCoefficient = 1e9;
constexpr double kMaxTemperatureC = 1e4;

void check_nonnegative(std::string_view name, double value, std::string_view unit) {
  if (!(value >= 0.0 && value <= kMaxCoefficient)) {
    throw UsageError(
        fmt::format("{} must be in [0, {:g}] {}, got {}", name, kMaxCoefficient, unit, value));
  }
}

void check_finite(std::string_view name, double value, double limit = kMaxCoefficient) {
  if (!(std::fabs(value) <= limit)) {
    throw UsageError(
        fmt::format("{} must be finite and at most {:g} in magnitude, got {}", name, limit, value));
  }
}

// Every generated sample is finite and within what foglab reads back (a
// model within the limits above could still overflow through a high-degree
// temperature polynomial).
void check_samples(std::int64_t first, const double* rate, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i) {
    if (!(std::fabs(rate[i]) <= kMaxSampleMagnitude)) {
      throw UsageError(
          fmt::format("the model gives a rate of {} at sample {} (beyond {:g} deg/h): its "
                      "options are too large (a temperature coefficient, a bias)",
                      rate[i], first + static_cast<std::int64_t>(i) + 1, kMaxSampleMagnitude));
    }
  }
}

std::int64_t validate(const ErrorModel& m, const TemperatureProfile& t, const GeneratorOptions& o) {
  if (!(o.sample_rate_hz >= kMinSampleRateHz && o.sample_rate_hz <= kMaxSampleRateHz)) {
    throw UsageError(fmt::format("sample_rate_hz must be in [{:g}, {:g}] Hz, got {}",
                                 kMinSampleRateHz, kMaxSampleRateHz, o.sample_rate_hz));
  }
  if (!std::isfinite(o.duration_s) || o.duration_s <= 0.0) {
    throw UsageError(fmt::format("duration_s must be > 0 [s], got {}", o.duration_s));
  }
  const double samples = std::round(o.duration_s * o.sample_rate_hz);
  if (samples < 1.0) {
    throw UsageError(fmt::format(
        "duration_s x sample_rate_hz must give at least 1 sample, got duration_s = {} s at {} Hz",
        o.duration_s, o.sample_rate_hz));
  }
  if (samples > 9e15) {
    throw UsageError(fmt::format("too many samples: duration_s = {} s at {} Hz", o.duration_s,
                                 o.sample_rate_hz));
  }
  for (const NoiseParameter& p : kNoiseParameters) {
    check_nonnegative(p.name, m.noise.*p.value, fmt::format("[{}]", p.unit));
  }
  if (m.noise.gm_sigma > 0.0 && !(m.noise.gm_tc > 0.0)) {
    throw UsageError(fmt::format("gm_tc must be > 0 [s] when gm_sigma > 0 (gm_sigma = {}), got {}",
                                 m.noise.gm_sigma, m.noise.gm_tc));
  }
  check_finite("bias", m.bias);
  check_finite("input_rate", m.input_rate);
  for (std::size_t k = 0; k < m.temp_coefs.size(); ++k) {
    check_finite(fmt::format("temp_coefs[{}]", k), m.temp_coefs[k]);
  }
  check_finite("temperature start_c", t.start_c, kMaxTemperatureC);
  check_finite("temperature span_c", t.span_c, kMaxTemperatureC);
  check_nonnegative("temperature jitter_c", t.jitter_c, "[degC]");
  check_nonnegative("temperature lsb_c", t.lsb_c, "[degC]");
  if (t.kind == TemperatureKind::file) {
    if (t.profile_time_s.empty() || t.profile_time_s.size() != t.profile_temperature_c.size()) {
      throw UsageError(fmt::format(
          "temperature profile: needs equally many (>= 1) times and temperatures, got {} and {}",
          t.profile_time_s.size(), t.profile_temperature_c.size()));
    }
    for (std::size_t i = 0; i < t.profile_time_s.size(); ++i) {
      check_finite(fmt::format("temperature profile time[{}]", i), t.profile_time_s[i]);
      check_finite(fmt::format("temperature profile temperature[{}]", i),
                   t.profile_temperature_c[i], kMaxTemperatureC);
      if (i > 0 && !(t.profile_time_s[i] > t.profile_time_s[i - 1])) {
        throw UsageError(fmt::format("temperature profile: time[{}] = {} s is not after time[{}] = {} s",
                                     i, t.profile_time_s[i], i - 1, t.profile_time_s[i - 1]));
      }
    }
  }
  return static_cast<std::int64_t>(samples);
}

// One fast flicker component (updated every sample, exact average).
struct FastComponent {
  std::uint64_t key = 0;
  double rho = 0, beta = 0, s_state = 0, s_avg_state = 0;
};

// One slow flicker component (exact OU steps every 2^level samples).
struct SlowComponent {
  std::uint64_t key = 0;
  int level = 1;
  double rho = 0, s_step = 0;  // over 2^level samples
  double state = 0;            // at the current block's first node
  std::vector<double> nodes;   // this block's node states
};

class Engine {
 public:
  Engine(const ErrorModel& model, const TemperatureProfile& temperature,
         const GeneratorOptions& options)
      : model_(model), temperature_(temperature), options_(options) {
    samples_ = validate(model, temperature, options);
    fs_ = options.sample_rate_hz;
    h_ = 1.0 / fs_;
    t_ref_ = temperature.reference_c(options.duration_s);
    const auto key = [&](std::uint64_t process) {
      return detail::process_key(options.seed, options.stream, process);
    };
    // Variance of the merged per-sample innovation (see pass_one).
    double innovation_var = model.noise.N * model.noise.N * fs_;
    key_white_ = key(kWhite);
    rw_scale_ = model.noise.K * std::sqrt(h_);
    key_rw_step_ = key(kRandomWalkStep);
    innovation_var += rw_scale_ * rw_scale_ / 12.0;
    if (model.noise.gm_sigma > 0.0) {
      gm_ = detail::ou_step(model.noise.gm_tc, h_);
      key_gm_step_ = key(kMarkovStep);
      innovation_var += model.noise.gm_sigma * model.noise.gm_sigma * gm_.s_avg * gm_.s_avg;
      gm_state_ = model.noise.gm_sigma * normal_at(zig_, key(kMarkovStart), 0);
    }
    quant_step_ = model.noise.Q * std::sqrt(12.0);
    key_quant_ = key(kQuantisation);
    key_jitter_ = key(kJitter);
    if (model.noise.B > 0.0) {
      const detail::FlickerDesign design =
          detail::design_flicker(fs_, static_cast<double>(samples_) * h_);
      double avg_var = 0.0;
      for (std::size_t j = 0; j < design.components.size(); ++j) {
        const auto& c = design.components[j];
        if (c.variance <= 0.0) continue;
        const double sd = model.noise.B * std::sqrt(c.variance);
        const double start = sd * normal_at(zig_, key(kFlickerStart + j), 0);
        if (c.level == 0) {
          const detail::OuStep s = detail::ou_step(c.tc_s, h_);
          FastComponent f;
          f.key = key(kFlickerComponent + j);
          f.rho = s.rho;
          f.beta = s.beta;
          f.s_state = sd * s.s_state;
          f.s_avg_state = sd * s.s_avg_state;
          avg_var += sd * sd * s.s_avg * s.s_avg;
          fast_.push_back(f);
          fast_state_.push_back(start);
        } else {
          SlowComponent s;
          s.key = key(kFlickerComponent + j);
          s.level = c.level;
          const double x = std::ldexp(h_, c.level) / c.tc_s;
          s.rho = std::exp(-x);
          s.s_step = sd * std::sqrt(-std::expm1(-2.0 * x));
          s.state = start;
          slow_.push_back(std::move(s));
          max_level_ = std::max(max_level_, c.level);
        }
      }
      innovation_var += avg_var;
      if (fast_.size() > kMaxFast) throw std::logic_error("flicker bank: too many fast components");
    }
    innovation_sigma_ = std::sqrt(innovation_var);
    const std::size_t chunks = kBlockSamples / kChunk;
    rw_end_.resize(chunks);
    gm_end_.resize(chunks);
    fast_end_.resize(chunks * fast_.size());
    rw_start_.resize(chunks);
    gm_start_.resize(chunks);
    fast_start_.resize(chunks * fast_.size());
  }

  std::int64_t samples() const { return samples_; }

  // Generates samples [first, first + count) (first a multiple of the block
  // length, blocks in order) into the three arrays.
  void block(std::int64_t first, std::size_t count, double* time, double* rate, double* temp) {
    assert(count <= kBlockSamples && first % static_cast<std::int64_t>(kBlockSamples) == 0);
    if (!slow_.empty()) slow_flicker_nodes(first, count);
    const auto chunks = static_cast<std::int64_t>((count + kChunk - 1) / kChunk);
#pragma omp parallel for schedule(dynamic, 1)
    for (std::int64_t c = 0; c < chunks; ++c) {
      const std::size_t begin = static_cast<std::size_t>(c) * kChunk;
      const std::size_t len = std::min(kChunk, count - begin);
      pass_one(static_cast<std::size_t>(c), first + static_cast<std::int64_t>(begin), len,
               time + begin, rate + begin, temp + begin);
      if (!slow_.empty()) add_slow_flicker(begin, len, rate + begin);
    }
    carry(count);
#pragma omp parallel for schedule(dynamic, 1)
    for (std::int64_t c = 0; c < chunks; ++c) {
      const std::size_t begin = static_cast<std::size_t>(c) * kChunk;
      const std::size_t len = std::min(kChunk, count - begin);
      pass_two(static_cast<std::size_t>(c), len, rate + begin);
    }
  }

 private:
  void pass_one(std::size_t chunk, std::int64_t first, std::size_t len, double* time, double* rate,
                double* temp);
  void carry(std::size_t count);
  void pass_two(std::size_t chunk, std::size_t len, double* rate) const;
  void slow_flicker_nodes(std::int64_t first, std::size_t count);
  void add_slow_flicker(std::size_t begin, std::size_t len, double* rate) const;

  const detail::Ziggurat& zig_ = detail::ziggurat();
  ErrorModel model_;
  TemperatureProfile temperature_;
  GeneratorOptions options_;
  std::int64_t samples_ = 0;
  double fs_ = 0, h_ = 0, t_ref_ = 0;
  double innovation_sigma_ = 0;
  std::uint64_t key_white_ = 0;
  double rw_scale_ = 0;
  std::uint64_t key_rw_step_ = 0;
  double rw_state_ = 0;
  detail::OuStep gm_;
  std::uint64_t key_gm_step_ = 0;
  double gm_state_ = 0;
  double quant_step_ = 0;
  std::uint64_t key_quant_ = 0, key_jitter_ = 0;
  std::vector<FastComponent> fast_;
  std::vector<double> fast_state_;
  std::vector<SlowComponent> slow_;
  int max_level_ = 0;
  std::vector<std::vector<double>> pyramid_;
  // Per sub-chunk: end states from zero start (pass 1) and true start states.
  std::vector<double> rw_end_, gm_end_, fast_end_;
  std::vector<double> rw_start_, gm_start_, fast_start_;
};

void Engine::pass_one(std::size_t chunk, std::int64_t first, std::size_t len, double* time,
                      double* rate, double* temp) {
  const auto index = [first](std::size_t k) { return static_cast<std::uint64_t>(first) + k; };
  // Time and temperature.
  for (std::size_t k = 0; k < len; ++k) time[k] = static_cast<double>(first + static_cast<std::int64_t>(k)) / fs_;
  const TemperatureProfile& tp = temperature_;
  switch (tp.kind) {
    case TemperatureKind::constant:
      for (std::size_t k = 0; k < len; ++k) temp[k] = tp.start_c;
      break;
    case TemperatureKind::ramp: {
      const double slope = tp.span_c / options_.duration_s;
      for (std::size_t k = 0; k < len; ++k) temp[k] = tp.start_c + slope * time[k];
      break;
    }
    case TemperatureKind::file: {
      const auto& pt = tp.profile_time_s;
      const auto& py = tp.profile_temperature_c;
      std::size_t hi = static_cast<std::size_t>(std::upper_bound(pt.begin(), pt.end(), time[0]) - pt.begin());
      for (std::size_t k = 0; k < len; ++k) {
        const double t = time[k];
        while (hi < pt.size() && pt[hi] <= t) ++hi;
        if (hi == 0) {
          temp[k] = py.front();
        } else if (hi == pt.size()) {
          temp[k] = py.back();
        } else {
          const std::size_t lo = hi - 1;
          temp[k] = py[lo] + (py[hi] - py[lo]) * ((t - pt[lo]) / (pt[hi] - pt[lo]));
        }
      }
      break;
    }
  }
  if (tp.jitter_c > 0.0) {
    for (std::size_t k = 0; k < len; ++k) temp[k] += tp.jitter_c * normal_at(zig_, key_jitter_, index(k));
  }
  // Systematic part: constant terms, temperature polynomial, ramp.
  const double constant = model_.input_rate + model_.bias;
  const auto& coefs = model_.temp_coefs;
  if (coefs.empty()) {
    for (std::size_t k = 0; k < len; ++k) rate[k] = constant;
  } else {
    for (std::size_t k = 0; k < len; ++k) {
      const double d = temp[k] - t_ref_;
      double p = 0.0;
      for (std::size_t i = coefs.size(); i-- > 0;) p = (p + coefs[i]) * d;
      rate[k] = constant + p;
    }
  }
  // The temperature sensor's step: the reading is rounded, the rate has
  // followed the temperature itself.
  if (tp.lsb_c > 0.0) {
    for (std::size_t k = 0; k < len; ++k) temp[k] = std::round(temp[k] / tp.lsb_c) * tp.lsb_c;
  }
  if (model_.noise.R != 0.0) {
    for (std::size_t k = 0; k < len; ++k) {
      rate[k] += model_.noise.R *
                 ((static_cast<double>(first + static_cast<std::int64_t>(k)) + 0.5) / fs_);
    }
  }
  // The per-sample innovations independent of every state and of each
  // other, merged into one normal: white rate noise, and the parts of the
  // random-walk, Gauss-Markov and fast-flicker interval averages that are
  // independent of their state steps.
  if (innovation_sigma_ > 0.0) {
    for (std::size_t k = 0; k < len; ++k) {
      rate[k] += innovation_sigma_ * normal_at(zig_, key_white_, index(k));
    }
  }
  // Angle quantisation: white angle noise e_k ~ U(-q/2, q/2), rate (e_{k+1} - e_k)/tau0.
  if (quant_step_ > 0.0) {
    double previous = quant_step_ * (detail::uniform_of(word_at(key_quant_, index(0))) - 0.5);
    for (std::size_t k = 0; k < len; ++k) {
      const double next = quant_step_ * (detail::uniform_of(word_at(key_quant_, index(k + 1))) - 0.5);
      rate[k] += (next - previous) * fs_;
      previous = next;
    }
  }
  // Rate random walk from zero state.
  if (rw_scale_ > 0.0) {
    double w = 0.0;
    for (std::size_t k = 0; k < len; ++k) {
      const double xi1 = normal_at(zig_, key_rw_step_, index(k));
      rate[k] += w + rw_scale_ * 0.5 * xi1;
      w += rw_scale_ * xi1;
    }
    rw_end_[chunk] = w;
  }
  // Gauss-Markov from zero state.
  if (model_.noise.gm_sigma > 0.0) {
    const double s = model_.noise.gm_sigma;
    const double a1 = s * gm_.s_state, a21 = s * gm_.s_avg_state;
    double x = 0.0;
    for (std::size_t k = 0; k < len; ++k) {
      const double xi1 = normal_at(zig_, key_gm_step_, index(k));
      rate[k] += gm_.beta * x + a21 * xi1;
      x = gm_.rho * x + a1 * xi1;
    }
    gm_end_[chunk] = x;
  }
  // Fast flicker components from zero state: one normal per component (the
  // averages' conditional parts are in the innovation above).
  if (!fast_.empty()) {
    const std::size_t nf = fast_.size();
    std::array<double, kMaxFast> x{};
    std::array<double, kMaxFast> rho{}, beta{}, ss{}, sa{};
    std::array<std::uint64_t, kMaxFast> keys{};
    for (std::size_t j = 0; j < nf; ++j) {
      rho[j] = fast_[j].rho;
      beta[j] = fast_[j].beta;
      ss[j] = fast_[j].s_state;
      sa[j] = fast_[j].s_avg_state;
      keys[j] = fast_[j].key;
    }
    for (std::size_t k = 0; k < len; ++k) {
      double sum = 0.0;
      for (std::size_t j = 0; j < nf; ++j) {
        const double xi = normal_at(zig_, keys[j], index(k));
        sum += beta[j] * x[j] + sa[j] * xi;
        x[j] = rho[j] * x[j] + ss[j] * xi;
      }
      rate[k] += sum;
    }
    for (std::size_t j = 0; j < nf; ++j) fast_end_[chunk * nf + j] = x[j];
  }
}

void Engine::carry(std::size_t count) {
  const std::size_t chunks = (count + kChunk - 1) / kChunk;
  const std::size_t nf = fast_.size();
  for (std::size_t c = 0; c < chunks; ++c) {
    const double len = static_cast<double>(std::min(kChunk, count - c * kChunk));
    rw_start_[c] = rw_state_;
    rw_state_ += rw_end_[c];
    gm_start_[c] = gm_state_;
    if (model_.noise.gm_sigma > 0.0) gm_state_ = std::pow(gm_.rho, len) * gm_state_ + gm_end_[c];
    for (std::size_t j = 0; j < nf; ++j) {
      fast_start_[c * nf + j] = fast_state_[j];
      fast_state_[j] = std::pow(fast_[j].rho, len) * fast_state_[j] + fast_end_[c * nf + j];
    }
  }
}

void Engine::pass_two(std::size_t chunk, std::size_t len, double* rate) const {
  // An OU state s at the chunk's start adds beta rho^k s to sample k; a
  // random-walk state adds s to every sample. One pass over the chunk for
  // both; the powers rho^k run in four interleaved chains (rho^4 steps).
  const double rw = rw_scale_ > 0.0 ? rw_start_[chunk] : 0.0;
  const bool gm = model_.noise.gm_sigma > 0.0;
  if (rw != 0.0 || gm) {
    std::array<double, 4> term{};
    double rho4 = 0.0;
    std::size_t gm_len = 0;
    if (gm) {
      const double coef = gm_.beta * gm_start_[chunk];
      const double stop = std::fabs(coef) * kDecayCutoff;
      term = {coef, coef * gm_.rho, coef * gm_.rho * gm_.rho, coef * gm_.rho * gm_.rho * gm_.rho};
      rho4 = term[3] == 0.0 ? 0.0 : (gm_.rho * gm_.rho) * (gm_.rho * gm_.rho);
      // Samples until rho^k falls below the cutoff (all of them for slow processes).
      const double log_rho = std::log(gm_.rho);
      gm_len = (coef == 0.0) ? 0
               : log_rho == 0.0 ? len
                                : static_cast<std::size_t>(std::min<double>(
                                      static_cast<double>(len), std::ceil(std::log(stop / std::fabs(coef)) / log_rho) + 4.0));
      gm_len -= gm_len % 4;
    }
    std::size_t k = 0;
    for (; k < gm_len; k += 4) {
      for (std::size_t l = 0; l < 4; ++l) {
        rate[k + l] += rw + term[l];
        term[l] *= rho4;
      }
    }
    if (rw != 0.0) {
      for (; k < len; ++k) rate[k] += rw;
    }
  }
  // Fast flicker components: their responses die out within a few thousand samples.
  const auto add_decay = [&](double rho, double coef) {
    double term = coef;
    const double stop = std::fabs(coef) * kDecayCutoff;
    for (std::size_t k = 0; k < len && std::fabs(term) > stop; ++k) {
      rate[k] += term;
      term *= rho;
    }
  };
  for (std::size_t j = 0; j < fast_.size(); ++j) {
    add_decay(fast_[j].rho, fast_[j].beta * fast_start_[chunk * fast_.size() + j]);
  }
}

void Engine::slow_flicker_nodes(std::int64_t first, std::size_t count) {
  // Node states of each slow component at samples first + n 2^level,
  // n = 0 .. ceil(count / 2^level) (the last is the next block's first).
  const auto nodes_at = [count](int level) {
    const std::size_t step = std::size_t{1} << level;
    return (count + step - 1) / step + 1;
  };
  const auto ns = static_cast<std::int64_t>(slow_.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t i = 0; i < ns; ++i) {
    SlowComponent& s = slow_[static_cast<std::size_t>(i)];
    const std::size_t n = nodes_at(s.level);
    s.nodes.resize(n);
    const std::uint64_t node0 = static_cast<std::uint64_t>(first) >> s.level;
    double x = s.state;
    s.nodes[0] = x;
    for (std::size_t k = 1; k < n; ++k) {
      x = s.rho * x + s.s_step * normal_at(zig_, s.key, node0 + k);
      s.nodes[k] = x;
    }
    if (count == kBlockSamples) s.state = s.nodes[n - 1];
  }
  // Dyadic pyramid: level L holds the sum, on its nodes, of every component
  // of level >= L, each interpolated linearly between its own nodes.
  pyramid_.resize(static_cast<std::size_t>(max_level_) + 1);
  for (int level = max_level_; level >= 1; --level) {
    auto& p = pyramid_[static_cast<std::size_t>(level)];
    const std::size_t n = nodes_at(level);
    p.resize(n);
    if (level < max_level_) {
      const auto& up = pyramid_[static_cast<std::size_t>(level) + 1];
      const auto pairs = static_cast<std::int64_t>(n / 2);
#pragma omp parallel for schedule(static) if (pairs > 8192)
      for (std::int64_t i = 0; i < pairs; ++i) {
        const auto k = static_cast<std::size_t>(2 * i);
        p[k] = up[k / 2];
        p[k + 1] = 0.5 * (up[k / 2] + up[k / 2 + 1]);
      }
      if (n % 2 == 1) p[n - 1] = up[(n - 1) / 2];
    } else {
      std::fill(p.begin(), p.end(), 0.0);
    }
    for (const auto& s : slow_) {
      if (s.level != level) continue;
      for (std::size_t k = 0; k < n; ++k) p[k] += s.nodes[k];
    }
  }
}

void Engine::add_slow_flicker(std::size_t begin, std::size_t len, double* rate) const {
  // Samples: the interpolant at the mid-point k + 1/2 of each sample interval
  // (its average over the interval, the interpolant being linear there).
  const auto& p = pyramid_[1];
  for (std::size_t i = 0; i < len; ++i) {
    const std::size_t k = begin + i;
    const std::size_t n = k >> 1;
    const double frac = (k & 1) ? 0.75 : 0.25;
    rate[i] += p[n] + frac * (p[n + 1] - p[n]);
  }
}

}  // namespace

void generate(const ErrorModel& model, const TemperatureProfile& temperature,
              const GeneratorOptions& options, const std::function<void(const Block&)>& sink) {
  Engine engine(model, temperature, options);
  OutputChain chain(model.output, options.sample_rate_hz, options.seed, options.stream);
  const bool chained = model.output.any();
  const std::int64_t total = engine.samples();
  const std::size_t buffer = std::min<std::size_t>(kBlockSamples, static_cast<std::size_t>(total));
  // Two sets of buffers: while the sink handles block b (on a helper thread,
  // so that writing overlaps generating), block b + 1 is generated.
  std::array<std::array<std::vector<double>, 3>, 2> buffers;
  for (auto& set : buffers) {
    for (auto& v : set) v = large_vector(buffer);
  }
  std::thread sink_thread;
  std::exception_ptr sink_error;
  const auto finish_sink = [&] {
    if (sink_thread.joinable()) sink_thread.join();
    if (sink_error) std::rethrow_exception(sink_error);
  };
  try {
    int which = 0;
    for (std::int64_t first = 0; first < total; first += static_cast<std::int64_t>(kBlockSamples)) {
      const auto count = static_cast<std::size_t>(
          std::min<std::int64_t>(static_cast<std::int64_t>(kBlockSamples), total - first));
      auto& set = buffers[static_cast<std::size_t>(which)];
      engine.block(first, count, set[0].data(), set[1].data(), set[2].data());
      if (chained) chain.apply(first, set[1].data(), count);
      check_samples(first, set[1].data(), count);
      finish_sink();  // the previous block, whose buffers are reused next
      Block block;
      block.first_index = first;
      block.time_s = std::span<const double>(set[0].data(), count);
      block.rate_deg_h = std::span<const double>(set[1].data(), count);
      block.temperature_c = std::span<const double>(set[2].data(), count);
      sink_thread = std::thread([&sink, &sink_error, block] {
        try {
          sink(block);
        } catch (...) {
          sink_error = std::current_exception();
        }
      });
      which = 1 - which;
    }
    finish_sink();
  } catch (...) {
    if (sink_thread.joinable()) sink_thread.join();
    throw;
  }
}

Recording generate(const ErrorModel& model, const TemperatureProfile& temperature,
                   const GeneratorOptions& options) {
  Engine engine(model, temperature, options);
  OutputChain chain(model.output, options.sample_rate_hz, options.seed, options.stream);
  const auto total = static_cast<std::size_t>(engine.samples());
  Recording r;
  r.sample_rate_hz = options.sample_rate_hz;
  r.time_s = large_vector(total);
  r.rate_deg_h = large_vector(total);
  r.temperature_c = large_vector(total);
  for (std::size_t first = 0; first < total; first += kBlockSamples) {
    const std::size_t count = std::min(kBlockSamples, total - first);
    engine.block(static_cast<std::int64_t>(first), count, r.time_s.data() + first,
                 r.rate_deg_h.data() + first, r.temperature_c.data() + first);
    if (model.output.any()) {
      chain.apply(static_cast<std::int64_t>(first), r.rate_deg_h.data() + first, count);
    }
    check_samples(static_cast<std::int64_t>(first), r.rate_deg_h.data() + first, count);
  }
  return r;
}

}  // namespace foglab::sim
