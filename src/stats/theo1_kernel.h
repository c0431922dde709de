// foglab — the sum at the core of the Theo1 variance.
//
// Definition (NIST SP 1065, W. J. Riley, "Handbook of Frequency Stability
// Analysis", 2008, section 5.2.15, eq. 30; D. A. Howe and T. N. Tasset,
// "Theo1: characterization of very long-term frequency stability", Proc.
// EFTF 2004). For phase data x_0 .. x_{N-1} and an even averaging factor m,
// 2 <= m <= N - 1, with M = N - m and h = m / 2,
//   theo1_sum(x, m) = sum_{i=0}^{M-1} sum_{d=0}^{h-1}
//                       (x_i - x_{i-d+h} + x_{i+m} - x_{i+d+h})^2 / (h - d).
// Theo1 = theo1_sum / (0.75 M m^2 tau0^2) at tau = 0.75 m tau0. Writing
// k = h - d (1 .. h) and g = m - k, the term is e_{i,k}^2 / k with
//   e_{i,k} = x_i - x_{i+k} - x_{i+g} + x_{i+m},
// which a constant or a ramp added to x leaves unchanged.
//
// Algorithm. Expanding the square, S_k = sum_i e_{i,k}^2 is a combination
// of window energies E(a) = sum_{i<M} x_{i+a}^2 (prefix sums) and windowed
// lag products sum_{i<M} x_{i+a} x_{i+a+L}. Each of those is the record's
// autocorrelation R(L) less a head and a tail: for the pairs (i, i+k),
// (i, i+g), (i+k, i+m) and (i+g, i+m) these are the autocorrelations Rh, Rt
// of the first and of the last m samples, and for the pair (i+k, i+g)
// (lag L = m - 2k) the "triangle" correlations
//   T(L) = sum_{p < (m - L)/2} s_p s_{p+L}
// of the first m samples and of the last m samples reversed. So
//   S_k = E(0) + E(k) + E(g) + E(m) + 2 [R(m) + R(m-2k) - 2R(k) - 2R(g)
//         + Rh(k) + Rh(g) + Rt(k) + Rt(g) - Th(m-2k) - Tt(m-2k)],
// all k at once from a few FFT correlations (FFTW): R by one real transform,
// Rh and Rt by transforms of length about 2m, and each triangle by divide
// and conquer (the triangle p + q < n splits into a rectangle, one FFT
// cross-correlation, and two triangles of half size; direct below 64).
// Cost per factor: O(N log m + (N/m) m log^2 m) = O(N log^2 m) (the record
// is processed in blocks, below), independent of the O(N m) of the direct
// sum; theo1_sums() uses the direct method wherever it needs at most 192
// terms per sample (m <= 384, and m close to N), where it is faster.
//
// Numerical safeguards. The expansion cancels: its pieces are of the size of
// sum x^2 over the span while S_k is the size of the (much smaller) second
// differences, and FFT correlation has an absolute error of a few eps times
// sum x^2. For red noise a whole record's phase grows like N^{3/2} (random
// walk FM), so a global expansion would lose (N/m)^3 eps relatively. The
// positions i are therefore split into blocks of at most 4m; each block
// refers its own span (block + m samples) to that span's least-squares line,
// evaluated with an exact product (fma) and an exact difference so that no
// large offset or slope leaks rounding into the residual, and is expanded on
// its own. The residuals then span about 5^{3/2} times the differences they
// feed, whatever N, and combinations are formed in long double. Block sums
// are added in a fixed order, and every correlation is computed by the same
// code whichever thread runs it, so the result does not depend on the
// thread count. Observed agreement with the direct method (harness): relative
// error 1e-14 or better up to m = N/2 for white PM, white FM and random walk
// FM, also with an offset of 1e9 and a slope of 1e4 per sample added (N up to
// 10^6); up to 1e-11 at m close to N, where only a few positions remain
// (theo1_sums() uses the direct method there).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace foglab::stats::detail {

/// theo1_sum(x, m) for every factor in `factors` (even, 2 <= m <= N - 1,
/// ascending): the blocked FFT method, or the direct one where that needs at
/// most 192 terms per sample. Throws UsageError on an invalid factor.
std::vector<double> theo1_sums(std::span<const double> x, std::span<const std::int64_t> factors);

/// The blocked FFT method alone, at any valid m (for tests and timing).
double theo1_sum_blocked(std::span<const double> x, std::int64_t m);

/// The same, directly: O((N - m) m / 2) terms, in parallel over fixed chunks
/// of positions. The reference for tests.
double theo1_sum_direct(std::span<const double> x, std::int64_t m);

}  // namespace foglab::stats::detail
