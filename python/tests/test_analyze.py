"""foglab.analyze against `foglab analyze --json` on the same generated record."""

import json
import subprocess

import numpy as np
import pytest

import foglab


@pytest.fixture(scope="module")
def tactical(cli, tmp_path_factory):
    """A generated tactical-grade record (0.5 h at 100 Hz) as float64 samples, and its truth."""
    folder = tmp_path_factory.mktemp("analyze")
    record, truth = folder / "tactical.f64", folder / "truth.json"
    subprocess.run([cli, "generate", "--preset", "class-tactical", "--hours", "0.5", "--seed",
                    "7", "--out", str(record), "--truth", str(truth)], check=True,
                   capture_output=True)
    return record, json.loads(truth.read_text())


def test_analyze_gives_the_documents_numbers(cli, tactical):
    record, truth = tactical
    cli_result = json.loads(subprocess.run(
        [cli, "analyze", str(record), "--fs", "100", "--json", "-"], check=True,
        capture_output=True, text=True).stdout)
    rate = np.fromfile(record, dtype=np.float64)
    result = foglab.analyze(rate, 100.0)
    # Everything but the input's description (a file there, an array here) and the command's
    # own notes about the file is the same.
    assert result["input"]["samples"] == cli_result["input"]["samples"] == rate.size
    assert set(result) == set(cli_result)
    for key in cli_result:
        if key not in ("input", "notes"):
            assert result[key] == cli_result[key], key
    assert set(result["notes"]) <= set(cli_result["notes"])
    # And it is right: N within its 95 % interval, near the truth.
    n = result["noise_model"]["N"]
    assert n["ci95"][0] <= truth["model"]["N"] <= n["ci95"][1]
    # The caller's array is not consumed.
    np.testing.assert_array_equal(rate, np.fromfile(record, dtype=np.float64))


def test_analyze_units_and_accelerometers(tactical):
    record, _ = tactical
    rate = np.fromfile(record, dtype=np.float64)
    in_deg_h = foglab.analyze(rate, 100.0)
    in_deg_s = foglab.analyze(rate / 3600.0, 100.0, units="deg/s")
    assert in_deg_s["noise_model"]["N"]["value"] == pytest.approx(
        in_deg_h["noise_model"]["N"]["value"], rel=1e-9)
    accel = foglab.analyze(rate * 1e-3, 100.0, units="m/s^2")
    assert accel["accuracy_class"] is None
    assert "gyroscopes only" in accel["accuracy_class_note"]
    assert "adev_m_s2" in accel["allan"]


def test_analyze_takes_gaps_and_nan_samples_as_the_cli_reads_them(cli, tactical, tmp_path):
    record, _ = tactical
    rate = np.fromfile(record, dtype=np.float64)
    # A logger lost 3 s in the middle: the record with NaN there, and without those samples
    # but with the gap read() would give, are one record with one gap.
    start, lost = 90_000, 300
    with_nan = rate.copy()
    with_nan[start:start + lost] = np.nan
    kept = np.delete(rate, np.arange(start, start + lost))
    by_nan = foglab.analyze(with_nan, 100.0)
    by_gaps = foglab.analyze(kept, 100.0, gaps=[(start, lost)])
    stitched = foglab.analyze(kept, 100.0)
    for result in (by_nan, by_gaps):
        gaps = result["input"]["gaps"]
        assert gaps["count"] == 1 and gaps["missing_samples"] == lost
        assert gaps["list"][0]["before_sample"] == start
        assert result["input"]["samples"] == kept.size
    assert by_nan["input"]["gaps"]["missing_value_rows"] == lost
    assert by_gaps["input"]["gaps"]["missing_value_rows"] == 0
    # The Allan terms across the gap are left out, not stitched over.
    assert by_gaps["allan"]["n"][0] < stitched["allan"]["n"][0]
    # The CLI on the same samples written with empty cells finds the same.
    table = tmp_path / "lost.csv"
    table.write_text("i,rate\n" + "".join(
        f"{i},{'' if np.isnan(v) else repr(float(v))}\n" for i, v in enumerate(with_nan)))
    cli_result = json.loads(subprocess.run(
        [cli, "analyze", str(table), "--channel", "rate", "--fs", "100", "--json", "-"],
        check=True, capture_output=True, text=True).stdout)
    assert cli_result["input"]["gaps"]["list"] == by_nan["input"]["gaps"]["list"]
    for key in cli_result:
        if key not in ("input", "notes"):
            assert by_nan[key] == cli_result[key] == by_gaps[key], key
    # The caller's array keeps its NaN.
    assert np.isnan(with_nan[start:start + lost]).all()
    # The share of a cluster that may be missing, as the CLI's option: at 0 no term spans the
    # gap, and where none did the deviations are the default's.
    pooled = foglab.analyze(kept, 100.0, gaps=[(start, lost)], max_missing_percent=0)
    assert pooled["options"]["max_missing_percent"] == 0
    assert by_gaps["options"]["max_missing_percent"] == 1
    assert pooled["allan"]["gap_spanning_terms"] == []
    assert any(n > 0 for n in by_gaps["allan"]["gap_spanning_terms"])
    for k, spanning in enumerate(by_gaps["allan"]["gap_spanning_terms"]):
        if spanning == 0 and k < len(pooled["allan"]["tau_s"]):
            assert pooled["allan"]["adev_deg_h"][k] == by_gaps["allan"]["adev_deg_h"][k]
    with pytest.raises(ValueError, match="max_missing_percent"):
        foglab.analyze(kept, 100.0, max_missing_percent=11)


def test_analyze_errors():
    with pytest.raises(ValueError, match="furlong"):
        foglab.analyze(np.ones(1000), 100.0, units="furlong/fortnight")
    with pytest.raises(ValueError, match="pair one to one"):
        foglab.analyze(np.ones(1000), 100.0, temperature=np.ones(999))
    with pytest.raises(foglab.DataError):
        foglab.analyze(np.zeros(1000), 100.0)
    with pytest.raises(ValueError, match="gaps"):
        foglab.analyze(np.ones(1000), 100.0, gaps=[(0, 5)])
    with pytest.raises(foglab.DataError, match="no sample left"):
        foglab.analyze(np.full(1000, np.nan), 100.0)
    with pytest.raises(foglab.DataError,
                       match=r"rate\[3\] is inf: every sample must be a finite number or NaN"):
        foglab.analyze(np.array([1.0, 2.0, 3.0, np.inf]), 100.0)
