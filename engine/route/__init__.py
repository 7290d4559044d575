"""Surveyed routes: WGS84 to a local frame, the noise of a track, circle fits and curve detection.

- :mod:`~engine.route.geodesy`: a route's longitude/latitude to a local metric frame;
- :mod:`~engine.route.noise`: the noise model of a sampled polyline;
- :mod:`~engine.route.fit`: least-squares circles and lines;
- :mod:`~engine.route.detect`: the horizontal curves of a polyline (the method in its docstring).
"""

from .detect import (
    FIT_FRACTION,
    PATH_FIT_VERTICES,
    PEAK_NOISE_FRACTION,
    PRECISE_FRACTION,
    SCALE_FACTOR,
    SHAPE_NOISE_FRACTION,
    SURVEY_NOISE_M,
    TRUNCATE,
    HorizontalCurve,
    RouteCurves,
    find_curves,
    spiral_length_m,
)
from .fit import (
    RADIUS_CONFIDENCE,
    CircleFit,
    fit_circle,
    fit_line,
    radius_lower_bound_m,
)
from .geodesy import (
    WGS84_A_M,
    WGS84_E2,
    WGS84_F,
    LocalFrame,
    ecef_m,
    local_frame,
    segment_lengths_m,
    turning_angles_rad,
)
from .noise import (
    CORRELATION_SIGNIFICANCE,
    G1,
    G2,
    HEADING_NOISE_RAD,
    NOISE_LAGS,
    NoiseModel,
    curvature_noise_per_m,
    estimate_noise,
    heading_noise_rad,
    residual_noise,
    vertex_noise_m,
)

__all__ = [
    "CORRELATION_SIGNIFICANCE",
    "FIT_FRACTION",
    "G1",
    "G2",
    "HEADING_NOISE_RAD",
    "NOISE_LAGS",
    "PATH_FIT_VERTICES",
    "PEAK_NOISE_FRACTION",
    "PRECISE_FRACTION",
    "RADIUS_CONFIDENCE",
    "SCALE_FACTOR",
    "SHAPE_NOISE_FRACTION",
    "SURVEY_NOISE_M",
    "TRUNCATE",
    "WGS84_A_M",
    "WGS84_E2",
    "WGS84_F",
    "CircleFit",
    "HorizontalCurve",
    "LocalFrame",
    "NoiseModel",
    "RouteCurves",
    "curvature_noise_per_m",
    "ecef_m",
    "estimate_noise",
    "find_curves",
    "fit_circle",
    "fit_line",
    "heading_noise_rad",
    "local_frame",
    "radius_lower_bound_m",
    "residual_noise",
    "segment_lengths_m",
    "spiral_length_m",
    "turning_angles_rad",
    "vertex_noise_m",
]
