"""Fixtures of the foglab pytest suite: the reference data and the CLI it is compared with.

CTest runs it with PYTHONPATH naming the module in the build tree, FOGLAB_CLI the foglab
executable and FOGLAB_SOURCE_DIR the source tree (python/CMakeLists.txt).
"""

import os
import pathlib

import numpy as np
import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("FOGLAB_SOURCE_DIR",
                                         pathlib.Path(__file__).resolve().parents[2]))
REFERENCE_DIR = SOURCE_DIR / "tests" / "data" / "stable32-phasedat"


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("FOGLAB_CLI")
    if not path or not os.access(path, os.X_OK):
        pytest.skip("FOGLAB_CLI does not name the foglab executable (CTest sets it)")
    return path


@pytest.fixture(scope="session")
def phase_dat():
    """PHASE.DAT: 1001 phase points at tau0 = 1 s (Stable32's test file)."""
    values = [float(line) for line in (REFERENCE_DIR / "PHASE.DAT").read_text().splitlines()
              if line.strip() and not line.startswith("#")]
    return np.array(values)


def stable32_table(name):
    """The rows of a Stable32 table: AF, tau, count, alpha, min sigma, sigma, max sigma."""
    rows = []
    for line in (REFERENCE_DIR / name).read_text().splitlines():
        fields = line.split()
        if not fields or line.startswith("#") or len(fields) < 7:
            continue
        af, tau, n, alpha, low, sigma, high = fields[:7]
        # Theo1's tables print the count as a float (4.9550e+03).
        rows.append((int(af), float(tau), round(float(n)), int(alpha), float(low), float(sigma),
                     float(high)))
    return rows


def nbs14_1000():
    """NIST SP 1065's NBS14 1000-point fractional-frequency set (p. 108)."""
    y = np.empty(1000)
    n = 1234567890
    for i in range(1000):
        y[i] = n / 2147483647.0
        n = (16807 * n) % 2147483647
    return y
