"""rollover HTTP service: a thin FastAPI layer over :mod:`engine` (schemas, routers, cache, settings)."""
