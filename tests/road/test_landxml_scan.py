"""The design cross sections read without a tree (app/formats/landxml.py, ``_cross_section_scan``) give what the
tree's reading gives, document by document: the same slopes and the same reading summary, or the same refusal word
for word. The second formulation is the tree's reading itself (the scan switched off), the one every other LandXML
test checks against the files' own numbers; the scan must be taken where it applies (else these tests compare the
tree with itself) and left where it does not recognise a section's shape.
"""

from __future__ import annotations

import contextlib
import random

import pytest

from app.formats import landxml, xmlsafe
from app.formats.alignment_io import AlignmentFormatError
from tests.landxml_writer import Design, Element
from tests.landxml_writer import landxml as write_landxml

SCAN = landxml._cross_section_scan
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
