"""AllanTools's calling conventions on foglab's statistics.

``foglab.compat.oadev(data, rate=1.0, data_type="phase", taus=None)`` and the other functions
here take AllanTools's arguments and return its tuple ``(taus, devs, errors, ns)``, so that a
script switches by its import line::

    import foglab.compat as allantools

Conventions kept (AllanTools 2024.06, allantools.py):

- ``data_type`` is ``"phase"`` by default, as in AllanTools; ``"freq"`` is fractional
  frequency (for a gyro: rate), integrated to phase by the sample interval;
- ``taus``: None or ``"octave"`` (m = 1, 2, 4, ... up to the phase record's length),
  ``"decade"`` (1, 2, 4, 10, 20, 40, ...), ``"all"``, ``"log10"``, or seconds; each becomes
  m = round(tau * rate), kept when 0 < m < the number of phase points, sorted, without
  duplicates;
- taus at which the statistic has no term are left out, and so are those with one term
  (AllanTools's ``remove_small_ns``);
- ``errors`` are AllanTools's simple ones, ``devs / sqrt(ns)``; foglab's own 68/95 %
  intervals from the edf are in ``foglab.allan``.

Differences that remain: ``ns`` is the number of terms foglab averages, which is AllanTools's
for adev, oadev, mdev, tdev, hdev, ohdev, mtotdev, ttotdev and htotdev; for totdev it is
N - 2 (the reflected record's terms), as in SP 1065 eq. 25. There is no ``theo1`` here:
AllanTools labels Theo1 at tau = m tau0 where SP 1065 (and ``foglab.allan(kind="theo1")``)
puts it at 0.75 m tau0.
"""

import numpy as np

from . import _foglab

__all__ = ["adev", "oadev", "mdev", "tdev", "hdev", "ohdev", "totdev", "mtotdev", "ttotdev",
           "htotdev", "tau_generator"]


def tau_generator(phase_points, rate, taus=None):
    """AllanTools's averaging factors for a phase record of ``phase_points`` points.

    Returns the sorted, unique integer factors m (as a numpy array of int64).
    """
    if rate <= 0:
        raise ValueError(f"rate={rate}: the sample rate must be > 0 Hz")
    if taus is None or (isinstance(taus, (list, tuple)) and len(taus) == 0):
        taus = "octave"
    if isinstance(taus, str):
        n = phase_points
        if taus == "all":
            m = np.arange(1, n + 1, dtype=float)
        elif taus == "octave":
            maxn = int(np.floor(np.log2(n)))
            m = np.logspace(0, maxn, maxn + 1, base=2.0)
        elif taus == "log10":
            maxn = np.log10(n)
            m = np.logspace(0, maxn, int(10 * maxn), base=10.0)
        elif taus == "decade":
            maxn = int(np.floor(np.log10(n)))
            m = np.array([f * 10.0 ** k for k in range(maxn + 1) for f in (1.0, 2.0, 4.0)])
        else:
            raise ValueError(f"taus='{taus}': expected 'all', 'octave', 'decade', 'log10' or "
                             "taus in seconds")
    else:
        m = np.asarray(taus, dtype=float) * rate
    m = np.round(m)
    m = m[(m > 0) & (m < phase_points)]
    return np.unique(m).astype(np.int64)


def _deviation(kind, data, rate, data_type, taus):
    data = np.ascontiguousarray(data, dtype=np.float64)
    if data.ndim != 1:
        raise ValueError(f"data must be one-dimensional (got {data.ndim} dimensions)")
    if data_type == "phase":
        input_kind, phase_points = "phase", data.size
    elif data_type == "freq":
        input_kind, phase_points = "rate", data.size + 1
    else:
        raise ValueError(f"data_type='{data_type}': expected 'phase' or 'freq'")
    m = tau_generator(phase_points, rate, taus)
    m = m[m <= _foglab.max_factor(kind, phase_points)]
    if m.size == 0:
        empty = np.array([], dtype=float)
        return empty, empty, empty, np.array([], dtype=np.int64)
    # AllanTools prints HTOTDEV without Riley's bias factor.
    r = _foglab.allan(data, rate, kind=kind, taus=list(m / float(rate)), input=input_kind,
                      confidence=False, bias_correction=False)
    keep = r.n > 1
    taus_used = r.tau_s[keep]
    devs = r.dev[keep]
    ns = r.n[keep]
    return taus_used, devs, devs / np.sqrt(ns), ns


def _statistic(kind, description):
    """AllanTools's function for `kind`: (data, rate=1.0, data_type="phase", taus=None)."""

    def deviation(data, rate=1.0, data_type="phase", taus=None):
        return _deviation(kind, data, rate, data_type, taus)

    deviation.__name__ = deviation.__qualname__ = kind
    deviation.__doc__ = (f"{description}\n\nAllanTools's arguments and result: "
                         "(taus, devs, errors, ns); see the module's documentation.")
    return deviation


adev = _statistic("adev", "Allan deviation (non-overlapping), SP 1065 eq. 7.")
oadev = _statistic("oadev", "Overlapping Allan deviation, SP 1065 eq. 11.")
mdev = _statistic("mdev", "Modified Allan deviation, SP 1065 eq. 15.")
tdev = _statistic("tdev", "Time deviation, tau / sqrt(3) times MDEV (SP 1065 eq. 17), in the "
                          "phase's unit.")
hdev = _statistic("hdev", "Hadamard deviation (non-overlapping), SP 1065 eq. 18.")
ohdev = _statistic("ohdev", "Overlapping Hadamard deviation, SP 1065 eq. 20.")
totdev = _statistic("totdev", "Total deviation, SP 1065 eq. 25.")
mtotdev = _statistic("mtotdev", "Modified total deviation, SP 1065 eq. 27 (no bias correction).")
ttotdev = _statistic("ttotdev", "Time total deviation, tau / sqrt(3) times MTOTDEV (SP 1065 eq. 28), "
                                "in the phase's unit.")
htotdev = _statistic("htotdev", "Hadamard total deviation, SP 1065 eq. 29, OHDEV at m = 1 (no bias "
                                "correction).")
