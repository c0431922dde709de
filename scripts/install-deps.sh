#!/usr/bin/env bash
# Installs the Debian 12 packages foglab needs to build and run, skipping
# those already present; with --tests also what the test suite needs
# (GNU Octave; headless Chromium for the reports' browser test; the ROS
# Python library that writes test bags; clang-14
# with its sanitizer and libFuzzer runtimes for the sanitizer build); with
# --fuzz only the latter. Run as root (or with sudo).
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libeigen3-dev libfftw3-dev libmatio-dev libhdf5-dev
  libcli11-dev nlohmann-json3-dev libfmt-dev libboost-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  gnuplot-nox
  # ROS 1 bags (src/io/rosbag.cc): rosbag_storage and the sensor_msgs/Imu
  # headers; rosbag/bag.h includes pluginlib's headers (pluginlib-dev, a
  # dependency of librosbag-storage-dev named here since the build needs it).
  librosbag-storage-dev libsensor-msgs-dev pluginlib-dev
  # The Python module (python/, pybind11) and `pip install .` (setup.py: setuptools without
  # build isolation, so nothing is fetched from PyPI).
  pybind11-dev python3-dev python3-numpy python3-setuptools python3-pip
)
if [ "${1:-}" = "--tests" ]; then
  # octave-cli runs the lab's MATLAB steps on lab2-data files in the tests
  # (octave 7 from Debian 12); its plots need a font, a Recommends of
  # octave-common that --no-install-recommends would skip.
  # chromium opens the lab reports in the browser test (headless).
  # python3-rosbag with the sensor_msgs and std_msgs Python messages writes
  # the bags that tests/io/rosbag_test.cc reads (tests/io/make_imu_bag.py).
  # python3-pytest runs the Python module's tests (python/tests); python3-distributed
  # (with python3-dask) runs foglab.dask's test on a LocalCluster. Users of foglab.dask
  # install it the same way (docs/python.md).
  packages+=(octave fonts-freefont-otf chromium
             python3-rosbag python3-sensor-msgs python3-std-msgs python3-pytest
             python3-dask python3-distributed)
fi
if [ "${1:-}" = "--tests" ] || [ "${1:-}" = "--fuzz" ]; then
  # clang-14 with its runtime (ASan, UBSan, libFuzzer) and OpenMP builds the
  # "asan" preset: the tests under the sanitizers and the fuzz targets
  # (scripts/sanitize-tests.sh, scripts/fuzz-smoke.sh).
  packages+=(clang-14 libclang-rt-14-dev libomp-14-dev)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]})); then
  echo "foglab: installing ${missing[*]}" >&2
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
