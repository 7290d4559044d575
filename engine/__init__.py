"""rollover engine: static rollover threshold of long combination vehicles (pure numerics).

The engine never does I/O, never logs and keeps no global state. Public entry points:

- :func:`engine.threshold.rollover_threshold` -- SRT of a vehicle on a road with a load case (3D, 2D or a
  closed-form model of Ch. 2), optionally with the curves against ay/g;
- :func:`engine.threshold.sweep` -- the same over a grid of road/load cases (Tables 17 and 19);
- :mod:`engine.road` -- Eqs. 9.1-9.3 and Table 21;
- :mod:`engine.vehicles` -- the vehicle record and the thesis presets;
- :mod:`engine.davies` -- the generic Davies-method statics core.
"""

#: bumped whenever a change can alter a number the engine returns (it is part of every cache key)
ENGINE_VERSION = "1.1.0"
__version__ = ENGINE_VERSION
