// foglab — equivalent degrees of freedom of Allan-family estimates.
//
// The chi-square confidence interval of a variance estimate needs its
// equivalent degrees of freedom (edf). foglab uses:
//   * Greenhall's general algorithm for variances built on finite
//     differences (C. A. Greenhall and W. J. Riley, "Uncertainty of
//     stability variances based on finite differences", Proc. 35th PTTI
//     Meeting, 2003; also NIST SP 1065 section 5.3.3): ADEV and OADEV (d = 2),
//     MDEV and TDEV (d = 2, modified), HDEV and OHDEV (d = 3). It is exact
//     for power-law noise up to a short sum, with the paper's Tables 1-3 for
//     the asymptotic cases;
//   * for TOTDEV, NIST SP 1065 Table 12: edf = b (T/tau) - c for white,
//     flicker and random-walk FM, with T/tau = N/m; Greenhall's OADEV edf for
//     the phase-noise types;
//   * for MTOTDEV and TTOTDEV, edf = b (T/tau) - c from m = 10, T/tau = N/m,
//     with SP 1065's b, c for white PM, flicker FM and random-walk FM and
//     Stable32's (larger) effective b, c for white FM and flicker PM (edf.cc);
//     the MDEV edf below m = 10;
//   * for Theo1, Howe and Peppler's edf fits (theo1_edf());
//   * for HTOTDEV, SP 1065's edf = (T/tau) / (b0 + b1 tau/T) for white and
//     flicker FM from m = 16; the OHDEV edf elsewhere (Stable32's bounds
//     below m = 16 imply 10-35 % larger edf: bounds within 1 % all the same).
#pragma once

#include <cstdint>
#include <span>

namespace foglab::stats {

/// The stride of the estimate's terms: 1 sample (overlapping) or m.
enum class Stride { overlapping, non_overlapping };
/// Plain differences of m-averages, or the modified (phase-averaged) form.
enum class Filter { plain, modified };

/// Which finite-difference variance: d = 2 for the Allan family, 3 for the
/// Hadamard; the defaults are the overlapping Allan variance (OADEV).
struct DifferenceVariance {
  int order = 2;  ///< d: 1, 2 (Allan) or 3 (Hadamard)
  Stride stride = Stride::overlapping;
  Filter filter = Filter::plain;
};

/// Greenhall's edf for a finite-difference variance: alpha the noise
/// exponent (+2 .. -4) with alpha + 2 d > 1, m the averaging factor, n_phase
/// the number of phase points. Returns NaN when the case is outside the
/// algorithm's domain.
double greenhall_edf(int alpha, std::int64_t m, std::int64_t n_phase,
                     const DifferenceVariance& variance = {});

/// The edf of a variance pooled over contiguous stretches of
/// `segment_points` phase points each (core/gaps.h): the sum of the
/// stretches' greenhall_edf() over those long enough for m (NaN if none is).
double pooled_edf(int alpha, std::int64_t m, std::span<const std::int64_t> segment_points,
                  const DifferenceVariance& variance = {});

/// edf of TOTDEV (SP1065 Table 12, Greenhall's OADEV edf for alpha > 0).
double totdev_edf(int alpha, std::int64_t m, std::int64_t n_phase);

/// The same pooled over contiguous stretches, as pooled_edf().
double pooled_totdev_edf(int alpha, std::int64_t m, std::span<const std::int64_t> segment_points);

/// edf of MTOTDEV and TTOTDEV (see above); NaN outside alpha = +2 .. -2.
double mtotdev_edf(int alpha, std::int64_t m, std::int64_t n_phase);
/// edf of HTOTDEV (see above).
double htotdev_edf(int alpha, std::int64_t m, std::int64_t n_phase);
/// edf of Theo1 at even factor m (tau = 0.75 m tau0), Howe and Peppler's
/// fits for alpha = +2 .. -2; NaN outside them (and for random-walk FM
/// beyond m ~ 0.84 N, where the fit turns negative).
double theo1_edf(int alpha, std::int64_t m, std::int64_t n_phase);
/// Riley's HTOTDEV bias, the expected HTOTVAR / HVAR for noise alpha at
/// factor m (1 at m = 1, where HTOTDEV is OHDEV, and for phase noise).
double htotdev_bias(int alpha, std::int64_t m);

/// The same pooled over contiguous stretches, as pooled_edf().
double pooled_mtotdev_edf(int alpha, std::int64_t m, std::span<const std::int64_t> segment_points);
double pooled_htotdev_edf(int alpha, std::int64_t m, std::span<const std::int64_t> segment_points);
double pooled_theo1_edf(int alpha, std::int64_t m, std::span<const std::int64_t> segment_points);

}  // namespace foglab::stats
