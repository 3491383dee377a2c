# SPDX-License-Identifier: BSD-3-Clause
"""lmk: custom perceptual landmarks for robot programming by demonstration.

Point clouds go in and out as numpy arrays; landmarks are captured, saved, loaded and searched for
with the C++ library's own functions (docs/python.md). Search settings are keywords with the names
of `lmk find`'s flags (``max_tilt=30`` for ``--max-tilt 30``), in the same units, checked by the
same rules.
"""

from ._lmk import (  # noqa: F401
    Cloud,
    Error,
    Landmark,
    Refused,
    SimulatedPr2,
    Tracker,
    ablate,
    __version__,
    capture,
    error_metrics,
    eval,
    find,
    find_setting_keys,
    fuse,
    load_landmark,
    plan,
    read_cloud,
    run,
)
