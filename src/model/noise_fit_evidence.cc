// foglab — noise-model fit, step 3: the random-bias evidence
// (noise_fit_internal.h).
#include "noise_fit_internal.h"

namespace foglab::model::detail {

void collect_random_bias_evidence(std::span<const SubsetFit> fits, double penalty,
                                  NoiseFitResult& r) {
  for (const SubsetFit& f : fits) {  // sorted by criterion
    const bool has_k = f.terms.contains(NoiseTerm::random_walk);
    const bool has_gm = f.terms.contains(NoiseTerm::gauss_markov);
    if (!has_k && !has_gm && !r.has_candidate_without_random_bias) {
      r.best_without_random_bias = candidate(f, penalty);
      r.has_candidate_without_random_bias = true;
    }
    if (has_k && !has_gm && !r.has_wiener_candidate) {
      r.best_wiener = candidate(f, penalty);
      r.has_wiener_candidate = true;
    }
    if (has_gm && !r.has_gauss_markov_candidate) {
      r.best_gauss_markov = candidate(f, penalty);
      r.has_gauss_markov_candidate = true;
    }
  }
  r.random_bias_process = RandomBiasProcess::none;
  if (fits.empty()) return;
  const NoiseTermSet chosen = fits.front().terms;
  if (chosen.contains(NoiseTerm::gauss_markov)) {
    r.random_bias_process = RandomBiasProcess::gauss_markov;
  } else if (chosen.contains(NoiseTerm::random_walk)) {
    r.random_bias_process = RandomBiasProcess::wiener;
  }
}

}  // namespace foglab::model::detail
