// foglab — the sum at the core of the modified and Hadamard total variances.
//
// Definition (NIST SP 1065, W. J. Riley, "Handbook of Frequency Stability
// Analysis", 2008, sections 5.2.12 and 5.2.14; D. A. Howe, "The total
// deviation approach to long-term characterization of frequency stability",
// IEEE Trans. UFFC 47 (2000)). For a record z_0 .. z_{L-1} and an averaging
// factor m with 1 <= m and 3m <= L, each of the M = L - 3m + 1 subsequences
// w_k = z_{i+k}, k = 0 .. 3m-1, has its slope
//   s = (mean(w_{h2} .. w_{3m-1}) - mean(w_0 .. w_{h1-1})) / h2,
//   h1 = floor(3m/2), h2 = ceil(3m/2) (the distance of the half centres),
// removed, x_k = w_k - s k, and is extended by uninverted even reflection to
// x* = [reverse(x), x, reverse(x)] (9m points). With S(j) the sum of the m
// values x*_j .. x*_{j+m-1},
//   T(i) = sum_{j=0}^{6m-1} (S(j) - 2 S(j+m) + S(j+2m))^2,
// and the total is sum_{i=0}^{M-1} T(i). MTOTVAR = total / (12 m^5 M) on
// phase data (SP1065 eq. 27), HTOTVAR = total / (36 m^3 M) on frequency data
// (eq. 29). A constant or a ramp added to z leaves every T(i) unchanged.
//
// Algorithm. With P the prefix sums of x*, each term is the third difference
// -P(j) + 3P(j+m) - 3P(j+2m) + P(j+3m). Writing j = q m + r (q = 0 .. 5,
// r = 0 .. m-1), the four points stay in fixed reflection blocks, and with Z
// the prefix sums of z the term of piece q is
//   U_q(i + r) + V_q(i - r) + W_q(i) - s_i g_q(r),
// U_q, V_q fixed combinations of Z at three shifts, W_q a combination of
// Z(i) and Z(i + 3m), g_q the (quadratic) response to the ramp. Its square
// summed over (i, r) splits into: sums of U^2 and V^2 with trapezoid
// multiplicities; the cross sum of U(i + r) V(i - r), where for each u the
// partners v = u - 2r form a run of one parity (stride-2 prefix sums); and
// products with the i-only parts, through window sums and first and second
// window moments of U and V (prefix sums). Cost O(L) per factor, independent
// of m (about 80 ns per subsequence on one core; 10^6 points on the full
// octave grid m = 1 .. 2^18 take about 1 s on two cores), and O(m) scratch
// memory per thread (about 250 m bytes); total_modified_sum() uses the direct
// O(M m) method for m <= 5, where that is faster.
//
// Numerical safeguards. Prefix sums of raw data grow like L |z| while each
// term is small, so expanding squares of them would lose every digit.
// Subsequences are therefore processed in blocks of 2m: each block refers
// its own span of data (3m - 1 + 2m samples) to the least-squares line of
// that span (allowed by the ramp invariance) and restarts its prefix sums,
// and moments are taken about block and window centres. Every product then
// involves numbers of the size of (samples spanned) x (local scatter), a
// small multiple of the terms themselves. Block results are summed in a
// fixed order with compensated summation, so the result does not depend on
// the thread count. Lines are evaluated in extended precision: a line
// rounded to double leaves a sawtooth error with a systematic slope, which
// the slope removal of long windows amplifies about sqrt(m) times. Observed
// agreement with the direct method on the same input (white noise, random
// walk, random walk of random walk, L up to 10^6, offset 1e6 plus a ramp):
// relative error below 1e-11.
#pragma once

#include <cstdint>
#include <span>

namespace foglab::stats::detail {

/// total(z, m) as defined above: the blocked O(L) method, or the direct one
/// for m <= 5. Throws UsageError unless 1 <= m and 3m <= z.size().
double total_modified_sum(std::span<const double> z, std::int64_t m);

/// The blocked O(L) method alone, at any m (for tests and timing).
double total_modified_sum_blocked(std::span<const double> z, std::int64_t m);

/// The same, directly: O(M m), each subsequence reflected and summed with
/// prefix sums referred to its own level and slope. The reference for tests.
double total_modified_sum_direct(std::span<const double> z, std::int64_t m);

}  // namespace foglab::stats::detail
