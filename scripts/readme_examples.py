"""Run the curl examples of docs/examples.md and of the README against the app (in process), with their real output.

    python scripts/readme_examples.py            # print docs/examples.md's Markdown block
    python scripts/readme_examples.py --readme   # print the README's quick-start block
    python scripts/readme_examples.py --write    # replace both blocks between their markers

Each example is the curl command a user types against `uvicorn app.main:app --host 127.0.0.1 --port 8000` and
what it prints; the same request goes through the app here (a fresh in-memory cache, so the first call is a miss).
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES_DOC = ROOT / "docs" / "examples.md"
README = ROOT / "README.md"
START, END = "<!-- examples:start -->", "<!-- examples:end -->"
README_START, README_END = "<!-- readme-examples:start -->", "<!-- readme-examples:end -->"
BASE = "http://127.0.0.1:8000"
JSON_TOOL = " | python -m json.tool"


def pretty(response) -> str:
    return json.dumps(response.json(), indent=4)


def cache_headers(response) -> str:
    lines = [f"HTTP/1.1 {response.status_code} {response.reason_phrase}"]
    lines += [f"{k}: {v}" for k, v in response.headers.items() if k.lower() in ("etag", "x-cache", "content-type")]
    return "\n".join(lines)


def run_shell(command: str, stdin: bytes | None = None, files: dict[str, bytes] | None = None) -> str:
    """Run the example's own shell command (a pipe, or the command after ``-o file &&``) on the real response, in
    a scratch directory, so the README shows exactly what it prints."""
    with tempfile.TemporaryDirectory() as tmp:
        for name, data in (files or {}).items():
            (Path(tmp) / name).write_bytes(data)
        done = subprocess.run(
            ["bash", "-c", command], input=stdin, cwd=tmp, capture_output=True, check=True, env={**os.environ}
        )
    return done.stdout.decode().rstrip("\n")


@dataclass
class Example:
    title: str
    method: str
    path: str
    body: dict[str, Any] | None = None
    pipe: str = JSON_TOOL
    show: Callable[[Any], str] | None = None
    curl_flags: str = "-s"
    headers: dict[str, str] = field(default_factory=dict)  # besides Content-Type (e.g. Accept)
    raw: str | None = None  # a file sent as it is (--data-binary), with headers["Content-Type"]
    upload: str | None = None  # a file of examples/ sent as it is (--data-binary @examples/...), or with ``form``
    form: bool = False  # ... as the part `file` of a multipart/form-data body (-F file=@examples/...)
    output: str | None = None  # curl -o <file>, then ``after`` runs on it
    after: str = ""
    note: str = ""  # a line of prose under the title
    heading: str = ""  # starts a new ### section of the examples

    def curl(self) -> str:
        if self.method != "POST":
            return f"curl {self.curl_flags} {BASE}{self.path}{self.pipe}"
        url = f"'{BASE}{self.path}'" if "?" in self.path else f"{BASE}{self.path}"
        tail = f" -o {self.output} && {self.after}" if self.output else self.pipe
        if self.upload is not None:  # run from the repository root: examples/ is there
            headers = dict(self.headers)
            if self.form:
                headers.pop("Content-Type", None)  # curl -F writes multipart/form-data with its boundary
                data = f"-F file=@examples/{self.upload}"
            else:
                data = f"--data-binary @examples/{self.upload}"
            flags = "".join(f" -H '{k}: {v}'" for k, v in headers.items())
            return f"curl {self.curl_flags} -X POST {url}{flags} \\\n  {data}{tail}"
        headers = {"Content-Type": "application/json", **self.headers}
        flags = " ".join(f"-H '{k}: {v}'" for k, v in headers.items())
        data = f"--data-binary $'{ansi_c(self.raw)}'" if self.raw is not None else f"-d '{json.dumps(self.body)}'"
        return f"curl {self.curl_flags} -X POST {url} {flags} \\\n  {data}{tail}"

    def send(self, client):
        if self.upload is not None:
            data = (ROOT / "examples" / self.upload).read_bytes()
            if self.form:
                extra = {k: v for k, v in self.headers.items() if k != "Content-Type"} or None
                return client.request(self.method, self.path, files={"file": (self.upload, data)}, headers=extra)
            return client.request(self.method, self.path, content=data, headers=self.headers)
        headers = {"Content-Type": "application/json", **self.headers}
        if self.raw is not None:
            return client.request(self.method, self.path, content=self.raw.encode(), headers=headers)
        return client.request(self.method, self.path, json=self.body, headers=self.headers or None)

    def shown(self, response) -> str:
        if self.show is not None:
            return self.show(response)
        if self.output:
            return run_shell(self.after, files={self.output: response.content})
        if self.pipe == JSON_TOOL:
            return pretty(response)
        if not self.pipe:
            return response.text.rstrip("\n")
        return run_shell(self.pipe.removeprefix(" | "), stdin=response.content)


def ansi_c(text: str) -> str:
    """Text inside bash's $'...' quoting: backslashes, single quotes and newlines escaped."""
    return text.replace("\\", "\\\\").replace("'", "\\'").replace("\n", "\\n")


BTRAIN = "table16-btrain"
sys.path.insert(0, str(ROOT))
from app.routes.schemas import EXAMPLE_GEOJSON  # noqa: E402
from app.vehicle_forms.builder_schemas import EXAMPLE_SPEC  # noqa: E402
from app.vehicle_forms.combination_builder_schemas import EXAMPLE_COMBINATION_SPEC  # noqa: E402
from scripts.docblock import split_block  # noqa: E402

CURVES_CSV = (
    "id,radius_m,superelevation_percent,grade_percent,posted_speed_kmh\n"
    "C1,120,8,-4,70\nC2,350,6,0,90\nC3,90,8,2,60\nC4,600,8,-4,100\n"
)
LANDXML = (
    '<?xml version="1.0"?>\n<LandXML xmlns="http://www.landxml.org/schema/LandXML-1.2" version="1.2"><Alignments>\n'
    '<Alignment name="BR-101" staStart="0"><CoordGeom>\n'
    '<Line staStart="0" length="200"><Start>0 0</Start><End>0 200</End></Line>\n'
    '<Curve rot="cw" radius="250" length="120" staStart="200" name="K1"/>\n'
    '<Curve rot="ccw" radius="140" length="90" staStart="380" name="K2"/>\n'
    "</CoordGeom></Alignment></Alignments></LandXML>\n"
)


def svg_series(path: str) -> str:
    """A one-line check of a plot: each series with its number of points, then the markers."""
    return (
        'python -c \'import sys, xml.etree.ElementTree as ET; ns = "{http://www.w3.org/2000/svg}"; '
        'gs = list(ET.parse(sys.argv[1]).getroot().iter(ns + "g")); '
        '[print(g.get("data-name"), len(g.find(ns + "polyline").get("data-x").split()), "points") '
        'for g in gs if g.get("class") == "series"]; '
        '[print("marker at", g.get("data-x")) for g in gs if g.get("class") == "marker"]\' '
        f"{path}"
    )


EXAMPLES = [
    Example("Health", "GET", "/healthz", heading="Vehicles, SRT, curve speed and minimum radius"),
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
    Example(
        "The combination presets (id and roll-coupled units)",
        "GET",
        "/v1/combinations",
        pipe=" | python -c 'import json,sys; "
        '[print(c["id"], c["roll_coupled_units"]) for c in json.load(sys.stdin)]\'',
        show=lambda r: "\n".join(f"{c['id']} {c['roll_coupled_units']}" for c in r.json()),
    ),
    Example(
        "One combination preset with the source of every value (the first three shown)",
        "GET",
        "/v1/combinations/btrain-table16",
        pipe=' | python -c \'import json,sys; s = json.load(sys.stdin)["sources"]; '
        '[print(k, "<-", s[k]) for k in list(s)[:3]]\'',
        show=lambda r: "\n".join(f"{k} <- {v}" for k, v in list(r.json()["sources"].items())[:3]),
    ),
    Example(
        "SRT of the whole B-double (the whole-combination model): each roll-coupled unit and the lift-offs",
        "POST",
        "/v1/srt",
        {"vehicle": "btrain-table16"},
        pipe=" | python -c 'import json,sys; r = json.load(sys.stdin); "
        'print(r["srt"], r["last_unit_front_llt_ratio"]); [print(e) for e in r["lift_sequence"]]\'',
        show=lambda r: "\n".join(
            [f"{r.json()['srt']} {r.json()['last_unit_front_llt_ratio']}", *(str(e) for e in r.json()["lift_sequence"])]
        ),
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
        "Advisory speed of one curve (150 m, 6 %, posted 100 km/h) with the B-train's rollover check: the plaque's "
        "speed, each method's, the treatment and the W1-13 rule",
        "POST",
        "/v1/advisory-speed",
        {
            "radius_m": 150,
            "superelevation_percent": 6,
            "deflection_deg": 40,
            "posted_speed_kmh": 100,
            "vehicle": BTRAIN,
        },
        pipe=' | python -c \'import json,sys; r = json.load(sys.stdin); print(r["advisory_speed_mph"], "mph by", '
        'r["governed_by"]); [print(m["id"], None if m["speed_kmh"] is None else round(m["speed_kmh"], 1), '
        '"legacy" if m["legacy"] else "", "" if m["verified"] else "unverified") for m in r["methods"]]; '
        'print(r["treatment"]["devices"]); print("W1-13", r["truck_rollover_warning"]["recommended"])\'',
        heading="Advisory speeds: `POST /v1/advisory-speed`",
        note="The Design Method's curve speed model could not be read in its primary text: it is listed, unverified, "
        "without a speed (docs/advisory.md).",
    ),
    Example(
        "SRT targets and the tilt-table angle: the rigid B-train against PBS / NZ and a fleet's own 0.45 g",
        "POST",
        "/v1/srt",
        {"vehicle": BTRAIN, "model": "rigid", "targets": {"general": 0.35, "dangerous_goods": 0.40, "fleet": 0.45}},
        pipe=' | python -c \'import json,sys; r = json.load(sys.stdin); print("srt", r["srt"], "tilt", '
        'r["tilt_table_angle_deg"]); [print(t) for t in r["targets"]]\'',
        heading="SRT targets and the tilt-table angle",
    ),
    Example(
        "Inverse limit: the highest load (CG height above the chassis) at which the B-train still has 0.30 g, "
        "and the same limit from 0 to 20 % overweight",
        "POST",
        "/v1/srt/limits",
        {"vehicle": BTRAIN, "parameter": "cg_height_above_chassis_m", "target_srt_g": 0.30},
        heading="Inverse limits: `POST /v1/srt/limits`",
    ),
    Example(
        "Sweep: Table 17's bank x slope grid (rear LLT limit 0.6) as CSV",
        "POST",
        "/v1/srt/sweep",
        {"vehicle": BTRAIN, "rear_llt_limit": 0.6, "grid": {"bank_percent": [0, 4, 8], "slope_percent": [-4, 0, 4]}},
        headers={"Accept": "text/csv"},
        pipe="",
        heading="Sweeps: `POST /v1/srt/sweep`",
    ),
    Example(
        "Alignment assessment: two curves for the B-train (rear LLT limit 0.6)",
        "POST",
        "/v1/alignments/assess",
        {
            "vehicle": BTRAIN,
            "rear_llt_limit": 0.6,
            "curves": [
                {"id": "C1", "radius_m": 120, "superelevation_percent": 8, "grade_percent": -4, "posted_speed_kmh": 70},
                {"id": "C2", "radius_m": 350, "superelevation_percent": 6, "posted_speed_kmh": 90},
            ],
        },
        heading="Alignment assessment: `POST /v1/alignments/assess` (and `/csv`, `/landxml`, `/ifc`)",
    ),
    Example(
        "Alignment assessment of a CSV file for two vehicles, answered as CSV (some of its columns)",
        "POST",
        "/v1/alignments/assess/csv?vehicle=table16-btrain&vehicle=table23-semitrailer&rear_llt_limit=0.6",
        raw=CURVES_CSV,
        headers={"Content-Type": "text/csv", "Accept": "text/csv"},
        pipe=" | cut -d, -f2,3,8,14,15,17-21",
        note="`--data-binary @curves.csv` sends a file the same way.",
    ),
    Example(
        "Alignment assessment of a LandXML 1.2 alignment (superelevation, grade and posted speed as defaults)",
        "POST",
        "/v1/alignments/assess/landxml?vehicle=table16-btrain&superelevation_percent=6&grade_percent=-2"
        "&posted_speed_kmh=80",
        raw=LANDXML,
        headers={"Content-Type": "application/xml"},
        pipe=' | python -c \'import json,sys; v = json.load(sys.stdin)["vehicles"][0]; print(v["summary"]); '
        '[print(r["id"], r["station_m"], r["srt_g"], r["safe_speed_kmh"], r["governed_by"], '
        'r["margin_kmh"], r["flagged"]) for r in v["rows"]]\'',
    ),
    Example(
        "A spreadsheet's CSV as it saves it (`;`, decimal commas, a byte-order mark, CRLF), uploaded as a form file: "
        "the answer names the dialect it read",
        "POST",
        "/v1/alignments/assess/csv?vehicle=table16-btrain",
        upload="curves-semicolon.csv",
        form=True,
        pipe=' | python -c \'import json,sys; r = json.load(sys.stdin); print(r["csv_dialect"]); [print(x["id"], '
        'x["radius_m"], x["superelevation_percent"], x["grade_percent"], x["safe_speed_kmh"], x["governed_by"]) '
        'for x in r["vehicles"][0]["rows"]]\'',
        note="Run from the repository root: `examples/` holds the sample files (a CSV in each dialect, LandXML, GPX, "
        "GeoJSON of one road with two curves, see examples/README.md); `--data-binary @examples/curves-comma.csv -H "
        "'Content-Type: text/csv'` sends a file as the body instead.",
    ),
    Example(
        "The same road's LandXML alignment as the body (superelevation and grade as defaults for its curves)",
        "POST",
        "/v1/alignments/assess/landxml?vehicle=table16-btrain&superelevation_percent=7.5&grade_percent=3.5",
        upload="alignment.xml",
        headers={"Content-Type": "application/xml"},
        pipe=' | python -c \'import json,sys; r = json.load(sys.stdin); [print(x["id"], x["station_m"], '
        'x["radius_m"], x["safe_speed_kmh"], x["governed_by"]) for x in r["vehicles"][0]["rows"]]\'',
    ),
    Example(
        "The same road as an IFC 4.3 file, uploaded as a form file: its grade (profile) and superelevation (cant) "
        "come from the file",
        "POST",
        "/v1/alignments/assess/ifc?vehicle=table16-btrain",
        upload="road.ifc",
        form=True,
        pipe=' | python -c \'import json,sys; r = json.load(sys.stdin); print(r["reading"]["format"], '
        'r["reading"]["superelevation_from"]); [print(x["id"], x["station_m"], x["radius_m"], '
        'x["superelevation_percent"], x["grade_percent"], x["safe_speed_kmh"], x["governed_by"]) '
        'for x in r["vehicles"][0]["rows"]]\'',
    ),
    Example(
        "An error in an uploaded CSV names the row and the column",
        "POST",
        "/v1/alignments/assess/csv?vehicle=table16-btrain",
        raw="id,radius_m,superelevation_percent\nC1,120,8\nC2,0,6\n",
        headers={"Content-Type": "text/csv"},
    ),
    Example(
        "Minimum radius at 80 km/h to DNIT's table (IPR-706 Quadro 5.4.3.1 f_max) instead of AASHTO 2018's",
        "POST",
        "/v1/min-radius",
        {"design_speed_kmh": 80, "superelevation_percent": 8, "vehicle": BTRAIN, "design_standard": "dnit-1999"},
        pipe=' | python -c \'import json,sys; r = json.load(sys.stdin); [print(k, r[k]) for k in ("design_standard", '
        '"side_friction", "side_friction_source", "side_friction_min_radius_m", "rollover_min_radius_m", '
        '"governed_by")]\'',
        heading="Design standards: `GET /v1/design-standards`, `POST /v1/superelevation`",
    ),
    Example(
        "The design standards (id, speed range, citation)",
        "GET",
        "/v1/design-standards",
        pipe=' | python -c \'import json,sys; [print(s["id"], s["speed_range_kmh"], "|", '
        's["citation"][:100]) for s in json.load(sys.stdin)["standards"]]\'',
    ),
    Example(
        "The superelevation a 300 m curve gets at 80 km/h with e_max 8 % (AASHTO Method 5)",
        "POST",
        "/v1/superelevation",
        {"design_standard": "aashto-2018", "design_speed_kmh": 80, "radius_m": 300, "max_superelevation_percent": 8},
    ),
    Example(
        "Build a semi-trailer from what can be measured (library tyre and suspension); the record's SRT-relevant "
        "fields and how two of them were obtained",
        "POST",
        "/v1/vehicles/build",
        {"spec": EXAMPLE_SPEC},
        pipe=' | python -c \'import json,sys; r = json.load(sys.stdin); v = r["vehicle"]; [print(k, v[k]) for k in '
        '("weight_kn", "cg_height_above_chassis_m", "suspension_height_m", "tire_stiffness_kn_per_m")]; '
        '[print(k, r["derivation"][k]) for k in ("weight_kn", "tire_stiffness_kn_per_m")]\'',
        heading="The vehicle builder: `POST /v1/vehicles/build`, `GET /v1/components`",
    ),
    Example(
        "The same spec straight into an SRT request (`vehicle: {spec: ...}`)",
        "POST",
        "/v1/srt",
        {"vehicle": {"spec": EXAMPLE_SPEC}},
        pipe=' | python -c \'import json,sys; r = json.load(sys.stdin); print(r["srt"], [t["meets"] for t in '
        'r["targets"]])\'',
    ),
    Example(
        "The component library's tyres and suspensions (ids)",
        "GET",
        "/v1/components",
        pipe=' | python -c \'import json,sys; r = json.load(sys.stdin); print([t["id"] for t in r["tyres"]]); '
        'print([s["id"] for s in r["suspensions"]])\'',
    ),
    Example(
        "Build a tractor-semitrailer from what can be measured of each unit (tyre sizes, suspension types, tare and "
        "payload with deck and load heights, a library fifth wheel): each unit's sprung mass and CG, the axle loads "
        "and where one value comes from",
        "POST",
        "/v1/combinations/build",
        {"combination_spec": EXAMPLE_COMBINATION_SPEC},
        pipe=' | python -c \'import json,sys; r = json.load(sys.stdin); [print(u["id"], round(u["sprung_mass_kg"]), '
        'round(u["sprung_cg_height_m"], 3), round(u["sprung_cg_position_m"], 3)) for u in r["units"]]; '
        '[print(a["unit"], a["group"], round(a["load_kg"])) for a in r["axle_loads"]]; '
        'd = r["derivation"]["units[1].groups[0].roll_stiffness_knm_per_rad"]; '
        'print(round(d["value"], 1), d["method"], d["source"][:90])\'',
        heading="The combination builder: `POST /v1/combinations/build`",
        note="Every unit kind is built the same way (rigid truck, tractor, semitrailer, B-train lead trailer, "
        "converter dolly, full trailer); [docs/vehicles.md](vehicles.md#building-a-combination) explains the inputs.",
    ),
    Example(
        "The same combination spec straight into an SRT request (`vehicle: {combination_spec: ...}`)",
        "POST",
        "/v1/srt",
        {"vehicle": {"combination_spec": EXAMPLE_COMBINATION_SPEC}},
        pipe=' | python -c \'import json,sys; r = json.load(sys.stdin); print(r["model"], r["srt"]); '
        '[print(e) for e in r["lift_sequence"]]\'',
    ),
    Example(
        "Acceptable payload by load height, and load height by payload, for a 0.45 g target (TERNZ's table)",
        "POST",
        "/v1/vehicles/payload-table",
        {"spec": EXAMPLE_SPEC, "target_srt_g": 0.45, "load_heights_m": [2.0, 2.4, 2.8], "rows": 3},
        headers={"Accept": "text/csv"},
        pipe="",
    ),
    # the routes' examples print their numbers rounded: a route's radii come out of iterative fits whose last digits
    # follow the machine's floating point (another CPU's LAPACK kernels), and a person reads a few digits anyway
    Example(
        "A route as GeoJSON: the curves found in it (geometry) and their assessment for the B-train",
        "POST",
        "/v1/routes/assess",
        {"vehicle": BTRAIN, "geojson": EXAMPLE_GEOJSON, "superelevation_percent": 6.0, "rear_llt_limit": 0.6},
        pipe=' | python -c \'import json,sys; r = json.load(sys.stdin); [print(p["id"], p["direction"], '
        'round(p["radius_m"], 1), "+-", p["radius_std_m"] and round(p["radius_std_m"], 1), "m;", '
        'round(p["length_m"]), "m long;", '
        'round(a["srt_g"], 4), "g;", round(a["safe_speed_kmh"], 2), "km/h", a["governed_by"], '
        'round(a["margin_kmh"], 2), a["flagged"]) for p in r["curves"] for a in [p["assessment"]]]\'',
        heading="Routes: `POST /v1/routes/assess` (and `/gpx`, `/geojson`)",
        note="A GPX track goes in `gpx` (the file's text) instead, or as it is to `/v1/routes/assess/gpx` (below); "
        "`Accept: application/geo+json` answers the curves as a GeoJSON FeatureCollection for a GIS; "
        "[docs/routes.md](routes.md) explains the curve detection and its accuracy.",
    ),
    Example(
        "A GPX track as it is: the body of `POST /v1/routes/assess/gpx`, the options in the query",
        "POST",
        "/v1/routes/assess/gpx?vehicle=table16-btrain&superelevation_percent=7.5&posted_speed_kmh=60",
        upload="road.gpx",
        headers={"Content-Type": "application/gpx+xml"},
        pipe=' | python -c \'import json,sys; r = json.load(sys.stdin); [print(p["id"], p["direction"], '
        'round(p["radius_m"], 1), "m from", round(p["start_m"]), "m;", round(a["safe_speed_kmh"], 2), "km/h", '
        'a["governed_by"], round(a["margin_kmh"], 2)) for p in r["curves"] for a in [p["assessment"]]]\'',
        note="The same answer, byte for byte, as `POST /v1/routes/assess` with the file's text in `gpx`; the sample "
        "road's curves are K1 (right, R 250.5 m from 300 m) and K2 (left, R 180 m from 830 m).",
    ),
    Example(
        "A GeoJSON file uploaded as a form file: `POST /v1/routes/assess/geojson`",
        "POST",
        "/v1/routes/assess/geojson?vehicle=table16-btrain&superelevation_percent=7.5&posted_speed_kmh=60",
        upload="road.geojson",
        form=True,
        pipe=' | python -c \'import json,sys; r = json.load(sys.stdin); [print(p["id"], p["direction"], '
        'round(p["radius_m"], 1), "m from", round(p["start_m"]), "m;", round(a["safe_speed_kmh"], 2), "km/h", '
        'a["governed_by"], round(a["margin_kmh"], 2)) for p in r["curves"] for a in [p["assessment"]]]\'',
        note="`--data-binary @examples/road.geojson -H 'Content-Type: application/geo+json'` sends it as the body.",
    ),
    Example(
        "Plot: tire normal loads against ay/g (thesis Fig. 92), saved and checked",
        "POST",
        "/v1/plots/tire-loads",
        {"vehicle": BTRAIN},
        output="tire-loads.svg",
        after=svg_series("tire-loads.svg"),
        note="`/v1/plots/llt`, `/v1/plots/roll` and `/v1/plots/cg-path` take the same body.",
        heading="Plots: `POST /v1/plots/...` (SVG)",
    ),
    Example(
        "Plot: minimum radius against design speed, Eq. 9.2 against Eq. 9.3 (thesis Figs. 108-114)",
        "POST",
        "/v1/plots/min-radius",
        {"vehicle": BTRAIN, "superelevation_percent": 4, "rear_llt_limit": 0.6, "load": {"vertical_offset_m": 0.5}},
        output="min-radius.svg",
        after=svg_series("min-radius.svg"),
    ),
    Example(
        "Single lane change of the A-double (88 km/h, 0.4 Hz, 0.15 g): rearward amplification, HSTO, peak LTR",
        "POST",
        "/v1/dynamics/lane-change",
        {"vehicle": "adouble", "speed_kmh": 88},
        pipe=" | python -c 'import json,sys; r = json.load(sys.stdin); "
        'print(round(r["rearward_amplification"], 6), round(r["high_speed_transient_offtracking_m"], 6), '
        'round(r["steer_axle_lateral_offset_m"], 6)); '
        '[print(u["units"], round(u["peak_load_transfer_ratio"], 6)) for u in r["roll_coupled_units"]]; '
        'print(r["validity"])\'',
        show=lambda r: "\n".join(
            [
                f"{round(r.json()['rearward_amplification'], 6)} "
                f"{round(r.json()['high_speed_transient_offtracking_m'], 6)} "
                f"{round(r.json()['steer_axle_lateral_offset_m'], 6)}",
                *(f"{u['units']} {round(u['peak_load_transfer_ratio'], 6)}" for u in r.json()["roll_coupled_units"]),
                str(r.json()["validity"]),
            ]
        ),
        heading="The combination in motion: `POST /v1/dynamics/...` and `/v1/pbs` (indicative screening)",
        note="Every dynamics answer carries `screening: true`, `validity` and the `parameters` used with their "
        "sources (docs/dynamics.md).",
    ),
    Example(
        "Rearward amplification against frequency, and its worst frequency",
        "POST",
        "/v1/dynamics/frequency-response",
        {"vehicle": "adouble", "frequencies_hz": [0.2, 0.4, 0.8]},
        pipe=" | python -c 'import json,sys; r = json.load(sys.stdin); "
        'print(r["frequencies_hz"], [round(x, 6) for x in r["rearward_amplification"]], '
        'round(r["worst_frequency_hz"], 4))\'',
        show=lambda r: (
            f"{r.json()['frequencies_hz']} {[round(x, 6) for x in r.json()['rearward_amplification']]} "
            f"{round(r.json()['worst_frequency_hz'], 4)}"
        ),
    ),
    Example(
        "Pulse steer: yaw damping of the rearmost articulation beside the least-damped mode",
        "POST",
        "/v1/dynamics/pulse-steer",
        {"vehicle": "adouble", "speed_kmh": 100},
        pipe=' | python -c \'import json,sys; r = json.load(sys.stdin); m = r["least_damped_mode"]; '
        'print(round(r["yaw_damping_ratio"], 6), r["articulation"], round(m["damping_ratio"], 6), '
        'round(m["frequency_hz"], 6))\'',
        show=lambda r: (
            f"{round(r.json()['yaw_damping_ratio'], 6)} {r.json()['articulation']} "
            f"{round(r.json()['least_damped_mode']['damping_ratio'], 6)} "
            f"{round(r.json()['least_damped_mode']['frequency_hz'], 6)}"
        ),
    ),
    Example(
        "Stability against speed (null: stable up to 200 km/h)",
        "POST",
        "/v1/dynamics/stability",
        {"vehicle": "truck-trailer"},
        pipe=" | python -c 'import json,sys; r = json.load(sys.stdin); "
        'print(r["sway_critical_speed_kmh"], r["divergence_speed_kmh"])\'',
        show=lambda r: f"{r.json()['sway_critical_speed_kmh']} {r.json()['divergence_speed_kmh']}",
    ),
    Example(
        "Steady turn: every group's path radius, every unit's articulation and roll",
        "POST",
        "/v1/dynamics/steady-turn",
        {"vehicle": "btrain-table16", "radius_m": 200, "speed_kmh": 60},
        pipe=" | python -c 'import json,sys; r = json.load(sys.stdin); "
        '[print(a["unit"], a["group"], round(a["path_radius_m"], 3)) for a in r["axles"]]; '
        '[print(u["unit"], u["articulation_deg"] and round(u["articulation_deg"], 6), round(u["roll_angle_deg"], 3)) '
        'for u in r["units"]]\'',
        show=lambda r: "\n".join(
            [
                *(f"{a['unit']} {a['group']} {round(a['path_radius_m'], 3)}" for a in r.json()["axles"]),
                *(
                    f"{u['unit']} {u['articulation_deg'] and round(u['articulation_deg'], 6)} "
                    f"{round(u['roll_angle_deg'], 3)}"
                    for u in r.json()["units"]
                ),
            ]
        ),
    ),
    Example(
        "Low-speed 90 degree turn (12.5 m at the outer steer tyre): swept path, tail swing, frontal swing",
        "POST",
        "/v1/dynamics/low-speed-turn",
        {"vehicle": "adouble"},
        pipe=" | python -c 'import json,sys; r = json.load(sys.stdin); "
        'print(r["swept_path_width_m"], r["tail_swing_m"], r["frontal_swing_m"], len(r["paths"]))\'',
        show=lambda r: (
            f"{r.json()['swept_path_width_m']} {r.json()['tail_swing_m']} {r.json()['frontal_swing_m']} "
            f"{len(r.json()['paths'])}"
        ),
    ),
    Example(
        "PBS screening of the A-double: value, limits by level (null: not read in the rules), level from verified "
        "limits only, the manoeuvre defaults unverified",
        "POST",
        "/v1/pbs",
        {"vehicle": "adouble"},
        pipe=" | python -c 'import json,sys; r = json.load(sys.stdin); "
        '[print(s["id"], round(s["value"], 3), s["unit"], [lim["limit"] for lim in s["limits"]], s["level"]) '
        'for s in r["standards"]]; print(r["standards"][0]["limits"][0]["source"]); '
        'c = r["conditions"]; print(c["verified"], c["unverified_defaults_used"]); print(r["note"])\'',
        show=lambda r: "\n".join(
            [
                *(
                    f"{s['id']} {round(s['value'], 3)} {s['unit']} {[lim['limit'] for lim in s['limits']]} {s['level']}"
                    for s in r.json()["standards"]
                ),
                r.json()["standards"][0]["limits"][0]["source"],
                f"{r.json()['conditions']['verified']} {r.json()['conditions']['unverified_defaults_used']}",
                r.json()["note"],
            ]
        ),
    ),
    Example(
        "Plot: lateral acceleration of every unit in the A-double's lane change, saved and checked",
        "POST",
        "/v1/dynamics/plots/lane-change",
        {"vehicle": "adouble"},
        output="lane-change.svg",
        after=svg_series("lane-change.svg"),
    ),
    Example(
        "Plot: rearward amplification against frequency, the worst marked",
        "POST",
        "/v1/dynamics/plots/frequency-response",
        {"vehicle": "adouble"},
        output="ra.svg",
        after=svg_series("ra.svg"),
    ),
    Example(
        "Plot: the low-speed turn's corner paths to scale, with the outer steer tyre's path",
        "POST",
        "/v1/dynamics/plots/low-speed-turn",
        {"vehicle": "tractor-semitrailer-table15"},
        output="swept-path.svg",
        after=svg_series("swept-path.svg"),
    ),
    Example(
        "An error: unknown preset (RFC 9457 problem details)",
        "GET",
        "/v1/vehicles/table99",
        heading="Errors and metrics",
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


def _print_srt_units() -> str:
    """The shell pipe of the README's first example: the governing SRT, each roll-coupled unit, the lift-offs."""
    return (
        ' | python -c \'import json,sys; r = json.load(sys.stdin); print("srt", round(r["srt"], 4), "g"); '
        '[print(u["units"], round(u["srt"], 4), u["limit"]) for u in r["roll_coupled_units"]]; '
        '[print(e["unit"], e["group"], "lifts off at", round(e["ay_g"], 4), "g") '
        'for e in r["lift_sequence"]]; print("LLTf/LLTr", round(r["last_unit_front_llt_ratio"], 3))\''
    )


README_EXAMPLES = [
    Example(
        "A tractor and the Table 15 semitrailer rolling together through the fifth wheel",
        "POST",
        "/v1/srt",
        {"vehicle": "tractor-semitrailer-table15"},
        pipe=_print_srt_units(),
    ),
    Example(
        "The thesis's 3D model of the B-train's rear trailer (Sec. 9.1), SRT and roll angle",
        "POST",
        "/v1/srt",
        {"vehicle": BTRAIN},
        pipe=' | python -c \'import json,sys; r = json.load(sys.stdin); print(r["srt"], r["roll_angle_deg"])\'',
    ),
    Example(
        "The smallest radius at 80 km/h on 6 % superelevation for the combination (Eq. 9.2 against Eq. 9.3)",
        "POST",
        "/v1/min-radius",
        {"vehicle": "tractor-semitrailer-table15", "design_speed_kmh": 80, "superelevation_percent": 6},
        pipe=' | python -c \'import json,sys; r = json.load(sys.stdin); print(round(r["governing_min_radius_m"], 1), '
        'r["governed_by"])\'',
    ),
    Example(
        "Every curve of a road from a spreadsheet's CSV (semicolons, decimal commas: the dialect is detected)",
        "POST",
        "/v1/alignments/assess/csv?vehicle=btrain-table16",
        upload="curves-semicolon.csv",
        form=True,
        pipe=' | python -c \'import json,sys; r = json.load(sys.stdin); print(r["csv_dialect"]); '
        '[print(x["id"], round(x["srt_g"], 3), "g, safe", round(x["safe_speed_kmh"], 1), "km/h, posted", '
        'x["posted_speed_kmh"], "flagged" if x["flagged"] else "ok") for x in r["vehicles"][0]["rows"]]\'',
    ),
    Example(
        "The curves of a GPS track found, fitted and assessed (raw GPX)",
        "POST",
        "/v1/routes/assess/gpx?vehicle=btrain-table16&superelevation_percent=7.5&posted_speed_kmh=60",
        upload="road.gpx",
        headers={"Content-Type": "application/gpx+xml"},
        pipe=" | python -c 'import json,sys; r = json.load(sys.stdin); "
        '[print(c["direction"], "R", round(c["radius_m"], 1), "m, at least", round(c["radius_lower_m"], 1), "m, safe", '
        'round(c["assessment"]["safe_speed_kmh"], 1), "km/h") for c in r["curves"]]\'',
    ),
]


def render(examples: list[Example] | None = None, markers: tuple[str, str] = (START, END)) -> str:
    examples = EXAMPLES if examples is None else examples
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
    out = [markers[0], ""]
    with TestClient(create_app(Settings(cache_backend="memory"))) as client:
        for ex in examples:
            response = ex.send(client)
            if response.status_code >= 500:
                raise SystemExit(f"{ex.title}: {response.status_code} {response.text[:300]}")
            note = [ex.note, ""] if ex.note else []
            heading = [f"### {ex.heading}", ""] if ex.heading else []
            out += [
                *heading,
                f"**{ex.title}**",
                "",
                *note,
                "```console",
                f"$ {ex.curl()}",
                ex.shown(response),
                "```",
                "",
            ]
    out.append(markers[1])
    return "\n".join(out)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--readme", action="store_true", help="print the README's block instead")
    parser.add_argument("--write", action="store_true", help="replace the blocks in docs/examples.md and README.md")
    args = parser.parse_args(argv)
    if not args.write:
        print(render(README_EXAMPLES, (README_START, README_END)) if args.readme else render())
        return 0
    for doc, examples, (start, end) in (
        (EXAMPLES_DOC, EXAMPLES, (START, END)),
        (README, README_EXAMPLES, (README_START, README_END)),
    ):
        try:
            head, _, tail = split_block(doc.read_text(encoding="utf-8"), start, end)
        except ValueError as exc:
            print(f"{doc.name}: {exc}", file=sys.stderr)
            return 1
        doc.write_text(head + render(examples, (start, end)) + tail, encoding="utf-8")
        print(f"{doc.relative_to(ROOT)} examples updated")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
