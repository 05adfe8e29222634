from typing import Any, Optional

import numpy.typing as npt

from ._sylva import *
from ._sylva import PlanarEkf, RangeBearing, RangeBearingReach, _PlanarFrontEnd

def sigmas(*values: Any) -> npt.NDArray: ...
def FrontEnd(
    ekf: PlanarEkf, sensor: Optional[RangeBearing] = None, reach: Optional[RangeBearingReach] = None, **options: Any
) -> _PlanarFrontEnd: ...
