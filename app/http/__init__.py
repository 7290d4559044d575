"""The HTTP plumbing every feature shares: the body limits (:mod:`~app.http.bodylimit`), the raw-body fast path
(:mod:`~app.http.fastpath`), the per-request metrics (:mod:`~app.http.request_metrics`), RFC 9457 problem details
(:mod:`~app.http.problems`), content negotiation (:mod:`~app.http.negotiation`), TCP options
(:mod:`~app.http.netopts`), the bodies a route reads itself (:mod:`~app.http.bodies`), computed responses
(:mod:`~app.http.responses`), the schema bases (:mod:`~app.http.schemas`) and the published OpenAPI document
(:mod:`~app.http.openapi`). Nothing here knows a feature."""
