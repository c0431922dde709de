"""foglab: stability statistics, noise identification and reports for gyroscopes and IMUs.

The numbers come from foglab's C++ library (the module ``foglab._foglab``), the same code the
``foglab`` command runs:

- ``allan(data, rate, kind="oadev", taus="octave", input="rate", min_clusters=10)``: one
  deviation (adev, oadev, mdev, hdev, ohdev, tdev, totdev) with noise identification, edf and
  68/95 % intervals, as numpy arrays (an ``AllanResult``);
- ``time_error(data, rate, kind="mtie", taus="octave", input="rate")``: MTIE or TIE rms
  (``kind="tierms"``) of the angle, as ``foglab allan --kind mtie`` computes it;
- ``psd(data, rate)``: Welch's two-sided PSD;
- ``analyze(rate, rate_hz, temperature=None, units="deg/h")``: the whole analysis of a static
  record, the document ``foglab analyze --json`` writes (docs/json.md);
- ``generate(preset="", rate_hz=None, hours=1.0, seed=1, **terms)``: a synthetic record and
  its truth, bit for bit those of ``foglab generate``;
- ``read(path, channel="", rate_hz=None, units="deg/h")``: a channel of a MAT, text or raw
  file, or a ROS bag's six IMU channels;
- ``batch(inputs, out, **options)``: a fleet of recordings analysed in parallel and its report,
  as ``foglab batch`` does it (docs/cli.md#batch); returns the fleet.json document;
- ``dask.batch(client, inputs, out, **options)``: the same batch with each recording analysed
  on a Dask cluster (``foglab.dask``, docs/python.md);
- ``compat``: AllanTools's functions and return values (``foglab.compat.oadev(...)``).

Errors: a bad argument raises ``ValueError``, unusable data ``foglab.DataError``, each with
foglab's message. Arrays of float64 are read in place; the GIL is released while computing.
"""

from ._foglab import (  # noqa: F401
    AllanResult,
    DataError,
    __version__,
    allan,
    analyze,
    batch,
    generate,
    max_factor,
    psd,
    read,
    time_error,
)
from . import compat  # noqa: F401

__all__ = ["AllanResult", "DataError", "allan", "analyze", "batch", "compat", "generate",
           "max_factor", "psd", "read", "time_error", "__version__"]
