// foglab — chi-square confidence intervals of a deviation.
//
// With edf degrees of freedom, edf * s^2 / sigma^2 is chi-square distributed
// (NIST SP 1065 section 5.3.1, eq. 45), so the interval at confidence p is
//   s * sqrt(edf / chi2_{(1+p)/2}(edf))  <=  sigma  <=  s * sqrt(edf / chi2_{(1-p)/2}(edf)).
// Quantiles from Boost.Math.
#pragma once

namespace foglab::stats {

/// The one-sigma confidence level, erf(1/sqrt(2)) = 0.682689...
inline constexpr double kConfidence68 = 0.6826894921370859;
inline constexpr double kConfidence95 = 0.95;

struct Interval {
  double low = 0.0;
  double high = 0.0;
};

/// Interval of a deviation `dev` with `edf` degrees of freedom at confidence
/// `p` in (0, 1). NaN bounds when edf is not a positive finite number.
Interval chi2_interval(double dev, double edf, double p);

/// The chi-square quantile of probability `p` in (0, 1) with `dof` > 0
/// degrees of freedom.
double chi2_quantile(double dof, double p);

/// The edf whose interval at confidence `p` has the width of [low, high]
/// around `dev` (log ratio high/low, the inverse of chi2_interval(): a
/// printed table's bounds give back its edf). NaN unless 0 < low < dev <
/// high; the edf is sought in [0.1, 1e9].
double edf_from_interval(double dev, double low, double high, double p);

}  // namespace foglab::stats
