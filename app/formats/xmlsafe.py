"""An XML document parsed into an ElementTree as ``defusedxml.ElementTree.fromstring`` parses it (the same refusals:
no entity declarations, no external entity references), at the speed of CPython's C ElementTree.

``defusedxml`` guards the parse by setting three handlers on its expat parser: an entity declaration (parsed or
unparsed) raises ``EntitiesForbidden``, an external entity reference ``ExternalReferenceForbidden``. To reach that
expat parser it subclasses the pure-Python ``XMLParser``, whose TreeBuilder calls Python for every start and end tag:
a LandXML alignment of 200,000 curves (42 MiB, 1.4 million elements) took 4.6 s to read, most of it in those calls.

Here the same three handlers are set on a bare expat parser with no other handler, which reads the whole document in
C (well-formedness and the guards, nothing kept); only a document that passes is then parsed by the C ElementTree.
Without an entity declaration the tree cannot expand anything (the five predefined entities and character references
aside, an undefined entity is a well-formedness error in both passes), so the second pass needs no guard. The errors
are ``defusedxml``'s own classes and ``xml.etree.ElementTree.ParseError`` with expat's message and position, as
``defusedxml.ElementTree.fromstring`` raises them (tests/road/test_xmlsafe.py compares both on bombs and malformed
documents).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from collections.abc import Callable
from typing import NoReturn
from xml.parsers import expat

from defusedxml.common import DefusedXmlException, EntitiesForbidden, ExternalReferenceForbidden

ParseError = ET.ParseError


def _entity(name, is_parameter_entity, value, base, sysid, pubid, notation_name) -> NoReturn:
    raise EntitiesForbidden(name, value, base, sysid, pubid, notation_name)


def _unparsed_entity(name, base, sysid, pubid, notation_name) -> NoReturn:
    raise EntitiesForbidden(name, None, base, sysid, pubid, notation_name)


def _external_reference(context, base, sysid, pubid) -> NoReturn:
    raise ExternalReferenceForbidden(context, base, sysid, pubid)


def fromstring(text: str | bytes) -> ET.Element:
    """The document's root element; raises ``defusedxml.common.DefusedXmlException`` (an entity declared, an external
    entity referenced) or :class:`ParseError` (not well-formed: ``.position`` is (line, column))."""
    guard = expat.ParserCreate()
    guard.EntityDeclHandler = _entity
    guard.UnparsedEntityDeclHandler = _unparsed_entity
    guard.ExternalEntityRefHandler = _external_reference
    try:
        guard.Parse(text, True)
    except expat.ExpatError as exc:
        err = ParseError(expat.ErrorString(exc.code) + f": line {exc.lineno}, column {exc.offset}")
        err.code, err.position = exc.code, (exc.lineno, exc.offset)
        raise err from None
    return ET.fromstring(text)


def local(tag: str) -> str:
    """An element's tag without its namespace (``{http://...}Curve`` -> ``Curve``)."""
    return tag.rsplit("}", 1)[-1]


def document(text: str | bytes, root: str, label: str, error: Callable[[str, str], Exception]) -> ET.Element:
    """The root element of a document whose root must be ``<root>`` (any namespace); each refusal raised as
    ``error(message, where)``, ``where`` starting with ``label`` (``"LandXML line 3, column 7"``): the one way the
    readers of LandXML and GPX word them."""
    try:
        element = fromstring(text)
    except DefusedXmlException as exc:
        raise error(f"refused: {exc.__class__.__name__} (entities are not allowed)", label) from None
    except ParseError as exc:
        line, col = getattr(exc, "position", (None, None))
        raise error(f"malformed XML: {exc}", f"{label} line {line}, column {col}") from None
    if local(element.tag) != root:
        raise error(f"the root element is <{local(element.tag)}>, not <{root}>", label)
    return element
