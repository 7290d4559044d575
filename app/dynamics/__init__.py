"""The combination in motion (``POST /v1/dynamics/...``) and the PBS screening (``POST /v1/pbs``): one router module
(:mod:`~app.dynamics.router`), the schemas (:mod:`~app.dynamics.schemas`) and the service
(:mod:`~app.dynamics.service`) over :mod:`engine.dynamics`. Every answer is an indicative screening."""
