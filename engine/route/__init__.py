"""Surveyed routes: WGS84 to a local frame, the noise of a track, circle fits and curve detection.

- :mod:`~engine.route.geodesy`: a route's longitude/latitude to a local metric frame;
- :mod:`~engine.route.noise`: the noise model of a sampled polyline;
- :mod:`~engine.route.fit`: least-squares circles and lines;
- :mod:`~engine.route.detect`: the horizontal curves of a polyline (the method in its docstring).

Exports (the face's ``__all__``, by concept; every other name is the package's own, importable by its
module path for the package and its tests):

From :mod:`~engine.route.detect`, horizontal curves of a route from its geometry: a polyline in a local metric frame ->
tangents and curves:

- ``find_curves``: Tangents and horizontal curves of a polyline (see the module docstring for the method)
- ``HorizontalCurve``: One horizontal curve of a route

From :mod:`~engine.route.geodesy`, WGS84 longitude/latitude of a route to a local metric frame in which its curves keep
their size:

- ``local_frame``: Develop a WGS84 route into a plane frame that keeps its segment lengths and turning angles
- ``segment_lengths_m``: Horizontal length of each segment of a polyline on the WGS84 surface, shape (n - 1,) [m]
"""

from .detect import (
    HorizontalCurve,
    find_curves,
)
from .geodesy import (
    local_frame,
    segment_lengths_m,
)

__all__ = [
    "HorizontalCurve",
    "find_curves",
    "local_frame",
    "segment_lengths_m",
]
