"""Advisory speeds on curves (``POST /v1/advisory-speed``): each method's speed, the plaque's speed, the sign treatment
and the truck rollover warning, over :mod:`engine.road.advisory` and :mod:`engine.road.profile`."""
