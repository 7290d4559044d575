"""The calculator page as the service serves it (no browser needed): headers, assets, package data, and the names
the page sends, checked against the published API and the engine's vehicle spec."""

from __future__ import annotations

import dataclasses
import fnmatch
import re
import tomllib
import typing
from html.parser import HTMLParser
from pathlib import Path

import pytest

import engine
from app.main import create_app
from app.page import WEB_DIR
from app.settings import Settings
from engine.builder.spec import VehicleSpec

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def client():
    from fastapi.testclient import TestClient

    with TestClient(create_app(Settings(cache_backend="memory"))) as c:
        yield c


class Tags(HTMLParser):
    """Every start tag of a document with its attributes."""

    def __init__(self) -> None:
        super().__init__()
        self.tags: list[tuple[str, dict[str, str]]] = []

    def handle_starttag(self, tag, attrs):
        self.tags.append((tag, {k: v or "" for k, v in attrs}))


def page_tags() -> list[tuple[str, dict[str, str]]]:
    parser = Tags()
    parser.feed((WEB_DIR / "index.html").read_text())
    return parser.tags


def test_the_page_is_served_at_the_root_with_a_self_only_policy(client):
    r = client.get("/")
    assert r.status_code == 200 and r.headers["content-type"].startswith("text/html")
    policy = dict(p.strip().split(" ", 1) for p in r.headers["content-security-policy"].split(";"))
    assert policy["default-src"] == "'none'"
    for directive in ("script-src", "style-src", "img-src", "connect-src", "font-src"):
        assert policy[directive] == "'self'", directive  # no other host, no 'unsafe-inline', no 'unsafe-eval'
    assert policy["frame-ancestors"] == "'none'"
    assert r.headers["x-content-type-options"] == "nosniff"
    assert client.head("/").status_code == 200


def test_the_curves_worker_runs_under_the_pages_policy(client):
    """A worker's policy is its own script's response: the curves' worker fetches from this origin only."""
    r = client.get("/web/js/curves-worker.js")
    assert r.status_code == 200
    assert r.headers["content-security-policy"] == client.get("/").headers["content-security-policy"]
    assert "content-security-policy" not in client.get("/web/js/curves.js").headers  # a module runs under the page's


def test_the_page_is_not_part_of_the_api_document(client):
    paths = client.get("/openapi.json").json()["paths"]
    assert "/" not in paths and not [p for p in paths if p.startswith("/web")]


def test_every_asset_and_module_import_is_served_with_its_type(client):
    referenced = {a.get("href") or a.get("src") for t, a in page_tags() if t in ("link", "script")}
    modules = {f"/web/js/{p.name}" for p in (WEB_DIR / "js").glob("*.js")}
    for js in (WEB_DIR / "js").glob("*.js"):
        for name in re.findall(r'from "\./([\w-]+\.js)"', js.read_text()):
            assert (WEB_DIR / "js" / name).exists(), f"{js.name} imports a missing {name}"
    types = {".js": "text/javascript", ".css": "text/css", ".svg": "image/svg+xml"}
    for path in referenced | modules:
        r = client.get(path)
        assert r.status_code == 200, path
        assert r.headers["content-type"].startswith(types[Path(path).suffix]), path  # modules need a JS type
        assert r.headers["x-content-type-options"] == "nosniff"
    assert client.get("/web/no-such-file.js").status_code == 404


def test_no_asset_names_another_host():
    allowed = {"http://www.w3.org/2000/svg"}  # the SVG namespace: a name, never fetched
    for path in WEB_DIR.rglob("*"):
        if path.is_file():
            urls = set(re.findall(r"(?:https?:)?//[\w.-]+\.[a-z]{2,}[^\s\"')]*", path.read_text()))
            assert urls <= allowed, (path.name, urls - allowed)


def test_the_page_files_are_package_data():
    globs = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["package-data"]["app"]
    files = [p.relative_to(WEB_DIR.parent).as_posix() for p in WEB_DIR.rglob("*") if p.is_file()]
    assert files
    assert [f for f in files if not any(fnmatch.fnmatch(f, g) for g in globs)] == []


def test_the_citation_is_the_engines():
    def words(text: str) -> str:
        return " ".join(re.sub(r"<[^>]+>|\*", "", text).split())

    doc = words(engine.__doc__)
    cited = doc[doc.index("Moreno, G. G.") : doc.index("2016).") + len("2016).")]
    html = words((WEB_DIR / "index.html").read_text())
    assert cited in html


def _resolve(schema: dict, path: list[str], components: dict) -> bool:
    """Whether a dotted path names a property of a JSON schema (through $ref, allOf/anyOf/oneOf)."""
    if "$ref" in schema:
        return _resolve(components[schema["$ref"].split("/")[-1]], path, components)
    if not path:
        return True
    for key in ("allOf", "anyOf", "oneOf"):
        if any(_resolve(s, path, components) for s in schema.get(key, [])):
            return True
    props = schema.get("properties", {})
    return path[0] in props and _resolve(props[path[0]], path[1:], components)


def test_every_field_the_page_names_is_a_request_field_of_the_api(client):
    spec = client.get("/openapi.json").json()
    components = spec["components"]["schemas"]
    bodies = [
        op["requestBody"]["content"]["application/json"]["schema"]
        for item in spec["paths"].values()
        for op in item.values()
        if "application/json" in op.get("requestBody", {}).get("content", {})
    ]
    not_json = {"authorization", "body", "spec"}  # a header, a raw upload, the builder spec (checked below)
    if "/v1/routes/assess" not in spec["paths"]:  # the page hides the route upload until the API has it
        not_json |= {"gpx", "geojson", "posted_speed_kmh"}
    names = {n for _, a in page_tags() if "data-field" in a for n in a["data-field"].split()}
    unknown = sorted(
        n
        for n in names - not_json
        if not n.startswith("spec.") and not any(_resolve(b, n.split("."), components) for b in bodies)
    )
    assert unknown == []


def _spec_has(cls: type, path: list[str]) -> bool:
    if not path:
        return True
    if path[0].isdigit():  # a list index: the element type
        return _spec_has(cls, path[1:])
    hints = typing.get_type_hints(cls)
    if path[0] not in hints:
        return False
    inner = [a for a in typing.get_args(hints[path[0]]) if a is not type(None) and a is not Ellipsis]
    target = inner[0] if inner else hints[path[0]]
    return _spec_has(target, path[1:]) if dataclasses.is_dataclass(target) else len(path) == 1


def test_every_builder_box_is_a_field_of_the_vehicle_spec():
    boxes = [a["data-spec"] for _, a in page_tags() if "data-spec" in a]
    assert len(boxes) > 20
    assert [b for b in boxes if not _spec_has(VehicleSpec, b.split("."))] == []


def test_each_url_parameter_is_named_after_the_api_field_it_feeds():
    pairs = [(a["data-param"], a["data-field"].split()[0]) for _, a in page_tags() if "data-param" in a]
    assert len(pairs) >= 17
    assert [(p, f) for p, f in pairs if f.split(".")[-1] != p] == []


def _luminance(hex_colour: str) -> float:
    """WCAG 2.1 relative luminance of an sRGB colour ``#rrggbb``."""
    channels = [int(hex_colour[i : i + 2], 16) / 255 for i in (1, 3, 5)]
    linear = [c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4 for c in channels]
    return 0.2126 * linear[0] + 0.7152 * linear[1] + 0.0722 * linear[2]


def contrast(a: str, b: str) -> float:
    """WCAG 2.1 contrast ratio (L1 + 0.05) / (L2 + 0.05)."""
    la, lb = sorted((_luminance(a), _luminance(b)), reverse=True)
    return (la + 0.05) / (lb + 0.05)


def test_contrast_closed_form():
    # the ratio's end points: black on white 21:1, a colour on itself 1:1
    assert contrast("#000000", "#ffffff") == pytest.approx(21.0)
    assert contrast("#0b4f8a", "#0b4f8a") == pytest.approx(1.0)


def test_text_colours_meet_wcag_aa_on_their_backgrounds():
    css = (WEB_DIR / "css" / "page.css").read_text()
    var = dict(re.findall(r"--([\w-]+):\s*(#[0-9a-fA-F]{6})", css))
    pairs = [  # (text, background) as page.css uses them
        ("ink", "paper"), ("ink", "panel"), ("muted", "paper"), ("muted", "panel"), ("accent", "paper"),
        ("accent-ink", "accent"), ("pass", "pass-bg"), ("fail", "fail-bg"), ("fail", "paper"), ("ink", "flag-bg"),
    ]  # fmt: skip
    for text, background in pairs:
        assert contrast(var[text], var[background]) >= 4.5, (text, background)  # WCAG 2.1 SC 1.4.3 (AA)
    assert contrast("#5f6368", "#eceef1") >= 4.5  # disabled boxes: still readable
    assert contrast(var["focus"], var["paper"]) >= 3.0  # the focus ring (SC 1.4.11, non-text)
