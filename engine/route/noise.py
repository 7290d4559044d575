"""Noise model of a surveyed polyline: curvature and heading noise of Gaussian-smoothed GPS vertices
(Eq. 1 of :mod:`engine.route.detect`), and the position noise estimated from the vertices themselves."""

from __future__ import annotations

import math

import numpy as np

#: Eq. 1 constant: integral of the squared second derivative of a unit Gaussian, 3 / (8 sqrt(pi))
G2 = 3.0 / (8.0 * math.sqrt(math.pi))
#: and of the squared first derivative, 1 / (4 sqrt(pi)) (heading noise)
G1 = 1.0 / (4.0 * math.sqrt(math.pi))
#: heading noise allowed after the light smoothing that precedes the heading (step 3) [rad]
HEADING_NOISE_RAD = 0.03


# ------------------------------------------------------------------------------------ noise model


def curvature_noise_per_m(noise_m: float, spacing_m: float, scale_m):
    """Standard deviation of the Gaussian-smoothed curvature from white position noise [1/m] (Eq. 1).

    sd = sigma sqrt(h int G''^2) = sigma sqrt(3 h / (8 sqrt(pi))) tau^-2.5 for lateral noise sigma at vertex
    spacing h and a Gaussian of standard deviation tau (valid for tau several times h).

    Parameters
    ----------
    noise_m : float
        Position noise sigma of the vertices [m].
    spacing_m : float
        Vertex spacing h [m].
    scale_m : float or array_like
        Smoothing scale tau [m].
    """
    return noise_m * np.sqrt(G2 * spacing_m) * np.asarray(scale_m, dtype=float) ** -2.5  # Eq. 1


def heading_noise_rad(noise_m: float, spacing_m: float, scale_m):
    """Standard deviation of the Gaussian-smoothed heading from white position noise [rad].

    sd = sigma sqrt(h / (4 sqrt(pi))) tau^-1.5 (the first-derivative counterpart of Eq. 1).

    Parameters
    ----------
    noise_m : float
        Position noise sigma [m].
    spacing_m : float
        Vertex spacing h [m].
    scale_m : float or array_like
        Smoothing scale tau [m].
    """
    return noise_m * np.sqrt(G1 * spacing_m) * np.asarray(scale_m, dtype=float) ** -1.5


def vertex_noise_m(x_m, y_m) -> float:
    """Robust estimate of the position noise sigma of polyline vertices [m] (step 1 of the method).

    The Menger curvature k of each vertex triple is 1/R for noise-free points on a circle at any spacing;
    the differences of k between neighbouring triples, times the mean of a b / 2 (a, b the triple's two
    segment lengths), have variance 5 sigma^2 under white lateral noise sigma. sigma = 1.4826 MAD / sqrt(5).
    Returns 0 for fewer than 8 vertices.

    Parameters
    ----------
    x_m, y_m : array_like
        Vertices, consecutive vertices distinct [m].
    """
    x, y = np.asarray(x_m, dtype=float), np.asarray(y_m, dtype=float)
    if x.size < 8:
        return 0.0
    dx, dy = np.diff(x), np.diff(y)
    seg = np.hypot(dx, dy)
    a, b = seg[:-1], seg[1:]
    c = np.hypot(x[2:] - x[:-2], y[2:] - y[:-2])
    cross = dx[:-1] * dy[1:] - dy[:-1] * dx[1:]
    with np.errstate(divide="ignore", invalid="ignore"):
        k = np.where(c > 0, 2.0 * cross / (a * b * c), 0.0)  # Menger curvature
    w = a * b / 2.0
    r = np.diff(k) * 0.5 * (w[:-1] + w[1:])
    mad = np.median(np.abs(r - np.median(r)))
    return float(1.4826 * mad / math.sqrt(5.0))
