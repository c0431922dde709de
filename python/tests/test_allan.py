"""foglab.allan and foglab.compat against the published references and AllanTools's rules."""

import threading
import time

import numpy as np
import pytest

import foglab
import foglab.compat as allantools
from conftest import REFERENCE_DIR, nbs14_1000, stable32_table

KINDS = ["adev", "oadev", "mdev", "tdev", "hdev", "ohdev", "totdev"]


@pytest.mark.parametrize("kind", KINDS)
def test_stable32_phase_dat_octave_tables(phase_dat, kind):
    """Deviations to 2e-4, counts exactly, 68 % bounds to 1 % (Stable32 1.60's tables)."""
    rows = stable32_table(f"phase_dat_{kind}_octave.txt")
    assert rows
    af = [row[0] for row in rows]
    r = foglab.allan(phase_dat, 1.0, kind=kind, taus=[float(m) for m in af], input="phase")
    assert isinstance(r, foglab.AllanResult)
    assert list(r.m) == af
    for k, (m, tau, n, alpha, low, sigma, high) in enumerate(rows):
        assert r.tau_s[k] == pytest.approx(tau)
        assert r.dev[k] == pytest.approx(sigma, rel=2e-4), f"{kind} AF {m}"
        assert r.n[k] == n, f"{kind} AF {m}"
        assert r.alpha[k] == alpha, f"{kind} AF {m}"
        assert r.ci68_low[k] == pytest.approx(low, rel=0.01), f"{kind} AF {m}"
        assert r.ci68_high[k] == pytest.approx(high, rel=0.01), f"{kind} AF {m}"
        assert r.ci95_low[k] < r.ci68_low[k] < r.dev[k] < r.ci68_high[k] < r.ci95_high[k]


@pytest.mark.parametrize("kind, table, options", [
    ("mtotdev", "phase_dat_mtotdev_decade.txt", {"noise_id": "stable32"}),
    ("htotdev", "phase_dat_htotdev_octave.txt", {}),
    ("htotdev", "phase_dat_htotdev_octave_nobias.txt", {"bias_correction": False}),
    ("theo1", "phase_dat_theo1_alpha0_decade.txt", {"confidence": False}),
])
def test_total_and_theo_family_reproduce_stable32(phase_dat, kind, table, options):
    """Values to 2e-4 at Stable32's factors (Theo1's tau = 0.75 m); the noise types and 68 %
    bounds where Stable32 printed them with its own noise identification."""
    rows = stable32_table(table)
    assert rows
    taus = [tau for _, tau, _, _, _, _, _ in rows]
    r = foglab.allan(phase_dat, 1.0, kind=kind, taus=taus, input="phase", **options)
    assert list(r.m) == [row[0] for row in rows]
    for k, (m, tau, n, alpha, low, sigma, high) in enumerate(rows):
        assert r.dev[k] == pytest.approx(sigma, rel=2e-4), f"{table} AF {m}"
        if options.get("noise_id") == "stable32" or not options:
            assert r.alpha[k] == alpha, f"{table} AF {m}"
            assert r.ci68_low[k] == pytest.approx(low, rel=0.01), f"{table} AF {m}"


def test_compat_total_family_is_raw_and_in_allantools_tuple(phase_dat):
    """AllanTools's mtotdev/htotdev/ttotdev: raw values (Stable32 1.60's MTOTDEV octave table,
    the bias-free HTOTDEV table), counts N - 3m + 1 and N - 3m."""
    taus, devs, errors, ns = allantools.mtotdev(phase_dat, taus=[1.0, 2.0, 4.0, 8.0, 16.0])
    table = stable32_table("phase_dat_mtotdev_octave.txt")
    assert devs == pytest.approx([row[5] for row in table], rel=2e-4)
    assert list(ns) == [row[2] for row in table]
    assert errors == pytest.approx(devs / np.sqrt(ns))
    _, hdevs, _, hns = allantools.htotdev(phase_dat, taus=[1.0, 2.0, 4.0, 8.0, 16.0])
    nobias = stable32_table("phase_dat_htotdev_octave_nobias.txt")
    assert hdevs == pytest.approx([row[5] for row in nobias], rel=2e-4)
    assert list(hns) == [row[2] for row in nobias]
    ttaus, tdevs, _, _ = allantools.ttotdev(phase_dat, taus=[1.0, 2.0, 4.0, 8.0, 16.0])
    assert tdevs == pytest.approx(devs * ttaus / np.sqrt(3.0), rel=1e-12)


NBS14 = {  # NIST SP 1065 Table 31: the NBS14 1000-point set at m = 1, 10, 100
    "adev": [2.922319e-01, 9.965736e-02, 3.897804e-02],
    "oadev": [2.922319e-01, 9.159953e-02, 3.241343e-02],
    "mdev": [2.922319e-01, 6.172376e-02, 2.170921e-02],
    "totdev": [2.922319e-01, 9.134743e-02, 3.406530e-02],
    "hdev": [2.943883e-01, 1.052754e-01, 3.910860e-02],
    "ohdev": [2.943883e-01, 9.581083e-02, 3.237638e-02],
    "tdev": [1.687202e-01, 3.563623e-01, 1.253382e+00],
}


@pytest.mark.parametrize("kind", KINDS)
def test_compat_matches_nist_nbs14_as_frequency_data(kind):
    taus, devs, errors, ns = getattr(allantools, kind)(nbs14_1000(), rate=1.0,
                                                        data_type="freq", taus=[1, 10, 100])
    np.testing.assert_array_equal(taus, [1.0, 10.0, 100.0])
    np.testing.assert_allclose(devs, NBS14[kind], rtol=1e-6)
    np.testing.assert_allclose(errors, devs / np.sqrt(ns), rtol=1e-15)


def test_compat_oadev_follows_allantools_conventions(phase_dat):
    # Phase data by default; octave taus 1 .. 512 for 1001 points (m < N); taus with a single
    # term are dropped (none here for OADEV: m = 512 leaves 1001 - 1024 < 0 terms, so m <= 500).
    taus, devs, errors, ns = allantools.oadev(phase_dat)
    np.testing.assert_array_equal(taus, [1, 2, 4, 8, 16, 32, 64, 128, 256])
    np.testing.assert_array_equal(ns, 1001 - 2 * taus)
    rows = {row[0]: row for row in stable32_table("phase_dat_oadev_octave.txt")}
    for tau, dev, n in zip(taus, devs, ns):
        if int(tau) in rows:
            assert dev == pytest.approx(rows[int(tau)][5], rel=2e-4)
            assert n == rows[int(tau)][2]
    np.testing.assert_allclose(errors, devs / np.sqrt(ns))
    # The same record as frequency data, at another rate: the taus scale, the values do not
    # change once the phase is in the same unit.
    freq = np.diff(phase_dat) * 10.0
    taus_f, devs_f, _, ns_f = allantools.oadev(freq, rate=10.0, data_type="freq")
    np.testing.assert_allclose(taus_f, taus / 10.0)
    np.testing.assert_allclose(devs_f, devs * 10.0, rtol=1e-9)
    np.testing.assert_array_equal(ns_f, ns)


def test_compat_tau_keywords_and_lists():
    m = allantools.tau_generator(1000, 1.0, "decade")
    np.testing.assert_array_equal(m, [1, 2, 4, 10, 20, 40, 100, 200, 400])
    m = allantools.tau_generator(1000, 1.0, "all")
    np.testing.assert_array_equal(m, np.arange(1, 1000))
    # Seconds at 10 Hz, unsorted, repeated, out of range: sorted, unique, kept in range.
    m = allantools.tau_generator(1000, 10.0, [3.0, 0.1, 0.1, 0.0, 500.0, 0.25])
    np.testing.assert_array_equal(m, [1, 2, 30])
    taus, devs, errors, ns = allantools.adev(nbs14_1000(), data_type="freq", taus="octave")
    assert ns[-1] > 1 and np.all(np.diff(taus) > 0)


def test_arrays_of_other_types_and_layouts_give_the_same_numbers():
    y = nbs14_1000()
    reference = foglab.allan(y, 1.0, taus=[1.0, 10.0]).dev
    strided = np.zeros(2 * y.size)
    strided[::2] = y
    np.testing.assert_array_equal(foglab.allan(strided[::2], 1.0, taus=[1.0, 10.0]).dev,
                                  reference)
    np.testing.assert_allclose(foglab.allan(list(y), 1.0, taus=[1.0, 10.0]).dev, reference)
    np.testing.assert_allclose(
        foglab.allan(y.astype(np.float32), 1.0, taus=[1.0, 10.0]).dev, reference, rtol=1e-6)


def test_errors_carry_foglabs_message():
    with pytest.raises(ValueError, match="oadevx"):
        foglab.allan(np.ones(100), 1.0, kind="oadevx")
    with pytest.raises(ValueError, match="taus='weekly'"):
        foglab.allan(np.ones(100), 1.0, taus="weekly")
    with pytest.raises(ValueError, match="one-dimensional"):
        foglab.allan(np.ones((10, 10)), 1.0)
    with pytest.raises(ValueError, match="data_type"):
        allantools.oadev(np.ones(100), data_type="angle")
    with_nan = np.ones(100)
    with_nan[42] = np.nan
    for call in (lambda: foglab.allan(with_nan, 1.0), lambda: foglab.psd(with_nan, 1.0),
                 lambda: foglab.analyze(with_nan, 1.0, nan_is_missing=False)):
        with pytest.raises(foglab.DataError, match=r"\[42\] is nan"):
            call()
    with pytest.raises(foglab.DataError) as error:
        foglab.allan(np.arange(3.0), 1.0, taus=[10.0])
    assert str(error.value)
    assert isinstance(error.value, RuntimeError)


def test_the_gil_is_released_while_computing():
    # A Python thread keeps running while foglab computes 2e7 samples' deviations.
    data = np.random.default_rng(1).standard_normal(20_000_000)
    done = threading.Event()
    ticks = 0

    def count():
        nonlocal ticks
        while not done.is_set():
            ticks += 1
            time.sleep(0.001)

    counter = threading.Thread(target=count)
    counter.start()
    start = time.perf_counter()
    foglab.allan(data, 100.0, confidence=False)
    elapsed = time.perf_counter() - start
    done.set()
    counter.join()
    # With the GIL held the counter would stop for the whole call; released, it ticks about
    # once a millisecond (loosely: a loaded machine schedules it less often).
    assert ticks > 0.1 * elapsed / 0.001


def test_results_own_their_arrays():
    r = foglab.allan(nbs14_1000(), 1.0)
    dev = r.dev
    del r
    assert dev.dtype == np.float64 and dev.size > 5 and np.all(np.isfinite(dev))
    assert foglab.__version__


@pytest.mark.parametrize("kind, table", [("mtie", "phase_dat_mtie.txt"),
                                         ("tierms", "phase_dat_tierms.txt")])
def test_time_error_reproduces_stable32(phase_dat, kind, table):
    """MTIE and TIE rms on PHASE.DAT: Stable32's values to 2e-4 and its counts."""
    rows = []
    for line in (REFERENCE_DIR / table).read_text().splitlines():
        fields = line.split()
        if fields and not line.startswith("#") and len(fields) == 4:
            rows.append((int(fields[0]), int(fields[2]), float(fields[3])))
    assert rows
    r = foglab.time_error(phase_dat, 1.0, kind=kind, taus=[float(af) for af, _, _ in rows],
                          input="phase")
    assert r["kind"] == kind
    assert list(r["m"]) == [af for af, _, _ in rows]
    assert list(r["n"]) == [n for _, n, _ in rows]
    np.testing.assert_allclose(r["value"], [v for _, _, v in rows], rtol=2e-4)
    with pytest.raises(ValueError, match="mtie or tierms"):
        foglab.time_error(phase_dat, 1.0, kind="tie")

