"""graspkit: GraspIt!'s grasp analysis and planning, from Python.

Units are GraspIt!'s: millimetres, grams, radians (mm for prismatic DOFs). A pose is a 4x4
homogeneous NumPy matrix; where a pose is read, a (translation, quaternion w-first) pair is
accepted too. See docs/python.md.
"""

from ._graspkit import *  # noqa: F401,F403
from ._graspkit import __doc__ as _doc  # noqa: F401

__version__ = version()  # noqa: F405
