"""The static rollover threshold: ``POST /v1/srt`` (:mod:`~app.srt.service`), its inverse limits
(``/v1/srt/limits``: ``limits_schemas``, ``limits_service``) and grid sweeps (``/v1/srt/sweep``: ``sweep_schemas``,
``sweep_service``), one router (:mod:`~app.srt.router`). :mod:`app.srt.schemas` also holds the SRT request fields
every computation that takes a vehicle shares (``SrtInputs``, ``VehicleRef``, ``LoadIn``, the targets)."""
