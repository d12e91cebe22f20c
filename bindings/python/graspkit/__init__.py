"""graspkit: GraspIt!'s grasp analysis and planning, from Python.

Units are GraspIt!'s: millimetres, grams, radians (mm for prismatic DOFs). A pose is a 4x4
homogeneous NumPy matrix; where a pose is read, a (translation, quaternion w-first) pair is
accepted too. See docs/python.md.
"""

import sys as _sys

try:
    import numpy as _numpy  # noqa: F401 (every array the module returns is one)
except ImportError as _missing:
    raise ImportError(
        f"graspkit needs NumPy, which this interpreter ({_sys.executable}) cannot import. "
        "graspkit is built for Debian's /usr/bin/python3 with python3-numpy (docs/python.md); "
        "run it with that interpreter, or rebuild with -DPython3_EXECUTABLE=<yours>."
    ) from _missing

from ._graspkit import *  # noqa: F401,F403,E402
from ._graspkit import __doc__ as _doc  # noqa: F401,E402

__version__ = version()  # noqa: F405
