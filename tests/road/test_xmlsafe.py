"""app.formats.xmlsafe parses as defusedxml.ElementTree.fromstring does: the same tree, the same refusals (the same
exception classes), the same well-formedness errors (message and position), on bombs, external references and
malformed documents."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import defusedxml.ElementTree as DefusedET
import pytest
from defusedxml.common import DefusedXmlException

from app.formats import xmlsafe

_LANDXML = '<LandXML xmlns="http://www.landxml.org/schema/LandXML-1.2" version="1.2">{}</LandXML>'
_CURVES = (
    '<Alignments><Alignment name="A&amp;B &#233;"><CoordGeom><Curve name="C1" radius="250.5" staStart="0"/>'
    '<!-- a comment --><Curve name="C2" radius="180"><![CDATA[<Curve>]]></Curve></CoordGeom></Alignment></Alignments>'
)

VALID = [
    _LANDXML.format(_CURVES),
    '<?xml version="1.0" encoding="UTF-8"?>\n' + _LANDXML.format(_CURVES),
    "<!DOCTYPE LandXML>" + _LANDXML.format(""),  # a DTD without declarations: allowed, as defusedxml allows it
    '<?xml version="1.0"?><gpx version="1.1"><trk><trkseg><trkpt lat="1" lon="2"><ele>3</ele></trkpt></trkseg></trk>'
    "</gpx>",
]

REFUSED = [
    '<?xml version="1.0"?><!DOCTYPE g [<!ENTITY a "aaaa"><!ENTITY b "&a;&a;">]><gpx>&b;</gpx>',  # billion laughs
    '<!DOCTYPE x [<!ENTITY a "aaaa">]><LandXML/>',  # declared, never used: refused all the same
    '<!DOCTYPE x [<!ENTITY % p "x">]><LandXML/>',  # a parameter entity
    '<!DOCTYPE x [<!NOTATION n SYSTEM "n"><!ENTITY u SYSTEM "file:///etc/passwd" NDATA n>]><LandXML/>',  # unparsed
    '<!DOCTYPE x [<!ENTITY e SYSTEM "file:///etc/passwd">]><LandXML>&e;</LandXML>',  # XXE
]

MALFORMED = [
    "",
    "<LandXML>",
    "<LandXML></landxml>",
    "<LandXML>&undefined;</LandXML>",  # no DTD: an undefined entity is not well-formed
    '<LandXML a="1" a="2"/>',
    "<LandXML/><second/>",
    "<LandXML>\n  <Alignment name='x'>\n  </Alignmen>\n</LandXML>",
    "\ufeff<LandXML/>junk",
]


def _outcome(parse, text: str | bytes):
    try:
        return "tree", ET.tostring(parse(text))
    except DefusedXmlException as exc:
        return "refused", type(exc).__name__
    except ET.ParseError as exc:
        return "malformed", str(exc), exc.position


@pytest.mark.parametrize("text", VALID + REFUSED + MALFORMED)
@pytest.mark.parametrize("as_bytes", [False, True])
def test_the_same_outcome_as_defusedxml(text, as_bytes):
    doc = text.encode() if as_bytes else text
    ours, theirs = _outcome(xmlsafe.fromstring, doc), _outcome(DefusedET.fromstring, doc)
    assert ours == theirs
    kind = "tree" if text in VALID else "refused" if text in REFUSED else "malformed"
    assert ours[0] == kind  # and each list is what it says: a test of the lists themselves


def test_a_refusal_is_raised_before_the_tree_is_built(monkeypatch):
    """The guard pass refuses; the C ElementTree never sees a document with an entity declaration."""
    monkeypatch.setattr(xmlsafe.ET, "fromstring", lambda text: pytest.fail("the tree was built"))
    for text in REFUSED:
        with pytest.raises(DefusedXmlException):
            xmlsafe.fromstring(text)


def test_a_document_read_in_chunks_is_the_same_tree_and_an_error_past_a_chunk_has_its_own_position(monkeypatch):
    # many chunks (of 7 characters): the tree and a malformed document's line and column as parsed whole
    doc = '<?xml version="1.0"?>\n<r a="1">' + "".join(f'<c n="{k}">é{k}</c>\n' for k in range(50)) + "</r>"
    whole = ET.fromstring(doc)
    monkeypatch.setattr(xmlsafe, "CHUNK", 7)
    for text in (doc, doc.encode()):
        got = xmlsafe.fromstring(text)
        assert ET.tostring(got) == ET.tostring(whole)
    bad = doc.replace('<c n="40">', '<c n="40"', 1)
    with pytest.raises(ET.ParseError) as expected:
        DefusedET.fromstring(bad)
    with pytest.raises(ET.ParseError) as got_error:
        xmlsafe.fromstring(bad)
    assert got_error.value.position == expected.value.position
    with pytest.raises(DefusedXmlException):  # the guards hold in chunks
        xmlsafe.fromstring('<!DOCTYPE r [<!ENTITY e "x">]><r>&e;</r>')


def test_free_empties_the_tree_and_the_collector_is_paused_until_the_last_reading_ends():
    import gc

    root = ET.fromstring("<r>" + "<a><b/><c><d/></c></a>" * 10_000 + "<e/></r>")
    kept = root[0]
    xmlsafe.free(root)
    assert len(root) == 0 and len(kept) == 0
    assert gc.isenabled()
    with xmlsafe.collection_paused():
        assert not gc.isenabled()
        with xmlsafe.collection_paused():
            assert not gc.isenabled()
        assert not gc.isenabled()  # the outer reading is still on
    assert gc.isenabled()
    gc.disable()
    try:  # a collector that was off stays off
        with xmlsafe.collection_paused():
            pass
        assert not gc.isenabled()
    finally:
        gc.enable()
