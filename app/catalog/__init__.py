"""Saved vehicles and fleets under the caller's bearer key: the routes (:mod:`~app.catalog.router`), their schemas,
the rules between the routes and the database (:mod:`~app.catalog.service`: validation on write and on every read,
optimistic concurrency, the lookups the computations use) and the keys (:mod:`~app.catalog.auth`). The tables and
migrations are in :mod:`app.db` (``python -m app.db upgrade``)."""
