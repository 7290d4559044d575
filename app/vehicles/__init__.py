"""Vehicles: the thesis presets (``GET /v1/vehicles``: :mod:`~app.vehicles.router`, records in
:mod:`~app.vehicle_forms.schemas`), the builder that turns a measurable spec into a record (``POST /v1/vehicles/build``,
the payload table, the component library: ``builder_router``, ``builder_schemas``, ``builder_service``), and the
resolution of every vehicle reference a computation takes -- preset id, record, spec, saved vehicle, fleet -- into
engine records (:mod:`~app.vehicles.refs`)."""
