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


def test_analyze_errors():
    with pytest.raises(ValueError, match="furlong"):
        foglab.analyze(np.ones(1000), 100.0, units="furlong/fortnight")
    with pytest.raises(ValueError, match="pair one to one"):
        foglab.analyze(np.ones(1000), 100.0, temperature=np.ones(999))
    with pytest.raises(foglab.DataError):
        foglab.analyze(np.zeros(1000), 100.0)
