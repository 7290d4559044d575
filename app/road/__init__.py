"""Curve design: the maximum speed on a curve (``POST /v1/curve-speed``, Eq. 9.1) and the minimum radius
(``POST /v1/min-radius``, Eqs. 9.2-9.3) in :mod:`~app.road.service`."""
