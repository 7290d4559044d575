"""Vehicles: the thesis presets (``GET /v1/vehicles``: :mod:`~app.vehicles.router`), the builder that turns a
measurable spec into a record (``POST /v1/vehicles/build``, the payload table, the component library:
``builder_router``, ``builder_service``), the combination presets and builder (``combination_router``,
``combination_builder_service``), and the one step that turns every vehicle reference a computation takes --
preset id, record, spec, combination, combination spec, saved vehicle, fleet -- into engine records
(:mod:`~app.vehicles.resolve`). The shapes of a vehicle and their builders are below the features, in
:mod:`app.vehicle_forms`."""
