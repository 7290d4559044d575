"""Uploads as real files come: CSV dialects, multipart/form-data, raw GPX and GeoJSON route bodies, the examples/.

Independent numbers: the sample road of examples/ is laid out exactly (examples/make_examples.py, from
tests/synthetic_routes.py), so its curves are known: K1 right-hand R = 250.5 m from chainage 300 m (arc from
360 m), K2 left-hand R = 180 m from 830 m (arc from 880 m), a +3.5 % grade (examples/README.md). The same curves in
three CSV dialects must give the same rows; a raw or multipart upload must answer what the JSON request answers,
byte for byte.
"""

from __future__ import annotations

import importlib.util
import json

import pytest

from app.alignments.schemas import CSV_UPLOAD_LIMIT

from .conftest import ROOT

EXAMPLES = ROOT / "examples"
BTRAIN = "table16-btrain"
CSV_PATH = "/v1/alignments/assess/csv"
LANDXML_PATH = "/v1/alignments/assess/landxml"

#: the sample curves as examples/README.md states them: id, radius, superelevation, grade, posted speed
KNOWN = [("K1", 250.5, 7.5, 3.5, 70.0), ("K2", 180.0, 8.0, 3.5, 60.0)]
#: each CSV sample and the dialect it is written in
DIALECTS = {
    "curves-comma.csv": {"separator": ",", "decimal": ".", "bom": False, "line_ending": "LF"},
    "curves-semicolon.csv": {"separator": ";", "decimal": ",", "bom": True, "line_ending": "CRLF"},
    "curves-tab.tsv": {"separator": "\t", "decimal": ".", "bom": False, "line_ending": "LF"},
}
ROUTE_QUERY = "vehicle=table16-btrain&superelevation_percent=7.5&posted_speed_kmh=60"
ROUTE_JSON = {"vehicle": BTRAIN, "superelevation_percent": 7.5, "posted_speed_kmh": 60}
ROUTE_FILES = {"gpx": ("road.gpx", "application/gpx+xml"), "geojson": ("road.geojson", "application/geo+json")}


def sample(name: str) -> bytes:
    return (EXAMPLES / name).read_bytes()


def raw(client, path, data: bytes, content_type: str, **headers):
    return client.post(path, content=data, headers={"Content-Type": content_type, **headers})


def multipart(client, path, data: bytes, filename="upload", **headers):
    return client.post(path, files={"file": (filename, data, "application/octet-stream")}, headers=headers or None)


def ok(r):
    assert r.status_code == 200, r.text
    return r


def problem(r, status=422):
    assert r.status_code == status, r.text
    assert r.headers["content-type"] == "application/problem+json"
    return r.json()


def rows(out):
    return out["vehicles"][0]["rows"]


# ------------------------------------------------------------------------------------------ the samples


def test_the_samples_are_what_make_examples_writes():
    spec = importlib.util.spec_from_file_location("make_examples", EXAMPLES / "make_examples.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    written = module.files()
    assert set(written) == {p.name for p in EXAMPLES.iterdir() if p.suffix not in (".py", ".md")}
    for name, data in written.items():
        assert sample(name) == data, f"examples/{name} is stale: run python examples/make_examples.py"


def test_the_semicolon_sample_is_as_a_spreadsheet_saves_it():
    data = sample("curves-semicolon.csv")
    assert data.startswith(b"\xef\xbb\xbfid;radius_m;") and b"\r\nK1;250,5;7,5;3,5;70\r\n" in data


# ------------------------------------------------------------------------------------------ CSV dialects


@pytest.fixture(scope="module")
def by_dialect(shared_client):
    """Each CSV sample posted raw: its answer."""
    return {name: ok(raw(shared_client, f"{CSV_PATH}?vehicle={BTRAIN}", sample(name), "text/csv")) for name in DIALECTS}


@pytest.mark.parametrize("name", sorted(DIALECTS))
def test_each_dialect_is_detected_and_named(by_dialect, name):
    out = by_dialect[name].json()
    assert out["csv_dialect"] == DIALECTS[name]
    got = [
        (r["id"], r["radius_m"], r["superelevation_percent"], r["grade_percent"], r["posted_speed_kmh"])
        for r in rows(out)
    ]
    assert got == KNOWN


def test_the_dialects_give_the_same_rows(by_dialect):
    answers = [by_dialect[name].json() for name in sorted(DIALECTS)]
    first = answers[0]
    for other in answers[1:]:
        assert {**other, "csv_dialect": None} == {**first, "csv_dialect": None}


@pytest.mark.parametrize("name", sorted(DIALECTS))
def test_multipart_and_json_forms_answer_what_the_raw_body_does(shared_client, by_dialect, name):
    path = f"{CSV_PATH}?vehicle={BTRAIN}"
    form = ok(multipart(shared_client, path, sample(name), filename=name))
    assert form.content == by_dialect[name].content and form.headers["etag"] == by_dialect[name].headers["etag"]
    as_json = ok(shared_client.post("/v1/alignments/assess", json={"vehicle": BTRAIN, "csv": sample(name).decode()}))
    assert as_json.content == by_dialect[name].content


def test_a_portuguese_locale_file_is_read_with_its_decimal_commas(shared_client):
    # the file of issue 23 item 4: once refused "missing column(s) id, radius_m"
    text = "id;radius_m;superelevation_percent\nC1;250,5;6\nC2;1200;4,5\n"
    out = ok(raw(shared_client, f"{CSV_PATH}?vehicle={BTRAIN}", text.encode(), "text/csv")).json()
    assert [(r["radius_m"], r["superelevation_percent"]) for r in rows(out)] == [(250.5, 6.0), (1200.0, 4.5)]
    assert out["csv_dialect"] == {"separator": ";", "decimal": ",", "bom": False, "line_ending": "LF"}


@pytest.mark.parametrize(
    ("text", "dialect", "radii"),
    [
        # a tab-separated file with decimal commas (a decimal-comma locale's "Text (tab delimited)")
        ("id\tradius_m\tsuperelevation_percent\r\nC1\t250,5\t6\r\n", ("\t", ",", "CRLF"), [250.5]),
        # old Mac line ends
        ("id;radius_m;superelevation_percent\rC1;99,5;6\rC2;100;6\r", (";", ",", "CR"), [99.5, 100.0]),
        # whole numbers only: either decimal mark reads them the same
        ("id;radius_m;superelevation_percent\nC1;300;6\n", (";", ".", "LF"), [300.0]),
        # a quoted id with the separator in it
        ('id;radius_m;superelevation_percent\n"A;1";120,25;6\n', (";", ",", "LF"), [120.25]),
        # header names in another case
        ("ID,Radius_M,SUPERELEVATION_PERCENT\nC1,410.5,6\n", (",", ".", "LF"), [410.5]),
        # Excel's separator line (it sets the separator; the header is the line after it)
        ("sep=;\r\nid;radius_m;superelevation_percent\r\nC1;250,5;6\r\n", (";", ",", "CRLF"), [250.5]),
        ("\ufeffSEP=\t\nid\tradius_m\tsuperelevation_percent\nC1\t99.5\t6\n", ("\t", ".", "LF"), [99.5]),
        # ... which wins over the header's own counts: a comma-separated file with a sep=, line
        ("sep=,\nid,radius_m,superelevation_percent\nC1,120,6\n", (",", ".", "LF"), [120.0]),
    ],
)
def test_other_dialects(shared_client, text, dialect, radii):
    out = ok(raw(shared_client, f"{CSV_PATH}?vehicle={BTRAIN}", text.encode(), "text/csv")).json()
    d = out["csv_dialect"]
    assert (d["separator"], d["decimal"], d["line_ending"]) == dialect
    assert [r["radius_m"] for r in rows(out)] == radii


@pytest.mark.parametrize(
    ("text", "location", "field", "words"),
    [
        # decimal commas in a comma-separated file: the number splits in two
        ("id,radius_m,superelevation_percent\nC1,250,5,6\n", "row 2", "body", "decimal comma in a comma-separated"),
        # ... or, quoted, is not a number in that dialect
        ('id,radius_m,superelevation_percent\nC1,"250,5",6\n', "row 2", "body.radius_m", "decimal comma"),
        # a decimal point in a decimal-comma file (or a thousands separator): never read as something else
        ("id;radius_m;superelevation_percent\nC1;250,5;6\nC2;300.5;6\n", "row 3", "body.radius_m", "row 2, radius_m"),
        ("id;radius_m;superelevation_percent\nC1;250,5;6\nC2;1.250,5;6\n", "row 3", "body.radius_m", "thousands"),
        ("id;radius_m;superelevation_percent\nC1;250.5;6\nC2;300,5;6\n", "row 3", "body.radius_m", "with a point"),
        # the column as the user typed it
        ("id;Radius_M;superelevation_percent\nC1;2,5;6\n", "row 2", "body.Radius_M", "Radius_M = 2.5"),
        ("id;radius_m;Grade\nC1;250,5;6\n", "row 1 (header)", "body.Grade", "unknown column(s) Grade"),
        ("Id;Radius_M;Id\nC1;250,5;6\n", "row 1 (header)", "body.Id", "duplicate column(s) Id"),
        # a header with none of the separators
        ("id|radius_m\nC1|250\n", "row 1 (header)", "body.id", "separated by ',', ';' or tabs"),
        # a separator line naming another separator
        ("sep=|\nid|radius_m\nC1|250\n", "the sep= line", "body", "names the separator '|'"),
        # the rows are counted from the header, as the spreadsheet shows them (the sep= line hidden)
        ("sep=;\nid;radius_m;superelevation_percent\nC1;250,5;6\nC2;300.5;6\n", "row 3", "body.radius_m", "row 2"),
    ],
)  # fmt: skip
def test_a_number_in_another_dialect_is_refused_with_its_row_and_column(shared_client, text, location, field, words):
    p = problem(raw(shared_client, f"{CSV_PATH}?vehicle={BTRAIN}", text.encode(), "text/csv"))
    assert p["type"] == "urn:rollover:problem:invalid-alignment"
    (error,) = p["errors"]
    assert (error["location"], error["field"]) == (location, field)
    assert words in error["message"], error["message"]


def test_the_json_csv_field_is_read_in_its_dialect_too(shared_client):
    p = problem(shared_client.post("/v1/alignments/assess", json={"vehicle": BTRAIN, "csv": "id;radius_m\nC1;2,5\n"}))
    assert p["errors"][0]["field"] == "csv.radius_m" and p["errors"][0]["location"] == "row 2"


@pytest.mark.parametrize(
    ("data", "words"),
    [
        ("id;radius_m\nC1;250,5\n".encode("utf-16"), "UTF-16"),
        ("id;radius_m;superelevation_percent\nCurva São João;250,5;6\n".encode("cp1252"), "not UTF-8"),
    ],
)
def test_text_that_is_not_utf8_is_refused_saying_how_to_save_it(shared_client, data, words):
    for r in (
        raw(shared_client, f"{CSV_PATH}?vehicle={BTRAIN}", data, "text/csv"),
        multipart(shared_client, f"{CSV_PATH}?vehicle={BTRAIN}", data),
    ):
        assert words in problem(r)["detail"] and "CSV UTF-8" in problem(r)["detail"]


def test_a_job_reads_the_csv_in_its_dialect(client):
    import time

    text = sample("curves-semicolon.csv").decode()
    r = client.post("/v1/jobs", json={"operation": "alignments.assess", "request": {"vehicle": BTRAIN, "csv": text}})
    assert r.status_code == 202, r.text
    location = r.headers["location"]
    deadline = time.monotonic() + 60
    while client.get(location).json()["status"] not in ("done", "failed", "cancelled"):
        assert time.monotonic() < deadline
        time.sleep(0.05)
    out = ok(client.get(f"{location}/result")).json()
    assert out["csv_dialect"] == DIALECTS["curves-semicolon.csv"]
    assert [(r["id"], r["radius_m"], r["superelevation_percent"]) for r in rows(out)] == [k[:3] for k in KNOWN]


# ------------------------------------------------------------------------------------------ LandXML


def test_the_landxml_sample_has_the_csv_curves(shared_client, by_dialect):
    q = f"{LANDXML_PATH}?vehicle={BTRAIN}&superelevation_percent=7.5&grade_percent=3.5"
    out = ok(raw(shared_client, q, sample("alignment.xml"), "application/xml")).json()
    assert [(r["id"], r["radius_m"], r["station_m"]) for r in rows(out)] == [("K1", 250.5, 360.0), ("K2", 180.0, 880.0)]
    assert out["csv_dialect"] is None
    # K1 as the CSV gives it (7.5 %, +3.5 %, no posted speed there): the same SRT and speeds
    csv_k1 = rows(by_dialect["curves-comma.csv"].json())[0]
    keep = ("radius_m", "superelevation_percent", "grade_percent", "srt_g", "rollover_speed_kmh", "safe_speed_kmh")
    assert {k: rows(out)[0][k] for k in keep} == {k: csv_k1[k] for k in keep}
    form = ok(multipart(shared_client, q, sample("alignment.xml"), filename="alignment.xml"))
    assert form.content == raw(shared_client, q, sample("alignment.xml"), "application/xml").content


def test_the_landxml_sample_in_feet_is_the_same_road(shared_client, by_dialect):
    """alignment-feet.xml: the road in feet, its grade a profile and its superelevation Superelevation elements; the
    rows are the CSV's curves (examples/README.md), read from the file alone (no superelevation or grade asked)."""
    q = f"{LANDXML_PATH}?vehicle={BTRAIN}"
    out = ok(raw(shared_client, q, sample("alignment-feet.xml"), "application/xml")).json()
    got = rows(out)
    for row, (cid, r, e, grade, _), arc_start, spiral in zip(got, KNOWN, (360.0, 880.0), (60.0, 50.0), strict=True):
        assert row["id"] == cid and row["radius_m"] == pytest.approx(r, rel=1e-12)
        assert row["station_m"] == pytest.approx(arc_start, rel=1e-12)
        assert (row["spiral_in_m"], row["spiral_out_m"]) == (pytest.approx(spiral), pytest.approx(spiral))
        assert (row["superelevation_percent"], row["superelevation_source"]) == (e, "file")
        assert (row["grade_percent"], row["grade_source"]) == (pytest.approx(grade, rel=1e-9), "profile")
    assert [r["direction"] for r in got] == ["right", "left"]
    assert out["reading"]["linear_unit"] == "foot" and out["reading"]["superelevation_from"] == "file"
    csv_k1 = rows(by_dialect["curves-comma.csv"].json())[0]
    for k in ("srt_g", "rollover_speed_kmh", "safe_speed_kmh"):
        assert got[0][k] == pytest.approx(csv_k1[k], rel=1e-9)


# ------------------------------------------------------------------------------------------ multipart


@pytest.mark.parametrize(
    ("files", "data", "field", "words"),
    [
        ({"upload": ("c.csv", b"id,radius_m\n")}, None, "upload", "unexpected form part"),
        ({"file": ("c.csv", b"id,radius_m,superelevation_percent\nC1,100,6\n")}, {"vehicle": BTRAIN}, "vehicle",
         "query parameters"),
        ([("file", ("a.csv", b"id,radius_m\n")), ("file", ("b.csv", b"id,radius_m\n"))], None, "file",
         "one file per request"),
    ],
)  # fmt: skip
def test_a_multipart_body_without_exactly_one_file_part_is_refused_naming_the_part(
    shared_client, files, data, field, words
):
    r = shared_client.post(f"{CSV_PATH}?vehicle={BTRAIN}", files=files, data=data)
    p = problem(r)
    assert p["errors"][0]["field"] == field and words in p["errors"][0]["message"]


def test_a_multipart_body_with_no_part_at_all_is_refused(shared_client):
    boundary = "xyz"
    body = f"--{boundary}--\r\n".encode()
    r = shared_client.post(
        f"{CSV_PATH}?vehicle={BTRAIN}",
        content=body,
        headers={"Content-Type": f"multipart/form-data; boundary={boundary}"},
    )
    assert problem(r)["errors"][0]["field"] == "file"


def form_body(*parts: tuple[str, str | None, bytes], boundary: str = "b0undary") -> tuple[bytes, dict[str, str]]:
    """A multipart/form-data body of (name, filename or None, content) parts, as curl -F writes it."""
    out = b""
    for name, filename, content in parts:
        disposition = f'form-data; name="{name}"' + (f'; filename="{filename}"' if filename else "")
        out += f"--{boundary}\r\nContent-Disposition: {disposition}\r\n\r\n".encode() + content + b"\r\n"
    return out + f"--{boundary}--\r\n".encode(), {"Content-Type": f"multipart/form-data; boundary={boundary}"}


def test_a_file_field_without_a_filename_is_the_file(shared_client, by_dialect):
    # curl -F 'file=<curves.csv' sends the content as a plain field
    body, headers = form_body(("file", None, sample("curves-comma.csv")))
    r = ok(shared_client.post(f"{CSV_PATH}?vehicle={BTRAIN}", content=body, headers=headers))
    assert r.content == by_dialect["curves-comma.csv"].content


def test_an_option_as_a_form_field_is_refused_saying_where_it_goes(shared_client):
    body, headers = form_body(("file", "c.csv", sample("curves-comma.csv")), ("rear_llt_limit", None, b"0.6"))
    p = problem(shared_client.post(f"{CSV_PATH}?vehicle={BTRAIN}", content=body, headers=headers))
    assert p["errors"][0]["field"] == "rear_llt_limit" and "query parameters" in p["errors"][0]["message"]


def test_errors_in_a_multipart_file_name_the_part(shared_client):
    p = problem(
        multipart(shared_client, f"{CSV_PATH}?vehicle={BTRAIN}", b"id;radius_m;superelevation_percent\nC1;250,5;x\n")
    )
    (error,) = p["errors"]
    assert (error["field"], error["loc"], error["location"]) == (
        "file.superelevation_percent",
        ["body", "file"],
        "row 2",
    )
    assert problem(multipart(shared_client, f"{CSV_PATH}?vehicle={BTRAIN}", b""))["errors"][0]["field"] == "file"


@pytest.mark.parametrize("path", [CSV_PATH, LANDXML_PATH, "/v1/routes/assess/gpx", "/v1/routes/assess/geojson"])
def test_the_body_limit_applies_to_a_multipart_upload(shared_client, path):
    from app.http.bodylimit import spec_limits

    limit = spec_limits(shared_client.get("/openapi.json").json())[path]
    if path == CSV_PATH:
        assert limit == CSV_UPLOAD_LIMIT
    r = multipart(shared_client, f"{path}?vehicle={BTRAIN}", b"x" * (limit + 1))
    assert problem(r, 413)["type"] == "urn:rollover:problem:body-too-large"


# ------------------------------------------------------------------------------------------ routes


@pytest.fixture(scope="module")
def route_answers(shared_client):
    """kind -> (raw answer, JSON-wrapped answer) for the GPX and GeoJSON samples."""
    out = {}
    for kind, (name, media) in ROUTE_FILES.items():
        data = sample(name)
        document = data.decode() if kind == "gpx" else json.loads(data)
        wrapped = ok(shared_client.post("/v1/routes/assess", json={**ROUTE_JSON, kind: document}))
        out[kind] = (ok(raw(shared_client, f"/v1/routes/assess/{kind}?{ROUTE_QUERY}", data, media)), wrapped)
    return out


@pytest.mark.parametrize("kind", sorted(ROUTE_FILES))
def test_a_raw_route_body_answers_what_the_json_request_does(route_answers, kind):
    by_raw, wrapped = route_answers[kind]
    assert by_raw.content == wrapped.content
    assert by_raw.headers["etag"] == wrapped.headers["etag"] and by_raw.headers["x-cache"] == "hit"


@pytest.mark.parametrize("kind", sorted(ROUTE_FILES))
@pytest.mark.parametrize("accept", ["application/geo+json", "text/csv"])
def test_raw_and_multipart_route_uploads_negotiate_like_the_json_request(shared_client, kind, accept):
    name, media = ROUTE_FILES[kind]
    data = sample(name)
    document = data.decode() if kind == "gpx" else json.loads(data)
    path = f"/v1/routes/assess/{kind}?{ROUTE_QUERY}"
    wrapped = ok(
        shared_client.post("/v1/routes/assess", json={**ROUTE_JSON, kind: document}, headers={"Accept": accept})
    )
    for r in (
        raw(shared_client, path, data, media, Accept=accept),
        multipart(shared_client, path, data, name, Accept=accept),
    ):
        assert ok(r).content == wrapped.content and r.headers["content-type"] == wrapped.headers["content-type"]
        assert r.headers["vary"] == "Accept"


def test_the_route_samples_have_the_known_curves(route_answers, by_dialect):
    found = {kind: route_answers[kind][0].json()["curves"] for kind in ROUTE_FILES}
    gpx, geojson = found["gpx"], found["geojson"]
    # the same vertices in both files: the same curves
    assert [c["radius_m"] for c in gpx] == pytest.approx([c["radius_m"] for c in geojson], rel=1e-12)
    # the layout's curves: direction, radius (a noise-free centreline: the fit within 0.5 %), where they start
    # (within a vertex spacing, 10 m) and the +3.5 % grade
    assert [c["direction"] for c in gpx] == ["right", "left"]
    assert [c["radius_m"] for c in gpx] == pytest.approx([250.5, 180.0], rel=5e-3)
    assert [c["start_m"] for c in gpx] == pytest.approx([300.0, 830.0], abs=10.0)
    assert [c["grade_percent"] for c in gpx] == pytest.approx([3.5, 3.5], abs=0.05)
    # and the CSV samples list the same radii
    csv_radii = [r["radius_m"] for r in rows(by_dialect["curves-comma.csv"].json())]
    assert [c["radius_m"] for c in gpx] == pytest.approx(csv_radii, rel=5e-3)


@pytest.mark.parametrize("kind", sorted(ROUTE_FILES))
def test_a_multipart_route_upload_is_the_raw_one(shared_client, route_answers, kind):
    name, _ = ROUTE_FILES[kind]
    r = ok(multipart(shared_client, f"/v1/routes/assess/{kind}?{ROUTE_QUERY}", sample(name), name))
    assert r.content == route_answers[kind][0].content


@pytest.mark.parametrize(
    ("kind", "data", "multi", "field", "location"),
    [
        ("geojson", b'{"type": "FeatureCollection", "features": [', False, "body", None),
        ("geojson", b"[1, 2]", False, "body", None),
        ("geojson", b"", False, "body", None),
        ("gpx", b"<gpx><trk>", False, "body", "GPX line 1"),
        ("gpx", b"", True, "file", None),
        ("gpx", sample("road.gpx").replace(b'lat="-25.4300000"', b'lat="S25.43"', 1), True, "file.lat",
         "trk[1] 'Example road (synthetic): two curves' trkseg[1] trkpt[1]"),
        ("geojson", sample("road.geojson").replace(b"[-49.0200000, -25.4300000", b"[-49.0200000, -95.4300000", 1),
         False, "body.latitude", "features[0].geometry.coordinates[0]"),
    ],
)  # fmt: skip
def test_route_upload_errors_name_the_part_and_vertex(shared_client, kind, data, multi, field, location):
    name, media = ROUTE_FILES[kind]
    path = f"/v1/routes/assess/{kind}?{ROUTE_QUERY}"
    r = multipart(shared_client, path, data, name) if multi else raw(shared_client, path, data, media)
    p = problem(r)
    assert p["type"] == "urn:rollover:problem:invalid-route"
    (error,) = p["errors"]
    assert error["field"] == field
    assert (error["location"] or "").startswith(location or "") and (location is not None) == (
        error["location"] is not None
    )


@pytest.mark.parametrize(
    ("query", "field"),
    [
        ("superelevation_percent=7.5", "vehicle"),
        ("vehicle=table16-btrain&superelevation_percent=70", "superelevation_percent"),
        ("vehicle=table16-btrain&superelevation_percent=7.5&noise_m=-1", "noise_m"),
        ("vehicle=table16-btrain&superelevation_percent=7.5&geojson=x", "geojson"),
    ],
)
def test_route_upload_query_errors_name_the_parameter(shared_client, query, field):
    p = problem(raw(shared_client, f"/v1/routes/assess/gpx?{query}", sample("road.gpx"), "application/gpx+xml"))
    assert field in {e["field"] for e in p["errors"]}
    assert all(e["loc"][0] == "query" for e in p["errors"])


def test_the_detection_options_are_query_parameters(shared_client):
    # a 300 m max radius leaves only K2 (180 m) as a curve
    q = f"{ROUTE_QUERY}&max_radius_m=200"
    by_raw = ok(raw(shared_client, f"/v1/routes/assess/gpx?{q}", sample("road.gpx"), "application/gpx+xml"))
    body = {**ROUTE_JSON, "gpx": sample("road.gpx").decode(), "detection": {"max_radius_m": 200}}
    assert by_raw.content == ok(shared_client.post("/v1/routes/assess", json=body)).content
    assert [c["direction"] for c in by_raw.json()["curves"]] == ["left"]


GARBAGE = [
    b"\x00\xff\xfe garbage",
    b"{}",
    b"<gpx/>",
    b"<LandXML/>",
    b"id\n",
    "é".encode("latin-1") * 10,
    b"\xef\xbb\xbf",
]


@pytest.mark.parametrize(
    "path", [CSV_PATH, LANDXML_PATH + "?superelevation_percent=6", "/v1/routes/assess/gpx", "/v1/routes/assess/geojson"]
)
@pytest.mark.parametrize("data", GARBAGE)
@pytest.mark.parametrize("multi", [False, True])
def test_garbage_is_a_problem_never_a_500(shared_client, path, data, multi):
    url = f"{path}{'&' if '?' in path else '?'}vehicle={BTRAIN}"
    r = multipart(shared_client, url, data) if multi else raw(shared_client, url, data, "application/octet-stream")
    assert 400 <= r.status_code < 500 and r.headers["content-type"] == "application/problem+json", r.text


# ------------------------------------------------------------------------------------------ the spec


@pytest.mark.parametrize(
    ("path", "media"),
    [
        (CSV_PATH, "text/csv"),
        (LANDXML_PATH, "application/xml"),
        ("/v1/routes/assess/gpx", "application/gpx+xml"),
        ("/v1/routes/assess/geojson", "application/geo+json"),
    ],
)
def test_the_spec_declares_the_raw_and_multipart_bodies(shared_client, path, media):
    spec = shared_client.get("/openapi.json").json()
    content = spec["paths"][path]["post"]["requestBody"]["content"]
    assert set(content) == {media, "multipart/form-data"}
    form = content["multipart/form-data"]["schema"]
    assert form["required"] == ["file"] and set(form["properties"]) == {"file"}
    assert "-F file=@" in spec["paths"][path]["post"]["description"]


def test_the_spec_names_the_csv_dialect_in_the_answer(shared_client):
    schemas = shared_client.get("/openapi.json").json()["components"]["schemas"]
    assert "csv_dialect" in schemas["AlignmentResult"]["required"]
    assert set(schemas["CsvDialectOut"]["properties"]) == {"separator", "decimal", "bom", "line_ending"}
