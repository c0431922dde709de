#include "foglab/io/sample.h"

#include <cmath>
#include <random>

namespace foglab::io {

Series builtin_sample() {
  using S = BuiltinSample;
  const auto count = static_cast<std::size_t>(S::kDurationS * S::kSampleRateHz);
  const double dt_s = 1.0 / S::kSampleRateHz;
  // White rate noise of density N has per-sample sigma N sqrt(fs); a rate
  // random walk of intensity K steps by K sqrt(dt) per sample.
  const double white_sigma = S::kWhiteN * std::sqrt(S::kSampleRateHz);
  const double walk_step = S::kRandomWalkK * std::sqrt(dt_s);
  std::mt19937_64 rng(S::kSeed);
  std::normal_distribution<double> normal(0.0, 1.0);
  Series series;
  series.path = "(built-in sample)";
  series.channel = "Y1";
  series.sample_rate_hz = S::kSampleRateHz;
  series.sample_rate_source = SampleRateSource::builtin;
  series.available_channels = {"Y1"};
  series.variables = series.available_channels;
  series.values.resize(count);
  double walk = 0.0;
  for (auto& v : series.values) {
    walk += walk_step * normal(rng);
    v = S::kBiasDegH + walk + white_sigma * normal(rng);
  }
  return series;
}

}  // namespace foglab::io
