"""foglab.batch and foglab.dask.batch against `foglab batch`: the same fleet, unit for unit."""

import json
import os
import pathlib
import subprocess

import pytest

import foglab


def _fleet(cli, folder, units=12, outliers=1):
    """A generated fleet (generate --fleet) with its truth."""
    made = subprocess.run(
        [cli, "generate", "--N", "0.06", "--B", "0.02", "--fs", "10", "--hours", "0.5",
         "--fleet", str(units), "--outliers", str(outliers), "--seed", "5",
         "--out", str(folder / "unit.mat")],
        capture_output=True, text=True)
    assert made.returncode == 0, made.stderr
    return json.loads((folder / "fleet_truth.json").read_text())


def _cli_batch(cli, inputs, out, *options):
    run = subprocess.run([cli, "batch", *map(str, inputs), "--no-plots", "--out", str(out),
                          *options], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    return json.loads((out / "fleet.json").read_text())


def _comparable(fleet):
    """fleet.json without what differs between a fresh batch and one that kept its units."""
    fleet = dict(fleet)
    fleet.pop("units_kept_from_earlier_run")
    return fleet


def _unit_documents(out):
    return {p.name: json.loads(p.read_text()) for p in sorted((out / "units").glob("*.json"))}


def test_batch_in_python_is_the_command(cli, tmp_path):
    truth = _fleet(cli, tmp_path / "fleet")
    by_cli = _cli_batch(cli, [tmp_path / "fleet"], tmp_path / "cli")
    by_python = foglab.batch([str(tmp_path / "fleet")], str(tmp_path / "py"), plots=False)
    assert by_python == by_cli
    assert _unit_documents(tmp_path / "py") == _unit_documents(tmp_path / "cli")
    planted = {(o["unit"], o["parameter"]) for o in truth["outliers"]}
    found = {(o["unit"], o["parameter"]) for o in by_python["fleet"]["outliers"]
             if o["parameter"] in ("N", "B")}
    assert found == planted


def test_batch_options_and_errors(cli, tmp_path):
    _fleet(cli, tmp_path / "fleet", units=10)
    with pytest.raises(ValueError, match="unknown option 'colour'"):
        foglab.batch([str(tmp_path / "fleet")], str(tmp_path / "out"), colour="red")
    with pytest.raises(ValueError, match="no such file or folder"):
        foglab.batch([str(tmp_path / "nothing.mat")], str(tmp_path / "out"))
    (tmp_path / "fleet" / "broken.csv").write_text("t,rate\n0,1\n0.1,x\n")
    fleet = foglab.batch([str(tmp_path / "fleet")], str(tmp_path / "out"), plots=False,
                         taus="decade")
    assert len(fleet["units"]) == 10
    assert [f["exit_code"] for f in fleet["failures"]] == [3]
    assert "broken.csv" in fleet["failures"][0]["input"]
    assert fleet["options"]["taus"] == "decade"


def test_dask_batch_on_a_local_cluster_is_the_command(cli, tmp_path):
    distributed = pytest.importorskip(
        "distributed", reason="foglab.dask needs Dask's distributed (Debian: python3-distributed)")
    import foglab.dask

    _fleet(cli, tmp_path / "fleet", units=12)
    by_cli = _cli_batch(cli, [tmp_path / "fleet"], tmp_path / "cli")
    with distributed.LocalCluster(n_workers=3, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        by_dask = foglab.dask.batch(client, [str(tmp_path / "fleet" / "*.mat")],
                                    tmp_path / "dask", plots=False)
        # The units were analysed on the workers: the report kept every one of them.
        assert by_dask["units_kept_from_earlier_run"] == 12
        assert _comparable(by_dask) == _comparable(by_cli) | {"inputs": by_dask["inputs"]}
        assert _unit_documents(tmp_path / "dask") == _unit_documents(tmp_path / "cli")
        # A rerun sends nothing to the workers (no unit written again) and gives the same report.
        written = {p: p.stat().st_mtime_ns for p in (tmp_path / "dask" / "units").iterdir()}
        again = foglab.dask.batch(client, [str(tmp_path / "fleet" / "*.mat")],
                                  tmp_path / "dask", plots=False)
        assert again == by_dask
        assert {p: p.stat().st_mtime_ns for p in (tmp_path / "dask" / "units").iterdir()} == written
