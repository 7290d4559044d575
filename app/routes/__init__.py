"""Route assessment: a route as geometry (GeoJSON or GPX, ``POST /v1/routes/assess``, :mod:`~app.routes.router`),
its horizontal curves found (:mod:`engine.route`) and assessed as an alignment's (:mod:`app.alignments.service`),
answered as JSON, GeoJSON or CSV (:mod:`~app.routes.service`)."""
