"""Property-based fuzzing of the catalog operations (and the preset routes that share their paths), in process,
on a fresh temporary SQLite database, once with a valid bearer key and once without any.

Checks on every generated request: no 5xx, status codes, content types, headers and bodies as the spec declares,
invalid input refused with a 4xx, and (schemathesis's ``ignored_auth``) that an operation which answered 2xx with
the key answers 401/403 without it, and no schema-valid request refused for its shape (``fuzzing.py``). Not
checked: ``positive_data_acceptance`` (a schema-valid request may still be refused: a record the engine finds
impossible, an id that does not exist, a stale If-Match).
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import pytest
import schemathesis
from hypothesis import settings

from app.main import create_app
from app.settings import Settings

from .fuzzing import CHECKS, FUZZ, config

KEY = "fuzz-key-" + "k" * 24
_TMP = tempfile.TemporaryDirectory(prefix="rollover-catalog-fuzz-")
SETTINGS = Settings(cache_backend="memory", database_url=f"sqlite:///{Path(_TMP.name) / 'fuzz.db'}", api_keys=KEY)
app = create_app(SETTINGS)
schema = schemathesis.openapi.from_asgi("/openapi.json", app, config=config()).include(
    path_regex=r"^/v1/(vehicles|fleets)"
)


@pytest.fixture(scope="module", autouse=True)
def _fresh_database():
    yield
    db = getattr(app.state, "db", None)
    if db is not None:
        db.dispose()
    _TMP.cleanup()


@schema.parametrize()
@settings(max_examples=25, **FUZZ)
def test_with_a_key(case):
    case.call_and_validate(headers={"Authorization": f"Bearer {KEY}"}, **CHECKS)


@schema.parametrize()
@settings(max_examples=15, **FUZZ)
def test_without_a_key(case):
    case.call_and_validate(**CHECKS)
