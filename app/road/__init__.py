"""Road design: the maximum speed on a curve (``POST /v1/curve-speed``, Eq. 9.1) and the minimum radius
(``POST /v1/min-radius``, Eqs. 9.2-9.3) in :mod:`~app.road.service`; the design standards (``GET
/v1/design-standards``) and their superelevation distribution (``POST /v1/superelevation[/table]``) in
``standards_router``, ``standards_schemas``, ``standards_service``."""
