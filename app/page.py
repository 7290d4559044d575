"""GET /: the calculator page, and its static assets (HTML, CSS, ES modules from ``app/web/``) under ``/web/``.

The page is the API's first client: it calls nothing but the public ``/v1`` operations (and ``/openapi.json`` to
see which ones this deployment has). It loads nothing from another host, and its Content-Security-Policy says so:
scripts, styles, images, fonts and requests from this origin only, no inline script or style, no plug-ins, no
framing. It is not part of the OpenAPI document, which describes the JSON API.

This module sits beside ``app/web/``, not in it: everything in that folder is served as it is (and installed as
package data), so no Python file belongs there.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from fastapi import APIRouter, FastAPI, Request
from fastapi.openapi.docs import get_redoc_html
from fastapi.responses import FileResponse, HTMLResponse
from starlette.responses import Response
from starlette.staticfiles import StaticFiles

#: the page's files, installed with the package (pyproject's package-data)
WEB_DIR = Path(__file__).resolve().parent / "web"
#: where the assets are served
ASSETS_PATH = "/web"

#: self only: nothing from another host, no inline script or style, no eval, no plug-ins, not framed
CONTENT_SECURITY_POLICY = "; ".join(
    (
        "default-src 'none'",
        "script-src 'self'",
        "style-src 'self'",
        "img-src 'self'",
        "font-src 'self'",
        "connect-src 'self'",
        "manifest-src 'self'",
        "base-uri 'none'",
        "form-action 'self'",
        "frame-ancestors 'none'",
    )
)
#: every response of the page and its assets: no MIME sniffing, revalidate (ETag) so an upgrade is seen at once
ASSET_HEADERS = {"X-Content-Type-Options": "nosniff", "Cache-Control": "no-cache"}
PAGE_HEADERS = {
    **ASSET_HEADERS,
    "Content-Security-Policy": CONTENT_SECURITY_POLICY,
    "Referrer-Policy": "no-referrer",
    "X-Frame-Options": "DENY",
}

router = APIRouter(include_in_schema=False)


@router.api_route("/", methods=["GET", "HEAD"], name="calculator_page")
def calculator_page() -> FileResponse:
    """The calculator page (HTML); its state is in the query string (see the README, "The calculator page")."""
    return FileResponse(WEB_DIR / "index.html", media_type="text/html; charset=utf-8", headers=PAGE_HEADERS)


class WebAssets(StaticFiles):
    """The page's static files, with :data:`ASSET_HEADERS`; a worker script (``*-worker.js``) with the page's
    Content-Security-Policy too (a worker's policy is its own script's: it fetches from this origin only)."""

    def file_response(self, full_path: Any, *args: Any, **kwargs: Any) -> Response:
        response = super().file_response(full_path, *args, **kwargs)
        response.headers.update(ASSET_HEADERS)
        if str(full_path).endswith("-worker.js"):
            response.headers["Content-Security-Policy"] = CONTENT_SECURITY_POLICY
        return response


#: ``/redoc``: ReDoc's bundle draws the Redocly logo from cdn.redoc.ly (an ``<img>`` its options cannot turn off; it
#: hides itself when the image fails). Everything from this origin (the bundle styles itself inline, searches in a
#: blob worker and may compile schemas with eval), nothing from another host: the logo is refused before any request.
REDOC_POLICY = "default-src 'self' data: blob: 'unsafe-inline' 'unsafe-eval'; frame-ancestors 'none'; base-uri 'none'"
#: where fastapi-offline serves its copies of the docs' assets (``FastAPIOffline(static_url=...)``'s default)
OFFLINE_DOCS = "/static-offline-docs"


def install_redoc(app: FastAPI, path: str = "/redoc") -> None:
    """ReDoc at ``path`` as fastapi-offline serves it (its own copy of the bundle, no Google fonts), with
    :data:`REDOC_POLICY`, so the page loads nothing from another host."""

    @app.get(path, include_in_schema=False)
    async def redoc_html(request: Request) -> HTMLResponse:
        root = request.scope.get("root_path", "")
        page = get_redoc_html(
            openapi_url=f"{root}{app.openapi_url}",
            title=f"{app.title} - ReDoc",
            redoc_js_url=f"{root}{OFFLINE_DOCS}/redoc.standalone.js",
            redoc_favicon_url=f"{root}{OFFLINE_DOCS}/favicon.png",
            with_google_fonts=False,
        )
        page.headers["Content-Security-Policy"] = REDOC_POLICY
        return page


def install_page(app: FastAPI) -> None:
    """Serve the page at ``/`` and its assets under :data:`ASSETS_PATH`."""
    app.include_router(router)
    app.mount(ASSETS_PATH, WebAssets(directory=WEB_DIR), name="web")
