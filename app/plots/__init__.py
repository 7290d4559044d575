"""The thesis's figures for one case as SVG (``POST /v1/plots/*``, :mod:`~app.plots.router`): the curves against
ay/g from the memoised SRT solve, and the minimum radius against the design speed (:mod:`~app.plots.service`, drawn
by :mod:`app.formats.svg`)."""
