"""Builds the Python package foglab: the C++ module with CMake, the Python files as they are.

    python3 -m pip install --no-build-isolation --break-system-packages .

(docs/python.md: why those two flags on Debian, and a virtual environment instead.) The
module is the CMake target foglab_python (python/CMakeLists.txt), built in a folder of its
own under build/ (or in the configured build tree FOGLAB_CMAKE_BUILD_DIR names, to reuse
its objects), for the Python that runs this file.
"""

import os
import pathlib
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


def project_version():
    text = (ROOT / "CMakeLists.txt").read_text()
    return re.search(r"project\(foglab VERSION (\d+\.\d+\.\d+)", text).group(1)


class CMakeBuild(build_ext):
    """Builds foglab._foglab with CMake and puts it where setuptools wants it."""

    def build_extension(self, ext):
        build_dir = pathlib.Path(os.environ.get("FOGLAB_CMAKE_BUILD_DIR") or
                                 ROOT / "build" / "python-package")
        module_dir = build_dir / "python"
        if not (build_dir / "CMakeCache.txt").exists():
            subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build_dir),
                            "-DCMAKE_BUILD_TYPE=Release", "-DFOGLAB_BUILD_PYTHON=ON",
                            "-DFOGLAB_BUILD_TESTS=OFF", "-DFOGLAB_BUILD_BENCH=OFF",
                            "-DFOGLAB_BUILD_EXAMPLES=OFF", f"-DPython_EXECUTABLE={sys.executable}",
                            f"-DFOGLAB_PYTHON_DIR={module_dir}"], check=True)
        else:
            module_dir = pathlib.Path(re.search(r"^FOGLAB_PYTHON_DIR:PATH=(.*)$",
                                                (build_dir / "CMakeCache.txt").read_text(),
                                                re.M).group(1))
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "foglab_python",
                        "--parallel", str(os.cpu_count() or 2)], check=True)
        built = sorted((module_dir / "foglab").glob("_foglab*.so"))
        if not built:
            raise RuntimeError(f"CMake built no foglab/_foglab*.so in {module_dir}")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[-1], target)
        # The ROS bag plugin, which the module loads from beside itself (src/io/rosbag_plugin.h).
        plugin = build_dir / "lib" / "foglab" / "foglab_rosbag.so"
        if not plugin.exists():
            raise RuntimeError(f"CMake built no ROS bag plugin {plugin}")
        shutil.copyfile(plugin, target.parent / plugin.name)


# setuptools's own folders (below) must exist before it runs.
(ROOT / "build" / "setuptools").mkdir(parents=True, exist_ok=True)

setup(
    name="foglab",
    version=project_version(),
    description="Stability statistics, noise identification and reports for gyroscopes and "
                "IMUs (Allan deviations with intervals, PSD, noise model, Kalibr)",
    license="see the repository",
    python_requires=">=3.9",
    install_requires=["numpy"],
    packages=["foglab"],
    package_dir={"": "python"},
    ext_modules=[Extension("foglab._foglab", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # setuptools's own folders under build/, apart from CMake's.
    options={"build": {"build_base": "build/setuptools"},
             "egg_info": {"egg_base": "build/setuptools"}},
    zip_safe=False,
)
