"""FastAPI dependencies and their ``Annotated`` aliases."""

from __future__ import annotations

from typing import Annotated

from fastapi import Depends, Request

from .cache import ResultCache, make_cache
from .settings import Settings, get_settings

SettingsDep = Annotated[Settings, Depends(get_settings)]


def resolve_settings(app) -> Settings:
    """The settings in force for ``app``: a test's ``dependency_overrides[get_settings]`` wins."""
    return app.dependency_overrides.get(get_settings, get_settings)()


def get_cache(request: Request) -> ResultCache:
    """The app's result cache (made in the lifespan; made here when a test transport skips the lifespan)."""
    app = request.app
    if getattr(app.state, "cache", None) is None:
        app.state.cache = make_cache(resolve_settings(app))
    return app.state.cache


CacheDep = Annotated[ResultCache, Depends(get_cache)]
