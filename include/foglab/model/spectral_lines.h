// foglab — finding the narrow-band disturbances of a record (spectral lines,
// core/spectral_line.h) in its Welch PSD, so that the noise fit can take
// their Allan variance as known instead of bending its terms around them.
//
// The noise floor is the running median of the PSD over 0.2 decade either
// side (taken every 1/20 decade, interpolated log-linearly). A line is a run
// of bins (gaps of up to two bins closed) where the PSD, averaged over 0.5 %
// of f, stands more than 3 times above the floor, 4 times at its highest,
// and whose excess over the floor is more than 10 times its own standard
// error (the floor times sqrt(bins / segments): a Welch average of K
// segments scatters by about 1/sqrt(K)). Runs of high bins start from the
// 17th bin (17 resolutions) up: there the +-0.2 decade window holds 15 bins
// or more, and a sinusoid's 4 (the Hann window's main lobe) do not lift
// its median. A line found extends over its skirts: the
// neighbouring bins whose averaged PSD stays more than four of its standard
// errors (sqrt(2 / (K bins averaged))) above the floor and holds at least
// 1/1000 of the line's highest excess (below that it is the floor's error:
// near a moving average's null the floor runs 30-50 % off the PSD), so a
// broad resonance's flanks are part of it, with their own frequencies (on the
// ADIS16405 z axes the line grows from 2.5-3.3 Hz to 9.6-10.1 Hz wide, and
// the bins hold three quarters of a resonance's variance instead of half).
// A line falls on both sides: its highest averaged bin stands three times
// above the PSD where its skirts end on either side. A steep roll-off of the
// output filter stands above the running median on one side only (the
// passband goes on at its level) and is not a line (a 2-sample average
// before a Butterworth at 15 Hz had given a 24 Hz wide "line" at 17 Hz).
// The line's bins carry their excess, 2 (S - floor) df each (both signs of
// f). A resonance hump a few hertz wide is a line in this sense: its bins
// are summed as they are.
//
// A hump wider than about a third of its frequency fills most of the
// +-0.2 decade window and lifts the median with it (the ADIS16405 z axes'
// 20 Hz resonance, with every fourth sample kept, aliases to a hump at
// 5 Hz of a 25 Hz record, 3-4 Hz wide, 2.6-5 times the floor: the narrow
// floor lay inside it). A second pass looks for such humps over the median
// of +-0.5 decade: runs of bins 2 times above that floor, 2.5 times at the
// highest, at least 0.15 of their frequency wide, falling on both sides to
// half their peak, with the same significance and skirts, not overlapping
// a line of the first pass (which keeps every narrow line as it was), and
// with the PSD beside them (as far out as they are wide, in bands of 1/100
// decade) at half the floor or more: a hump on the noise floor returns to
// it, a moving average's side lobe falls into the average's nulls. It
// searches from 64 resolutions up: over +-0.5 decade the median of a steep
// low-frequency spectrum (a random walk's 1/f^2) lies well under the PSD.
//
// Slow lines. A sinusoid of a few hundredths of a hertz (a thermal
// chamber's or a room's control cycle, a rate table's hunting) bends the
// Allan deviation where the bias instability and the random bias are read,
// with a hump at 0.37 / f that a Gauss-Markov term follows (a 0.01 Hz line
// of 0.35 deg/h rms on a tactical FOG: a "Gauss-Markov random bias" of
// Tc 42 s, B and K lost). The record's Welch PSD starts its search at 17
// resolutions (0.013 Hz for 2 h at 100 Hz with the automatic segments of
// N/4 to N/8); below that the narrow pass is made once more on a PSD with
// segments twice as long or longer (the largest power of two up to half the
// longest stretch, at most 2^21 samples: 3 to 6 segments, more where that
// cap binds; from 0.0065 Hz, 47 periods in a 2 h record), for lines that
// start below the first PSD's search. That PSD is taken of the record's
// means over blocks that leave 4096 to a segment (its band lies far below
// their Nyquist frequency): a pass over the samples and short FFTs, where
// the full segments had cost 0.3 s on 10^7 samples. Its lines keep their
// variance (SpectralLine::takes_variance_scale).
//
// A slow line, that PSD's or a narrow line of the record's own PSD below
// 1/8 of the block means' rate (0.195 Hz for 2 h at 100 Hz; a block mean
// passes it with 97 % of its amplitude or more, which the fit takes out),
// is then taken again as the least-squares sinusoid of those block means
// (a constant beside it; the frequency searched over +-2 / T and half the
// line's width around the bins' centre, T the record's span). When that
// sinusoid holds most of the line's variance (0.8 of it or more), leaves
// no other sinusoid in that band of 3 % of its variance and 10 times the
// band's median (an amplitude that changes over the record puts sidebands
// there), and the line is not one
// of a harmonic series, it is taken out of the record before
// the Allan variance (remove_sinusoids(), SpectralLine::removed_from_record). A periodic
// disturbance that is not one sinusoid (a heater's square wave, a triangle wave: a harmonic series
// whose lowest line is such a sinusoid, or that line alone with a harmonic 2 to 5 standing out of
// the noise) is taken out as a whole, its harmonics up to 0.3 of the block means' rate
// (SpectralLine::harmonics; the series' other lines are dropped). The Welch bins give a
// strong line's variance to within about 6 %, and a Gauss-Markov hump at the line's taus took that
// error: a 0.01 Hz line three times the random bias left Tc 28.6 % off (median of 10 records,
// against 9.2 % without the line) with the line's Allan variance taken as known. Taken out, the
// record's Allan variance is that of the noise less its part at the line's frequency (two degrees
// of freedom of hundreds of thousands), and the terms come out as without the line (Tc 6.8 %). A
// line that is not periodic (a drifting period, a changing amplitude, a narrow random resonance)
// keeps its bins and its Allan variance.
#pragma once

#include <span>
#include <vector>

#include "foglab/core/gaps.h"
#include "foglab/core/spectral_line.h"
#include "foglab/stats/psd.h"

namespace foglab::model {

/// The lines of `psd` (two-sided, stats::welch_psd()), strongest first, at
/// most `max_lines`.
std::vector<SpectralLine> find_spectral_lines(const stats::PsdResult& psd,
                                              std::size_t max_lines = 8);

/// The lines of `rate` (sampled at `sample_rate_hz`, with `gaps`) whose
/// Welch PSD is `psd`: those of find_spectral_lines(psd) and the slow ones
/// of the long-segment PSD below its search, strongest first, at most
/// `max_lines`.
std::vector<SpectralLine> find_spectral_lines(std::span<const double> rate, double sample_rate_hz,
                                              const stats::PsdResult& psd,
                                              std::span<const Gap> gaps = {},
                                              std::size_t max_lines = 8);

/// Subtracts from `rate` (sampled at `sample_rate_hz`, with `gaps`) the
/// sinusoid of every line of `lines` that is removed_from_record.
void remove_sinusoids(std::span<double> rate, double sample_rate_hz, std::span<const Gap> gaps,
                      std::span<const SpectralLine> lines);

/// Adds them (the inverse of remove_sinusoids()).
void add_sinusoids(std::span<double> rate, double sample_rate_hz, std::span<const Gap> gaps,
                   std::span<const SpectralLine> lines);

/// The periodic disturbances that are not one sinusoid (lines with
/// harmonics) in the slow band of `rate`'s block means, as
/// find_spectral_lines() would take them out of the record: looked for
/// before the bias steps, whose search takes a square wave's edges for
/// steps (a 0.5 deg/h square wave at 0.01 Hz over tactical-grade noise:
/// 4 of its 144 edges levelled out, which left the record's level 1.5
/// deg/h off for an hour).
std::vector<SpectralLine> find_periodic_disturbances(std::span<const double> rate,
                                                     double sample_rate_hz,
                                                     std::span<const Gap> gaps = {});

}  // namespace foglab::model
