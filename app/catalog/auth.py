"""Bearer keys for the catalog (saved vehicles and fleets): who may save, and whose rows a request sees.

The keys come from ``ROLLOVER_API_KEYS`` (comma-separated). A key is never logged and never stored: a row's
``owner`` is :func:`owner_of` the key, the hex SHA-256 of a domain-separated key. A plain (unkeyed) hash is
enough because the keys are long random tokens (at least 16 characters, enforced in the settings), not
passwords: there is nothing to brute-force from the hash that is easier than guessing the key itself.

A presented key is checked against every configured key with :func:`hmac.compare_digest` on the fixed-length
digests, without an early exit, so the time taken does not depend on which key (if any) matched, nor on how long
a prefix matched.
"""

from __future__ import annotations

import hashlib
import hmac
from typing import Annotated

from fastapi import Depends
from fastapi.security import HTTPAuthorizationCredentials, HTTPBearer

from app.deps import SettingsDep
from app.settings import Settings

_DOMAIN = b"rollover-owner-v1\x00"

#: the ``bearerAuth`` security scheme of the OpenAPI document; ``auto_error=False``: the service answers
#: its own 401/403 problems
bearer_scheme = HTTPBearer(
    scheme_name="bearerAuth",
    bearerFormat="opaque key from ROLLOVER_API_KEYS",
    description="`Authorization: Bearer <key>`, one of the deployment's `ROLLOVER_API_KEYS`. Needed to save, "
    "change, delete and read saved vehicles and fleets; each key sees only its own.",
    auto_error=False,
)
BearerDep = Annotated[HTTPAuthorizationCredentials | None, Depends(bearer_scheme)]


class CatalogDisabled(Exception):
    """The deployment configures no key: nothing can be saved."""


class NotAuthenticated(Exception):
    """No bearer key, or one that is not configured. ``error`` is RFC 6750's code (None when none was given)."""

    def __init__(self, error: str | None) -> None:
        super().__init__(error or "missing bearer key")
        self.error = error


def owner_of(key: str) -> str:
    """The owner id stored for ``key``: hex SHA-256 of the domain-separated key (64 characters)."""
    return hashlib.sha256(_DOMAIN + key.encode()).hexdigest()


def authenticate(credentials: HTTPAuthorizationCredentials | None, settings: Settings) -> str:
    """The owner id of the request's bearer key.

    Raises :class:`CatalogDisabled` when no key is configured, :class:`NotAuthenticated` when the request has no
    bearer key or one that is not configured.
    """
    keys = settings.api_key_list()
    if not keys:
        raise CatalogDisabled()
    if credentials is None or not credentials.credentials:
        raise NotAuthenticated(None)
    presented = owner_of(credentials.credentials).encode()
    matched = False
    for key in keys:  # every key, no early exit
        matched |= hmac.compare_digest(presented, owner_of(key).encode())
    if not matched:
        raise NotAuthenticated("invalid_token")
    return presented.decode()


async def require_owner(credentials: BearerDep, settings: SettingsDep) -> str:
    """Dependency: the caller's owner id (403 problem when the catalog is disabled, 401 without a valid key)."""
    return authenticate(credentials, settings)


OwnerDep = Annotated[str, Depends(require_owner)]
