"""Run the README's curl examples against the app (in process) and print them with their real output.

    python scripts/readme_examples.py           # print the Markdown block
    python scripts/readme_examples.py --write   # replace the block between the README's example markers

Each example is the curl command a user types against `uvicorn app.main:app --host 127.0.0.1 --port 8000` and
what it prints; the same request goes through the app here (a fresh in-memory cache, so the first call is a miss).
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
START, END = "<!-- examples:start -->", "<!-- examples:end -->"
BASE = "http://127.0.0.1:8000"
JSON_TOOL = " | python -m json.tool"


def pretty(response) -> str:
    return json.dumps(response.json(), indent=4)


def cache_headers(response) -> str:
    lines = [f"HTTP/1.1 {response.status_code} {response.reason_phrase}"]
    lines += [f"{k}: {v}" for k, v in response.headers.items() if k.lower() in ("etag", "x-cache", "content-type")]
    return "\n".join(lines)


@dataclass
class Example:
    title: str
    method: str
    path: str
    body: dict[str, Any] | None = None
    pipe: str = JSON_TOOL
    show: Callable[[Any], str] = pretty
    curl_flags: str = "-s"

    def curl(self) -> str:
        if self.method != "POST":
            return f"curl {self.curl_flags} {BASE}{self.path}{self.pipe}"
        return (
            f"curl {self.curl_flags} -X POST {BASE}{self.path} -H 'Content-Type: application/json' \\\n"
            f"  -d '{json.dumps(self.body)}'{self.pipe}"
        )


EXAMPLES = [
    Example("Health", "GET", "/healthz"),
    Example(
        "The presets (ids only; each item is a full record)",
        "GET",
        "/v1/vehicles",
        pipe=" | python -c 'import json,sys; print([v[\"id\"] for v in json.load(sys.stdin)])'",
        show=lambda r: str([v["id"] for v in r.json()]),
    ),
    Example("One preset: the B-train of Table 16", "GET", "/v1/vehicles/table16-btrain"),
    Example(
        "The models (id, equation, reference)",
        "GET",
        "/v1/models",
        pipe=' | python -c \'import json,sys; [print(m["id"], "|", m["equation"], "|", m["reference"]) '
        "for m in json.load(sys.stdin)]'",
        show=lambda r: "\n".join(f"{m['id']} | {m['equation']} | {m['reference']}" for m in r.json()),
    ),
    Example("SRT of the B-train, 3D model, flat road", "POST", "/v1/srt", {"vehicle": "table16-btrain"}),
    Example(
        "The same request again: ETag and X-Cache (now a hit)",
        "POST",
        "/v1/srt",
        {"vehicle": "table16-btrain"},
        pipe=" | grep -iE '^(HTTP|etag|x-cache|content-type)'",
        show=cache_headers,
        curl_flags="-si",
    ),
    Example(
        "SRT with the Table 17 conditions (8 % bank, 4 % downhill, rear LLT limit 0.6) and 3-point curves",
        "POST",
        "/v1/srt",
        {
            "vehicle": "table16-btrain",
            "model": "3d",
            "road": {"bank_percent": 8, "slope_percent": -4},
            "rear_llt_limit": 0.6,
            "include_curves": True,
            "curve_points": 3,
        },
    ),
    Example("Rigid-vehicle SRT (Eq. 2.6)", "POST", "/v1/srt", {"vehicle": "table16-btrain", "model": "rigid"}),
    Example(
        "Maximum curve speed from a given SRT (Table 18)", "POST", "/v1/curve-speed", {"radius_m": 80, "srt": 0.3364}
    ),
    Example(
        "Maximum curve speed from an SRT request (flat road, rear LLT limit 0.6; Table 20 uses 0.202 g at 120 m)",
        "POST",
        "/v1/curve-speed",
        {"radius_m": 120, "vehicle": "table16-btrain", "rear_llt_limit": 0.6},
    ),
    Example(
        "Minimum radius at 60 km/h on an 8 % superelevation with the B-train's SRT on that bank",
        "POST",
        "/v1/min-radius",
        {"design_speed_kmh": 60, "superelevation_percent": 8, "vehicle": "table16-btrain", "rear_llt_limit": 0.6},
    ),
    Example(
        "Minimum radius from a given SRT where rollover governs",
        "POST",
        "/v1/min-radius",
        {"design_speed_kmh": 80, "superelevation_percent": 10, "srt": 0.172},
    ),
    Example(
        "An error: unknown preset (RFC 9457 problem details)",
        "GET",
        "/v1/vehicles/table99",
    ),
    Example(
        "An error: a validation problem names the field and the reason",
        "POST",
        "/v1/srt",
        {"vehicle": "table16-btrain", "road": {"bank_percent": 25}},
    ),
    Example(
        "Prometheus metrics (the service's own counters)",
        "GET",
        "/metrics",
        pipe=" | grep -E '^rollover_cache_lookups_total'",
        show=lambda r: "\n".join(
            line for line in r.text.splitlines() if line.startswith("rollover_cache_lookups_total")
        ),
    ),
]


def render() -> str:
    sys.path.insert(0, str(ROOT))
    import warnings

    warnings.filterwarnings("ignore", message="Using `httpx` with `starlette.testclient`")
    import structlog
    from fastapi.testclient import TestClient

    from app.main import create_app
    from app.settings import Settings

    structlog.configure(
        processors=[structlog.processors.KeyValueRenderer()], logger_factory=structlog.ReturnLoggerFactory()
    )
    out = [START, ""]
    with TestClient(create_app(Settings(cache_backend="memory"))) as client:
        for ex in EXAMPLES:
            response = client.request(ex.method, ex.path, json=ex.body)
            out += [f"**{ex.title}**", "", "```console", f"$ {ex.curl()}", ex.show(response), "```", ""]
    out.append(END)
    return "\n".join(out)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--write", action="store_true", help="replace the example block in README.md")
    args = parser.parse_args(argv)
    block = render()
    if not args.write:
        print(block)
        return 0
    text = README.read_text(encoding="utf-8")
    if START not in text or END not in text:
        print(f"README.md has no {START} ... {END} block", file=sys.stderr)
        return 1
    head, rest = text.split(START, 1)
    _, tail = rest.split(END, 1)
    README.write_text(head + block + tail, encoding="utf-8")
    print("README.md examples updated")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
