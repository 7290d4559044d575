"""The design cross sections read without a tree (app/formats/landxml.py, ``_cross_section_scan``) give what the
tree's reading gives, document by document: the same slopes and the same reading summary, or the same refusal word
for word. The second formulation is the tree's reading itself (the scan switched off), the one every other LandXML
test checks against the files' own numbers; the scan must be taken where it applies (else these tests compare the
tree with itself) and left where it does not recognise a section's shape.

Every test runs twice: with the compiled scan (app.formats._xsectscan, app/formats/csrc/xsectscan.c) taking the
sections it takes, and with the Python scan alone (what runs where the module was not built). The compiled scan is
also compared with the Python scan region by region, and its numbers with Python's ``float``, on valid, random,
truncated and adversarial contents. Where the module was not built these compiled runs skip; under CI=true they
fail (setup.py builds it where a C compiler is found: the deployment image and CI have one).
"""

from __future__ import annotations

import contextlib
import math
import os
import random
import struct

import numpy as np
import pytest

from app.formats import landxml, xmlsafe
from app.formats.alignment_io import AlignmentFormatError
from tests.landxml_writer import Design, Element
from tests.landxml_writer import landxml as write_landxml

SCAN = landxml._cross_section_scan
COMPILED = landxml._xsectscan


def _compiled_module():
    if COMPILED is None:
        if os.environ.get("CI") == "true":
            pytest.fail("app.formats._xsectscan was not built: setup.py needs a C compiler and Python's headers")
        pytest.skip("app.formats._xsectscan was not built here (no C compiler): the Python scan runs")
    return COMPILED


def pytest_generate_tests(metafunc):
    """Each test of the reading twice (the tests of the compiled scan itself, which take ``compiled``, once)."""
    if "compiled" not in metafunc.fixturenames:
        metafunc.parametrize("scanner", ["compiled scan", "python scan"], indirect=True)


@pytest.fixture(autouse=True)
def scanner(request, monkeypatch):
    """The compiled scan where it takes the sections, or the Python scan alone."""
    which = getattr(request, "param", "compiled scan")
    monkeypatch.setattr(landxml, "_xsectscan", _compiled_module() if which == "compiled scan" else None)
    return which


@pytest.fixture
def compiled():
    return _compiled_module()


SECTION = (
    '<CrossSect sta="{sta}"><DesignCrossSectSurf name="Top">'
    "<CrossSectPnt>-3.5 {zl}</CrossSectPnt><CrossSectPnt>0 100</CrossSectPnt><CrossSectPnt>3.5 {zr}</CrossSectPnt>"
    "</DesignCrossSectSurf></CrossSect>"
)


def _doc(sections: str, *, before: str = "", unit: str = "meter") -> str:
    return (
        '<?xml version="1.0"?>\n<LandXML xmlns="http://www.landxml.org/schema/LandXML-1.2" version="1.2">'
        f'<Units><Metric linearUnit="{unit}"/></Units>{before}<Alignments><Alignment name="A" staStart="0">'
        '<CoordGeom><Line length="100"/><Curve rot="cw" radius="300" length="100" name="K"/><Line length="100"/>'
        f"</CoordGeom>{sections}</Alignment></Alignments></LandXML>"
    )


def _outcome(doc: str | bytes, *, scan: bool, monkeypatch) -> tuple:
    """The reading of ``doc`` as data (the alignments' cross slopes, skipped notes and element counts), or the
    refusal's text; and whether the scan read its sections."""
    used = []

    def spy(text):
        got = SCAN(text) if scan else None
        used.append(got is not None)
        return got

    monkeypatch.setattr(landxml, "_cross_section_scan", spy)
    try:
        rf = landxml.read_road_file(doc)
        out = ("read", [a.cross_slopes for a in rf.alignments], rf.skipped, rf.elements)
    except AlignmentFormatError as exc:
        out = ("refused", str(exc), exc.location, exc.field)
    return out, any(used)


def _same(doc: str | bytes, monkeypatch, *, scanned: bool) -> tuple:
    ours, used = _outcome(doc, scan=True, monkeypatch=monkeypatch)
    tree, _ = _outcome(doc, scan=False, monkeypatch=monkeypatch)
    assert used is scanned, "the scan was (not) taken"
    assert ours == tree
    return ours


def _random_sections(rng: random.Random, n: int) -> str:
    parts = []
    for k in range(n):
        zl, zr = 100 - rng.uniform(-0.2, 0.2), 100 + rng.uniform(-0.2, 0.2)
        parts.append(SECTION.format(sta=f"{25 + 50 * k:g}", zl=f"{zl:.4f}", zr=f"{zr:.4f}"))
    return "".join(parts)


@pytest.mark.parametrize("as_bytes", [False, True])
def test_sections_of_the_usual_shape_are_scanned_and_read_as_the_tree_reads_them(monkeypatch, as_bytes):
    rng = random.Random(5)
    doc = _doc(f"<CrossSects>{_random_sections(rng, 6)}</CrossSects>")
    out = _same(doc.encode() if as_bytes else doc, monkeypatch, scanned=True)
    assert out[0] == "read" and len(out[1][0]) == 6


def test_the_writers_documents_in_every_unit_are_scanned_alike(monkeypatch):
    rng = random.Random(11)
    for unit in ("meter", "foot", "USSurveyFoot", "millimeter"):
        sections = [(rng.uniform(0, 300), rng.uniform(-4, 4), rng.uniform(-4, 4), 3.5) for _ in range(5)]
        sections.sort()
        design = Design(
            "X", 0.0, [Element("Line", 100.0), Element("Curve", 100.0, 300.0, 300.0, "ccw", "K")],
            cross_sections=sections,
        )  # fmt: skip
        doc = write_landxml(design, unit) if unit != "meter" else write_landxml(design)
        _same(doc, monkeypatch, scanned=True)


def test_a_section_spread_over_lines_with_attributes_and_text_between_is_scanned(monkeypatch):
    sections = (
        "<CrossSects>\r\n  stray text\n"
        '  <CrossSect name="0+25" sta=\'25\'>\n    <DesignCrossSectSurf name="Top" side="both">\n'
        '      <CrossSectPnt code="EP">\t-3.5   99.9 </CrossSectPnt>\n      <CrossSectPnt>0 100</CrossSectPnt>\n'
        "      <CrossSectPnt>3.5\n100.1</CrossSectPnt>\n    </DesignCrossSectSurf>\n  </CrossSect>\n"
        "  <CrossSect sta=' 75 '><DesignCrossSectSurf><CrossSectPnt>-3 99.9</CrossSectPnt>"
        "<CrossSectPnt>3 99.9</CrossSectPnt></DesignCrossSectSurf></CrossSect>"
        # one side only: skipped, and said so
        '  <CrossSect sta="125"><DesignCrossSectSurf><CrossSectPnt>0 100</CrossSectPnt>'
        "<CrossSectPnt>3 99.9</CrossSectPnt></DesignCrossSectSurf></CrossSect>"
        "</CrossSects>"
    )
    out = _same(_doc(sections), monkeypatch, scanned=True)
    assert len(out[1][0]) == 2 and any("one side" in why for _, why in out[2])


@pytest.mark.parametrize(
    ("sta", "point"),
    [
        ("abc", "1 2"),  # a station not a number
        ("1\n2", "1 2"),  # the tree's value has a space where the text has a line feed
        ("inf", "1 2"),  # not finite
        ("10", "1 x"),  # a point's number
        ("10", "1 nan"),
    ],
)
def test_the_refusals_are_the_trees_word_for_word(monkeypatch, sta, point):
    sections = (
        f'<CrossSects>{SECTION.format(sta=5, zl=99.9, zr=99.9)}<CrossSect sta="{sta}"><DesignCrossSectSurf>'
        f"<CrossSectPnt>-3 99</CrossSectPnt><CrossSectPnt>{point}</CrossSectPnt></DesignCrossSectSurf></CrossSect>"
        "</CrossSects>"
    )
    out = _same(_doc(sections), monkeypatch, scanned=True)
    assert out[0] == "refused" and "CrossSect 2" in out[2]


def test_a_section_without_sta_is_refused_as_the_tree_refuses_it(monkeypatch):
    sections = '<CrossSects><CrossSect name="x"><DesignCrossSectSurf><CrossSectPnt>-3 99</CrossSectPnt>'
    sections += "<CrossSectPnt>3 99</CrossSectPnt></DesignCrossSectSurf></CrossSect></CrossSects>"
    out = _same(_doc(sections), monkeypatch, scanned=True)
    assert out[0] == "refused" and out[3] == "sta"


@pytest.mark.parametrize(
    "sections",
    [
        # a point of three words (the tree takes the first two)
        '<CrossSects><CrossSect sta="1"><DesignCrossSectSurf><CrossSectPnt>-3 99 EP</CrossSectPnt>'
        "<CrossSectPnt>3 99</CrossSectPnt></DesignCrossSectSurf></CrossSect></CrossSects>",
        # a character reference
        '<CrossSects><CrossSect sta="1"><DesignCrossSectSurf><CrossSectPnt>&#45;3 99</CrossSectPnt>'
        "<CrossSectPnt>3 99</CrossSectPnt></DesignCrossSectSurf></CrossSect></CrossSects>",
        # a comment inside
        '<CrossSects><!-- x --><CrossSect sta="1"><DesignCrossSectSurf><CrossSectPnt>-3 99</CrossSectPnt>'
        "<CrossSectPnt>3 99</CrossSectPnt></DesignCrossSectSurf></CrossSect></CrossSects>",
        # two surfaces (the tree takes the first)
        '<CrossSects><CrossSect sta="1"><DesignCrossSectSurf><CrossSectPnt>-3 99</CrossSectPnt>'
        "<CrossSectPnt>3 99</CrossSectPnt></DesignCrossSectSurf><DesignCrossSectSurf><CrossSectPnt>-3 98"
        "</CrossSectPnt><CrossSectPnt>3 98</CrossSectPnt></DesignCrossSectSurf></CrossSect></CrossSects>",
        # another surface element (as Aplitop writes it)
        '<CrossSects><CrossSect sta="1"><CrossSectSurf><PntList2D>-3 99 0 100 3 99</PntList2D></CrossSectSurf>'
        "</CrossSect></CrossSects>",
        # a prefixed section inside
        '<CrossSects xmlns:l="urn:x"><l:CrossSect sta="1"><l:DesignCrossSectSurf><l:CrossSectPnt>-3 99'
        "</l:CrossSectPnt><l:CrossSectPnt>3 99</l:CrossSectPnt></l:DesignCrossSectSurf></l:CrossSect></CrossSects>",
        # a point's text not ASCII (a no-break space splits the words in the tree)
        '<CrossSects><CrossSect sta="1"><DesignCrossSectSurf><CrossSectPnt>-3\u00a099</CrossSectPnt>'
        "<CrossSectPnt>3 99</CrossSectPnt></DesignCrossSectSurf></CrossSect></CrossSects>",
    ],
)
def test_sections_the_scan_does_not_recognise_are_read_by_the_tree(monkeypatch, sections):
    _same(_doc(sections), monkeypatch, scanned=False)


def test_cross_sections_written_inside_a_comment_are_not_read(monkeypatch):
    hidden = f"<!-- <CrossSects>{SECTION.format(sta=5, zl=99, zr=99)}</CrossSects> -->"
    out = _same(_doc(hidden), monkeypatch, scanned=False)
    assert out[1] == [()]
    # before the root too, and a processing instruction likewise
    out = _same(_doc("", before=f"<?pi <CrossSects>{SECTION.format(sta=5, zl=99, zr=99)}</CrossSects>?>"),
                monkeypatch, scanned=False)  # fmt: skip
    assert out[1] == [()]


def test_a_document_naming_the_marker_itself_is_read_by_the_tree(monkeypatch):
    # the marker element stands for scanned content; a file that writes it must not point the reader at a scan
    real = f"<CrossSects>{SECTION.format(sta=5, zl=99, zr=99)}</CrossSects>"
    for forged, scanned in (
        (f'<CrossSects><{landxml._SCANNED} key="0"/></CrossSects>', False),  # not a section: not scanned
        (f'<l:CrossSects xmlns:l="urn:x"><l:{landxml._SCANNED} key="0-0"/></l:CrossSects>', True),
    ):
        out = _same(_doc(forged + real), monkeypatch, scanned=scanned)
        assert out[0] == "read" and len(out[1][0]) == 1


def _random_section(rng: random.Random, k: int) -> str:
    """A section in one of the shapes writers use, now and then with something the scan must refuse or the tree
    refuses (numbers, attributes, white space, a third word, an empty element, a character reference)."""
    ws = lambda: rng.choice(["", " ", "\n  ", "\r\n\t"])  # noqa: E731
    sta = rng.choice(
        [f"{10 * k}", f" {10 * k}.0 ", f"{10 * k}e0", "x", "", "inf"] if rng.random() < 0.1 else [f"{10 * k}"]
    )
    quote = rng.choice(['"', "'"]) if rng.random() < 0.2 else '"'
    attrs = rng.choice(["", ' name="S"', " name='a>b'", ' a="&amp;"', ' b = "x\'>y"']) if rng.random() < 0.2 else ""
    start = f"<CrossSect{attrs} sta={quote}{sta}{quote}{ws()}>" if rng.random() > 0.05 else f"<CrossSect{attrs}>"
    points = []
    for _ in range(rng.choice([0, 1, 2, 3, 3, 3, 5])):
        x = rng.choice([-3.5, -2.0, 0.0, 0.0, 1.5, 3.5])
        z = round(100 + rng.uniform(-0.2, 0.2), 3)
        text = f"{ws()}{x:g}{rng.choice([' ', '  ', chr(9), chr(10)])}{z}{ws()}"
        if rng.random() < 0.03:
            text = rng.choice([f"{x} {z} EP", f"{x}", "a b", "&#45;1 2", f"{x} nan"])
        tags = ["<CrossSectPnt>", '<CrossSectPnt code="EP">', "<CrossSectPnt code='a>b'>", "<CrossSectPnt c='&amp;'>"]
        tag = rng.choice(tags) if rng.random() < 0.2 else "<CrossSectPnt>"
        points.append(f"{ws()}{tag}{text}</CrossSectPnt>" if rng.random() > 0.01 else "<CrossSectPnt/>")
    surf = rng.choice(["<DesignCrossSectSurf>", '<DesignCrossSectSurf name="Top">', "<DesignCrossSectSurf n='>'>"])
    body = f"{surf}{''.join(points)}{ws()}</DesignCrossSectSurf>"
    if rng.random() < 0.02:
        body = "<CrossSectSurf><PntList2D>-3 99 0 100 3 99</PntList2D></CrossSectSurf>"
    return f"{ws()}{start}{ws()}{body}{ws()}</CrossSect>"


@pytest.mark.parametrize("seed", range(300))
def test_random_documents_read_alike_with_and_without_the_scan(monkeypatch, seed):
    rng = random.Random(seed)
    parts = [_random_section(rng, k) for k in range(rng.randint(0, 12))]
    if rng.random() < 0.2:  # now and then something not well-formed (or not proved so) among them, or after them
        odd = rng.choice(["\x02", "]]>", "&x;", "&amp;", "<a b='1' b='2'/>", "<p:a/>", "</CrossSect>", "<!-- -->"])
        parts.insert(rng.randint(0, len(parts)), f"\n{odd}" if rng.random() < 0.5 else odd)
    sections = "".join(parts)
    doc = _doc(f"<CrossSects>{sections}</CrossSects>" + rng.choice(["", "", "\n<Oops/ >", "<a>"]))
    ours, _ = _outcome(doc.encode() if seed % 2 else doc, scan=True, monkeypatch=monkeypatch)
    tree, _ = _outcome(doc.encode() if seed % 2 else doc, scan=False, monkeypatch=monkeypatch)
    assert ours == tree, doc


# ---------------------------------------------------------------------------------------------- the guard's share
# A content the scan proves well-formed by itself is left out of the guard's pass (xmlsafe.fromstring); what the
# guard then refuses, and where, must be what it refuses over the whole document, and anything the proof does not
# cover must be guarded as before.


def _guarded_bytes(doc: str | bytes, monkeypatch) -> int:
    """How many characters (or bytes) the guard read of ``doc``, over every pass."""
    seen = []
    guard = xmlsafe._guard

    def spy(pieces):
        pieces = list(pieces)
        seen.append(sum(len(p) for p in pieces))
        return guard(pieces)

    monkeypatch.setattr(xmlsafe, "_guard", spy)
    with contextlib.suppress(AlignmentFormatError):
        landxml.read_road_file(doc)
    monkeypatch.undo()
    return sum(seen)


@pytest.mark.parametrize("as_bytes", [False, True])
def test_a_proved_content_is_left_out_of_the_guard_and_a_content_not_proved_is_guarded(monkeypatch, as_bytes):
    rng = random.Random(3)
    content = _random_sections(rng, 20)
    doc = _doc(f"<CrossSects>{content}</CrossSects>")
    doc = doc.encode() if as_bytes else doc
    assert _guarded_bytes(doc, monkeypatch) == len(doc) - len(content)
    # each of these is well-formed but not proved (or not well-formed): the whole document is guarded
    for odd in ("<!-- -->", "]]>", "&amp;", '<CrossSect sta="9" a="1" a="2"><DesignCrossSectSurf/></CrossSect>'):
        odd_doc = _doc(f"<CrossSects>{content} {odd} </CrossSects>")
        odd_doc = odd_doc.encode() if as_bytes else odd_doc
        assert _guarded_bytes(odd_doc, monkeypatch) >= len(odd_doc), odd


ONE = SECTION.format(sta=5, zl=99, zr=99)


def _in(content: str) -> str:
    return "<CrossSects>" + content + "</CrossSects>"


@pytest.mark.parametrize(
    "sections",
    [
        # not well-formed inside the sections: a forbidden character (between sections, in a point), "]]>" in text,
        # a duplicate attribute (on each start tag), an attribute name XML does not allow, an undefined entity, an
        # unbound prefix and a reserved namespace (the tree's parser reads namespaces)
        _in(ONE + "\x01"),
        _in(ONE.replace("<CrossSectPnt>0", "<CrossSectPnt>0\x0c")),
        _in(ONE + " ]]> "),
        _in(ONE.replace("sta=", 'a="1" a="2" sta=')),
        _in(ONE.replace("Surf name", 'Surf b="1" name="2" b')),
        _in(ONE.replace("<CrossSectPnt>", '<CrossSectPnt c="1" c="2">')),
        _in(ONE.replace("sta=", '1a="1" sta=')),
        _in(ONE + " &undefined; "),
        _in(ONE.replace("sta=", 'p:a="1" sta=')),
        _in(ONE.replace("sta=", 'xmlns="http://www.w3.org/2000/xmlns/" sta=')),
        # not well-formed after the sections (on a later line, and on the same line): the guard's own position
        "<CrossSects>\n" + ONE + "\r\n" + ONE.replace('sta="5', 'sta="55') + "\r</CrossSects><Oops></Alignment>",
        _in(ONE) + "<Oops a='1' a='2'/>",
        _in(ONE) + "&undefined;",
        # before them
        "<Oops a='<'/>" + _in(ONE),
        "<CrossSects a='1' a='2'>" + ONE + "</CrossSects>",
        # the sections not closed
        _in(ONE + "</CrossSect>"),
        _in("<CrossSect sta='1'>" + ONE),
    ],
)
@pytest.mark.parametrize("as_bytes", [False, True])
def test_a_malformed_document_is_refused_as_the_guard_refuses_it_whole(monkeypatch, sections, as_bytes):
    doc = _doc(sections)
    ours, _ = _outcome(doc.encode() if as_bytes else doc, scan=True, monkeypatch=monkeypatch)
    tree, _ = _outcome(doc.encode() if as_bytes else doc, scan=False, monkeypatch=monkeypatch)
    assert ours == tree
    assert ours[0] == "refused" and "malformed XML" in ours[1]


def test_entities_declared_before_the_sections_are_refused(monkeypatch):
    doc = _doc(f"<CrossSects>{SECTION.format(sta=5, zl=99, zr=99)}</CrossSects>")
    doc = doc.replace("<LandXML", '<!DOCTYPE LandXML [<!ENTITY e "x">]>\n<LandXML', 1)
    out = _same(doc, monkeypatch, scanned=False)
    assert out[0] == "refused" and "EntitiesForbidden" in out[1]


# ---------------------------------------------------------------------------------------------- the compiled scan
# What the compiled scan takes it must read as the Python scan reads it (the same stations, the same numbers bit for
# bit, each section's count, proved); what it does not take it declines (None), and the Python scan judges it. A
# region it declines costs time only, so these tests also require it to take the shapes design packages write.


def _numbers_of(sc) -> tuple[bytes, list[int], bytes, bool]:
    """A region's reading as data: the stations and the points' numbers as float64 bytes (bit for bit: -0.0 is not
    0.0), each section's count of numbers, and whether the content was proved well-formed."""
    if sc.station_values is not None:
        stations = np.asarray(sc.station_values, dtype=float)
    else:
        stations = np.array([float(t) for t in sc.stations], dtype=float)
    values = [v if v is not None else np.array([float(w) for w in words]) for _, _, v, words in sc.chunks]
    flat = np.concatenate(values) if values else np.empty(0)
    return stations.tobytes(), [int(c) for c in sc.counts], np.asarray(flat, dtype=float).tobytes(), sc.proved


def _compiled_agrees(content: bytes) -> bool:
    """Whether the compiled scan took ``content`` (every test here runs it on contents the Python scan is given
    too); where it did, its reading is the Python scan's."""
    mine = landxml._scan_region_compiled(content, 0, len(content))
    if mine is None:
        return False
    python = landxml._scan_region_python(content)
    assert python is not None, content
    assert _numbers_of(mine) == _numbers_of(python), content
    assert mine.proved
    # the points it picks give the slopes the Python scan's numbers give
    _, counts, values, _ = _numbers_of(python)
    slopes = landxml._slopes(np.frombuffer(values), np.array(counts, dtype=np.int64))
    assert landxml._slopes_from(*mine.picks.T).tobytes() == slopes.tobytes(), content
    return True


def _usual(n: int, rng: random.Random, *, spaced: bool = False) -> bytes:
    parts = []
    for k in range(n):
        zl, zr = 100 - rng.uniform(-0.2, 0.2), 100 + rng.uniform(-0.2, 0.2)
        one = SECTION.format(sta=f"{25 + 50 * k:g}", zl=f"{zl:.4f}", zr=f"{zr:.4f}")
        parts.append(one.replace("><", ">\n  <") if spaced else one)
    return "".join(parts).encode()


def test_the_compiled_scan_takes_the_shapes_writers_use_and_reads_them_as_the_python_scan(compiled):
    rng = random.Random(8)
    for content in (
        _usual(50, rng),
        _usual(50, rng, spaced=True),
        b"",
        b" \r\n\t",
        # attributes, either quote, white space where XML allows it, no point, one side only
        b'\n<CrossSect  name=\'0+25\' sta = " 25 " >\r\n<DesignCrossSectSurf name="Top" side=\'b"oth\'>'
        b"<CrossSectPnt >\t-3.5   99.9 </CrossSectPnt ><CrossSectPnt>0\n100</CrossSectPnt>"
        b"</DesignCrossSectSurf ></CrossSect\t>\n"
        b"<CrossSect sta='75'><DesignCrossSectSurf></DesignCrossSectSurf></CrossSect>"
        b'<CrossSect sta="1e2"><DesignCrossSectSurf><CrossSectPnt>+0 -0</CrossSectPnt>'
        b"<CrossSectPnt>.5 5.</CrossSectPnt><CrossSectPnt>-00.0500E+01 1E-3</CrossSectPnt></DesignCrossSectSurf>"
        b"</CrossSect>"
        # ties on each side (the first of equals) and several points at offset 0 (the last)
        b'<CrossSect sta="80"><DesignCrossSectSurf><CrossSectPnt>-3.5 1</CrossSectPnt><CrossSectPnt>-3.5 2'
        b"</CrossSectPnt><CrossSectPnt>0 5</CrossSectPnt><CrossSectPnt>-0 6</CrossSectPnt><CrossSectPnt>2 7"
        b"</CrossSectPnt><CrossSectPnt>2 8</CrossSectPnt><CrossSectPnt>-7 0</CrossSectPnt><CrossSectPnt>0.0 4"
        b"</CrossSectPnt><CrossSectPnt>9 9</CrossSectPnt></DesignCrossSectSurf></CrossSect>",
    ):
        assert _compiled_agrees(content), content
    # in chunks: a content over several MiB
    big = _usual(40_000, rng)
    assert len(big) > 2 * landxml._SCAN_CHUNK
    assert _compiled_agrees(big)


def _number_texts(rng: random.Random, n: int) -> list[str]:
    """Decimal texts of every form float() reads: signs, leading zeros, no integer or no fraction digits, up to 30
    significant digits, exponents far beyond a double's (overflow: not finite; underflow: 0 and subnormals), and
    the edges of the one-operation conversion (2^53, 10^22)."""
    out = ["0", "-0", "+0.0", "1.", ".5", "9007199254740992", "9007199254740993", "9007199254740993e-3", "1e22",
           "1e23", "1e-22", "1e-23", "123456789012345678", "1234567890123456789", "12345678901234567890",
           "0.1", "2.2250738585072011e-308", "4.9e-324", "2e-324", "1.7976931348623157e308", "1.8e308", "1e999",
           "-1e-999", "0e99999999999", "1e-99999999999", "0." + "0" * 30 + "1", "1" + "0" * 40, "1" * 400]  # fmt: skip
    for _ in range(n):
        digits = "".join(rng.choice("0123456789") for _ in range(rng.randint(1, 30)))
        point = rng.randint(0, len(digits))
        text = rng.choice(["", "-", "+"]) + digits[:point] + "." + digits[point:] if rng.random() < 0.8 else digits
        if rng.random() < 0.4:
            text += (
                rng.choice("eE")
                + rng.choice(["", "-", "+"])
                + str(rng.choice([rng.randint(0, 30), rng.randint(0, 400)]))
            )
        out.append(text)
    return out


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_the_compiled_scan_converts_numbers_as_float_does(compiled, seed):
    """Each number bit for bit Python's ``float`` of its text (the tree's reading converts the same text so), and a
    text whose number is not finite declined: the Python scan refuses it naming the section."""
    rng = random.Random(seed)
    for text in _number_texts(rng, 3000):
        x = float(text)
        got = compiled.scan(
            f'<CrossSect sta="{text}"><DesignCrossSectSurf><CrossSectPnt>{text} 1</CrossSectPnt>'
            f"</DesignCrossSectSurf></CrossSect>".encode()
        )
        if not math.isfinite(x):
            assert got is None, text
            continue
        assert got is not None, text
        stations, values = np.frombuffer(got[0]), np.frombuffer(got[2])
        expected = struct.pack("d", x)
        assert stations.tobytes() == expected and values[:1].tobytes() == expected, (text, x, stations, values)


SOUND = (
    b'<CrossSect sta="25"><DesignCrossSectSurf name="Top"><CrossSectPnt>-3.5 99.93</CrossSectPnt>'
    b"<CrossSectPnt>0 100</CrossSectPnt><CrossSectPnt>3.5 99.93</CrossSectPnt></DesignCrossSectSurf></CrossSect>"
)


@pytest.mark.parametrize(
    "content",
    [
        SOUND.replace(b"99.93<", b"nan<", 1),
        SOUND.replace(b"99.93<", b"inf<", 1),
        SOUND.replace(b"99.93<", b"-Infinity<", 1),
        SOUND.replace(b"99.93<", b"1e400<", 1),  # overflows: not finite
        SOUND.replace(b"99.93<", b"1_0<", 1),  # float() reads it; not a decimal the scan takes
        SOUND.replace(b"99.93<", b"0x1p3<", 1),
        SOUND.replace(b"99.93<", b"1.2.3<", 1),
        SOUND.replace(b"99.93<", b"99.93 EP<", 1),  # three words
        SOUND.replace(b"-3.5 99.93", b"-3.5", 1),  # one word
        SOUND.replace(b"-3.5 99.93", b"&#45;3.5 99.93", 1),  # a character reference
        SOUND.replace(b'sta="25"', b'sta="2&#53;"', 1),
        SOUND.replace(b'sta="25"', b'sta="2 5"', 1),
        SOUND.replace(b'sta="25"', b'sta=""', 1),
        SOUND.replace(b'sta="25"', b'name="x"', 1),  # no station
        SOUND.replace(b'sta="25"', b'sta="25" sta="26"', 1),  # twice
        SOUND.replace(b'name="Top"', b'name="Top" name="Top"', 1),
        SOUND.replace(b'name="Top"', b'l:name="Top"', 1),  # a namespace prefix
        SOUND.replace(b'name="Top"', b'xmlns="urn:x"', 1),
        SOUND.replace(b'name="Top"', b'XmLa="1"', 1),
        SOUND.replace(b'name="Top"', b'1a="1"', 1),
        SOUND.replace(b'name="Top"', b'name="a>b"', 1),
        SOUND.replace(b'name="Top"', b'name="a<b"', 1),
        SOUND.replace(b'name="Top"', b'name="T\x01p"', 1),
        SOUND.replace(b'name="Top"', b'name="T\xc3\xa9p"', 1),
        SOUND.replace(b'name="Top"', b"name=Top", 1),
        SOUND.replace(b'name="Top"', b'name="Top', 1),
        SOUND.replace(b' name="Top"', b'name="Top"', 1),
        SOUND.replace(b"<CrossSectPnt>0", b'<CrossSectPnt code="CL">0', 1),  # attributes on a point
        SOUND.replace(b"<CrossSectPnt>0 100</CrossSectPnt>", b"<CrossSectPnt/>", 1),
        SOUND.replace(b"<CrossSectPnt>0", b"<CrossSectPnt><!-- c -->0", 1),
        SOUND.replace(b"<CrossSectPnt>0", b"<CrossSectPnt><![CDATA[0]]>", 1),
        SOUND.replace(b"<CrossSectPnt>0", b"<CrossSectPnt><?pi?>0", 1),
        SOUND.replace(b"0 100", b"0\x0c100", 1),  # a character XML forbids
        SOUND.replace(b"0 100", b"0\xc2\xa0100", 1),  # not ASCII (the tree splits at the no-break space)
        SOUND.replace(b"<DesignCrossSectSurf", b"<CrossSectSurf", 1),
        SOUND.replace(b"<CrossSect ", b"<l:CrossSect ", 1),
        SOUND.replace(b"<CrossSect ", b"<CrossSectX ", 1),
        SOUND.replace(b"</CrossSect>", b"</CrossSectX>", 1),
        SOUND.replace(b"</DesignCrossSectSurf>", b"", 1),  # nested wrong
        SOUND.replace(b"</DesignCrossSectSurf></CrossSect>", b"</CrossSect></DesignCrossSectSurf>", 1),
        SOUND.replace(b"</CrossSectPnt>", b"</DesignCrossSectSurf>", 1),
        SOUND + SOUND.replace(b"<CrossSect ", b"<CrossSect><CrossSect ", 1),
        SOUND + b"stray text",  # text between sections (the tree ignores it; the Python scan judges it)
        SOUND + b"]]>",
        SOUND + b"<!-- -->",
        SOUND + b"</CrossSect>",
        b"<CrossSect/>",
        b"<",
    ],
)
def test_the_compiled_scan_declines_what_it_does_not_take(compiled, content):
    assert compiled.scan(SOUND) is not None
    assert compiled.scan(content) is None, content
    _compiled_agrees(content)


def test_a_truncated_content_is_declined_at_every_length(compiled):
    whole = SOUND.replace(b'name="Top"', b"name='T op' code=\"x\"") + b"\n"
    taken = [k for k in range(len(whole) + 1) if compiled.scan(whole[:k]) is not None]
    # only the empty content, the whole section, and the whole section with its trailing white space
    assert taken == [0, len(whole) - 1, len(whole)]
    for k in range(len(whole)):
        _compiled_agrees(whole[:k])


@pytest.mark.parametrize("seed", range(40))
def test_mutated_contents_are_declined_or_read_as_the_python_scan_reads_them(compiled, seed):
    """Random edits of valid contents with the characters that matter to XML and to numbers: whatever the compiled
    scan takes, the Python scan takes and reads alike."""
    rng = random.Random(seed)
    base = bytearray(_usual(4, rng, spaced=seed % 2 == 1))
    alphabet = b"<>/=\"'&;!?-. \t\n\r\x00\x01\x7f\xffeE+0123456789aAxX:_[]"
    digits = [k for k, c in enumerate(base) if chr(c).isdigit()]
    taken = 0
    for _ in range(200):
        doc = bytearray(base)
        for _ in range(rng.randint(1, 3)):
            at = rng.randrange(len(doc) + 1)
            what = rng.random()
            if what < 0.15:  # a digit for a digit (a valid content, another number)
                doc[rng.choice(digits)] = ord(rng.choice("0123456789"))
            elif what < 0.4 and at < len(doc):
                doc[at] = rng.choice(alphabet)
            elif what < 0.7:
                doc[at:at] = bytes([rng.choice(alphabet)])
            else:
                del doc[at : at + rng.randint(1, 8)]
        taken += _compiled_agrees(bytes(doc))
    assert taken  # some edits keep a valid content (a digit for a digit, white space for white space)


def test_a_document_the_compiled_scan_reads_answers_as_the_tree(compiled, monkeypatch):
    rng = random.Random(21)
    doc = _doc("<CrossSects>" + _usual(30, rng, spaced=True).decode() + "</CrossSects>").encode()
    sc = landxml._cross_section_scan(doc)
    assert sc is not None and all(region.station_values is not None for region in sc[1].values())  # (it read them)
    out = _same(doc, monkeypatch, scanned=True)
    assert out[0] == "read" and len(out[1][0]) == 30


def _slopes_one_by_one(values: list[float], counts: list[int]) -> list[tuple[float, float]]:
    """landxml._slopes's rule, section by section in plain Python (the second formulation): the nearest point on
    each side (the first of equals), the centreline's elevation the last point at offset 0, else interpolated."""
    out, at = [], 0
    for c in counts:
        pts = [(values[at + 2 * k], values[at + 2 * k + 1]) for k in range(c // 2)]
        at += c
        lefts = [p for p in pts if p[0] < 0]
        rights = [p for p in pts if p[0] > 0]
        if not lefts or not rights:
            out.append((math.nan, math.nan))
            continue
        xl, zl = next(p for p in lefts if p[0] == max(q[0] for q in lefts))
        xr, zr = next(p for p in rights if p[0] == min(q[0] for q in rights))
        centre = [p[1] for p in pts if p[0] == 0]
        zc = centre[-1] if centre else zl + (zr - zl) * (0 - xl) / (xr - xl)
        out.append((100.0 * (zc - zl) / (0 - xl), 100.0 * (zr - zc) / xr))
    return out


@pytest.mark.parametrize("seed", range(5))
def test_the_slopes_are_the_rule_applied_section_by_section(seed):
    """Ties (the first of equals), several points at offset 0 (the last), sections with no point, one side only or
    an odd number of numbers, offsets of -0.0: the vectorised slopes, bit for bit the rule's."""
    rng = random.Random(seed)
    counts = [rng.choice([0, 1, 2, 3, 4, 6, 6, 6, 7, 10, 14]) for _ in range(500)]
    offsets = [-7.0, -3.5, -3.5, -1e-9, -0.0, 0.0, 0.0, 1e-9, 3.5, 3.5, 7.0]
    values = []
    for c in counts:
        for k in range(c):
            values.append(rng.choice(offsets) if k % 2 == 0 else round(rng.uniform(99, 101), rng.randint(0, 6)))
    got = landxml._slopes(np.array(values), np.array(counts))
    expected = np.array(_slopes_one_by_one(values, counts)).reshape(-1, 2)
    assert got.tobytes() == expected.tobytes()


@pytest.mark.parametrize("end_tag", ["</CrossSect>", "</CrossSect >", "</CrossSect\n>"])
def test_the_compiled_scan_is_called_a_chunk_at_a_time_however_the_sections_end(compiled, monkeypatch, end_tag):
    """Each call holds the interpreter's lock: a content of several MiB is handed over about a MiB at a time, cut
    after a section's end tag however it is written."""
    rng = random.Random(4)
    content = _usual(40_000, rng).replace(b"</CrossSect>", end_tag.encode())
    sizes = []

    class Spy:
        @staticmethod
        def scan(chunk):
            sizes.append(len(chunk))
            return compiled.scan(chunk)

    monkeypatch.setattr(landxml, "_xsectscan", Spy)
    assert _compiled_agrees(content)
    assert len(sizes) >= 3 and sum(sizes) == len(content)
    assert max(sizes) < landxml._SCAN_CHUNK + 1000


@pytest.mark.parametrize("chunk", [1, 3, 7, 64])
def test_the_chunked_find_and_ascii_encoding_equal_one_call(monkeypatch, chunk):
    """A 64 MiB document's search for </CrossSects> and the ASCII encoding of a content sent as text go a chunk at a
    time (the lock given up between two); whatever the chunk, the same answer as one call."""
    monkeypatch.setattr(landxml, "_SCAN_CHUNK", chunk)
    rng = random.Random(chunk)
    for _ in range(200):
        text = "".join(rng.choice("ab</Cé") for _ in range(rng.randint(0, 40)))
        sub = rng.choice(["</C", "b", "ab<", "é", "</CrossSects"])
        start = rng.randint(0, len(text))
        assert landxml._find(text, sub, start) == text.find(sub, start)
        assert landxml._find(text.encode(), sub.encode(), start) == text.encode().find(sub.encode(), start)
        end = rng.randint(start, len(text))
        got = landxml._ascii(text, start, end)
        want = text[start:end].encode("ascii") if text[start:end].isascii() else None
        assert (None if got is None else bytes(got)) == want
