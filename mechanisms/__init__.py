"""Kinematics of planar linkage mechanisms: the package of the book.

Layers, bottom up (a module imports only from layers below it):

1. motion of a link (:mod:`~mechanisms.motion`, :mod:`~mechanisms.links`);
2. building blocks (:mod:`mechanisms.blocks`);
3. mechanisms (:mod:`~mechanisms.base` and one module per mechanism);
4. analysis (:mod:`mechanisms.analysis`);
5. verification (:mod:`~mechanisms.verify`, :mod:`~mechanisms.jet`);
6. presentation (:mod:`~mechanisms.plot`, :mod:`~mechanisms.present`, :mod:`~mechanisms.cli`).
"""

from . import motion
from .base import Mechanism, Solution
from .errors import AssemblyError, DeadCentreWarning, InvalidParameterError, MechanismError
from .motion import (AngleMotion, Motion, PointMotion, fixed_point, lagrange_point, plane_motion, point_on_link, polar,
                     translated_point)
from .links import LINK_TYPES, LinkType, harmonic, link_type

# mechanisms (layer 3), one line per chapter -------------------------------------------
# chapter 3:
from .crank_slider import CrankSlider  # noqa: E402
# chapter 4:
from .four_bar import FourBar  # noqa: E402
from .lambda_mechanism import LambdaMechanism  # noqa: E402
# chapter 5:
from .slotted import RockerInBlock, Shaper, SliderOnCoupler, SlottedLever, SlottedRockers  # noqa: E402
# ---------------------------------------------------------------------------------------

from . import verify  # noqa: E402  (layer 5, after the mechanisms it checks)
from . import plot, plot_plans, present  # noqa: E402  (layer 6)
from .present import difference, magnitude, markdown_table  # noqa: E402

__version__ = "0.1.0"
