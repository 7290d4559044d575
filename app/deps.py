"""FastAPI dependencies and their ``Annotated`` aliases: the app's settings and its result cache.

Both live on ``app.state``: :func:`app.main.create_app` stores the settings it was given (or read from the
environment) and the lifespan opens the cache; a request reads them from its app.
"""

from __future__ import annotations

from typing import Annotated

from fastapi import Depends, Request

from app.compute.cache import ResultCache
from app.settings import Settings


async def get_app_settings(request: Request) -> Settings:
    """The settings of the app serving this request."""
    return request.app.state.settings


async def get_cache(request: Request) -> ResultCache:
    """The app's result cache (opened in the lifespan)."""
    return request.app.state.cache


SettingsDep = Annotated[Settings, Depends(get_app_settings)]
CacheDep = Annotated[ResultCache, Depends(get_cache)]
