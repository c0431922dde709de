"""What the Python benchmarks share: timing a call, finding AllanTools (not part of this
repository), and naming the machine a result was measured on."""
import os
import platform
import statistics
import sys
import time


def timed(call, repeat):
    """Runs call() `repeat` times; returns (median s, every run's s, the last result)."""
    times, result = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        result = call()
        times.append(time.perf_counter() - start)
    return statistics.median(times), times, result


def runs_text(times):
    return ", ".join(f"{t:.3f}" for t in times)


def import_allantools(path, required=True):
    """AllanTools from `path` (a folder holding the allantools/ package) or the installed one.
    Exits with how to get it when `required`, else returns None."""
    if path:
        sys.path.insert(0, os.path.abspath(path))
    try:
        import allantools
    except ImportError as error:
        if not required:
            print(f"AllanTools not timed: cannot import it ({error}); give --allantools DIR")
            return None
        sys.exit(
            f"error: cannot import allantools ({error}).\n"
            "AllanTools is not part of this repository. Install it with\n"
            "    pip install allantools\n"
            "(it needs numpy and scipy) on a machine with PyPI access, or clone\n"
            "https://github.com/aewallin/allantools and pass the clone's top\n"
            "directory (the one holding allantools/) as --allantools DIR.")
    return allantools


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def machine_line():
    import numpy as np
    return (f"machine: {platform.platform()}, {cpu_model()}, {os.cpu_count()} logical CPUs; "
            f"python {platform.python_version()}, numpy {np.__version__}")
