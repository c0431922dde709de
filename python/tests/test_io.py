"""foglab.generate and foglab.read against the CLI's files."""

import json
import subprocess

import numpy as np
import pytest

import foglab


def test_generate_is_the_clis_generator_bit_for_bit(cli, tmp_path):
    record, truth = tmp_path / "g.f64", tmp_path / "truth.json"
    subprocess.run([cli, "generate", "--preset", "class-navigation", "--hours", "0.2",
                    "--seed", "11", "--K", "0.002", "--out", str(record), "--truth", str(truth)],
                   check=True, capture_output=True)
    g = foglab.generate("class-navigation", hours=0.2, seed=11, K=0.002)
    np.testing.assert_array_equal(g["rate_deg_h"], np.fromfile(record, dtype=np.float64))
    assert g["sample_rate_hz"] == 100.0
    assert g["rate_deg_h"].size == g["time_s"].size == g["temperature_c"].size == 72000
    assert g["truth"] == json.loads(truth.read_text())["model"]
    assert g["truth"]["K"] == 0.002
    other = foglab.generate("class-navigation", hours=0.2, seed=11, stream=1, K=0.002)
    assert not np.array_equal(other["rate_deg_h"], g["rate_deg_h"])


def test_read_a_text_file_and_a_bag(cli, tmp_path):
    csv = tmp_path / "r.csv"
    subprocess.run([cli, "generate", "--N", "10", "--fs", "50", "--hours", "0.01", "--seed", "2",
                    "--drop", "10:1", "--out", str(csv)], check=True, capture_output=True)
    r = foglab.read(str(csv))
    assert r["sample_rate_hz"] == pytest.approx(50.0)
    assert r["gaps"] == [(500, 50)]
    assert r["values"].size == 1800 - 50
    in_deg_s = foglab.read(str(csv), units="deg/s")
    np.testing.assert_allclose(in_deg_s["values"], r["values"] * 3600.0)

    bag = tmp_path / "imu.bag"
    subprocess.run([cli, "generate", "--imu", "--hours", "0.01", "--seed", "3", "--out",
                    str(bag)], check=True, capture_output=True)
    b = foglab.read(str(bag))
    assert b["topic"] and b["sample_rate_hz"] == pytest.approx(400.0, rel=1e-6)
    for key in ("gyro_x_rad_s", "gyro_y_rad_s", "gyro_z_rad_s", "accel_x_m_s2", "accel_y_m_s2",
                "accel_z_m_s2"):
        assert b[key].size == 14400, key
    assert abs(np.mean(b["accel_z_m_s2"]) - 9.80665) < 0.1  # gravity on z


def test_read_errors_name_the_file(tmp_path):
    missing = tmp_path / "missing.csv"
    with pytest.raises((ValueError, foglab.DataError), match="missing.csv"):
        foglab.read(str(missing))
    text = tmp_path / "bad.csv"
    text.write_text("rate\n1.0\nnan\n2.0\n")
    with pytest.raises(foglab.DataError, match="bad.csv"):
        foglab.read(str(text), rate_hz=10.0, nan_is_missing=False)
    with pytest.raises(ValueError, match="is not a ROS bag"):
        foglab.read(str(text), rate_hz=10.0, topic="/imu")
    with pytest.raises(ValueError, match="rate_hz"):
        foglab.generate(N=1.0)
    with pytest.raises(ValueError, match="Z="):
        foglab.generate(rate_hz=10.0, Z=1.0)


def test_read_leaves_nan_rows_out_as_gaps_like_analyze(tmp_path):
    # a logger's lost samples: NaN, and an empty cell (pandas' to_csv)
    text = tmp_path / "lost.csv"
    text.write_text("time_s,rate\n0.0,1.0\n0.1,nan\n0.2,\n0.3,2.0\n0.4,3.0\n0.5,nan\n")
    r = foglab.read(str(text), channel="rate")
    assert r["values"].tolist() == [1.0, 2.0, 3.0]
    assert r["missing_value_rows"] == 3
    assert r["gaps"] == [(1, 2)]  # the trailing NaN shortens the record
    assert r["sample_rate_hz"] == pytest.approx(10.0)

