"""structlog configuration: one JSON object per line on stdout (the app only; the engine never logs)."""

from __future__ import annotations

import logging
import sys

import orjson
import structlog


def _dumps(obj, **_kw) -> str:
    return orjson.dumps(obj, default=str).decode()


def configure_logging(level: str = "INFO", *, force: bool = False) -> None:
    """Configure structlog for JSON lines, once per process (a later app instance, or a test that captures
    the logs, keeps the configuration in force unless ``force``)."""
    if structlog.is_configured() and not force:
        return
    structlog.configure(
        processors=[
            structlog.contextvars.merge_contextvars,
            structlog.processors.add_log_level,
            structlog.processors.TimeStamper(fmt="iso", utc=True),
            structlog.processors.format_exc_info,
            structlog.processors.JSONRenderer(serializer=_dumps),
        ],
        wrapper_class=structlog.make_filtering_bound_logger(logging.getLevelName(level)),
        logger_factory=structlog.PrintLoggerFactory(sys.stdout),
        cache_logger_on_first_use=False,
    )


def get_logger(name: str = "rollover"):
    return structlog.get_logger(name)
