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

Both passes are fed :data:`CHUNK` characters (or bytes) at a time. A parser's one call over a whole document is one C
call that holds the interpreter's lock throughout: a 56 MiB LandXML held it for 4 s, and every other request of the
process (the event loop's own) waited that long. Between chunks the reading thread gives the lock up
(``time.sleep(0)``), so another thread waits at most one chunk's parse (a few milliseconds) for it; the chunks are
views, not copies, and expat keeps its state (and its error positions) across them.

Two more waits of the same kind come from the tree itself, and the readers avoid both
(:func:`collection_paused`, :func:`free`): the cyclic garbage collector's full passes, each a C call over every
object alive (the tree's million elements: up to a second each, several while the tree grows), and the freeing of
the tree, one C call that frees every element when the root's last reference goes.
"""

from __future__ import annotations

import gc
import threading
import time
import xml.etree.ElementTree as ET
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from typing import NoReturn
from xml.parsers import expat

from defusedxml.common import DefusedXmlException, EntitiesForbidden, ExternalReferenceForbidden

ParseError = ET.ParseError
#: characters (or bytes) per parser call: about 2 ms of parsing on the 2-core development machine (a few MB/s under
#: load to 30 MB/s), the longest another thread waits for the interpreter's lock while a document is read
CHUNK = 64 * 2**10


def _entity(name, is_parameter_entity, value, base, sysid, pubid, notation_name) -> NoReturn:
    raise EntitiesForbidden(name, value, base, sysid, pubid, notation_name)


def _unparsed_entity(name, base, sysid, pubid, notation_name) -> NoReturn:
    raise EntitiesForbidden(name, None, base, sysid, pubid, notation_name)


def _external_reference(context, base, sysid, pubid) -> NoReturn:
    raise ExternalReferenceForbidden(context, base, sysid, pubid)


#: a reader's edit of a document (:func:`fromstring`): the pieces to build the tree from and the pieces to guard, or
#: None (the document for both)
Edit = Callable[[str | bytes], tuple[Iterable[str | bytes | memoryview], Iterable[str | bytes | memoryview]] | None]


def fromstring(text: str | bytes, edit: Edit | None = None) -> ET.Element:
    """The document's root element; raises ``defusedxml.common.DefusedXmlException`` (an entity declared, an external
    entity referenced) or :class:`ParseError` (not well-formed: ``.position`` is (line, column)).

    ``edit`` lets a reader take part of a document without a tree (app/formats/landxml.py, the cross sections): it
    gives the pieces (of ``text``'s type) the tree is built from and the pieces the guard reads, the document with
    the parts the reader has itself proved well-formed element content left out (the reader's proof: only known
    tags with distinct well-formed attribute names, no reference, no markup declaration, no character XML forbids;
    content that is balanced in itself leaves the rest of the document as well-formed as it was). The guard's
    verdict and errors are always the whole document's: where the pieces fail it, the whole document is guarded
    again and its own error raised (with its position in the document)."""
    pieces = edit(text) if edit is not None else None
    tree, guarded = ((text,), (text,)) if pieces is None else pieces
    try:
        _guard(guarded)
    except (DefusedXmlException, ParseError):
        if pieces is None:
            raise
        _guard((text,))  # the whole document's own error (and its position)
        tree = (text,)  # (a proof that was wrong: the whole document passes, and is read as a tree)
    parser = ET.XMLParser()
    for piece in tree:
        for chunk in _chunks(piece):
            parser.feed(chunk)
    return parser.close()


def _guard(pieces: Iterable[str | bytes | memoryview]) -> None:
    """Parse ``pieces`` (one document) with the guard's handlers only; raise as :func:`fromstring` says."""
    guard = expat.ParserCreate()
    guard.EntityDeclHandler = _entity
    guard.UnparsedEntityDeclHandler = _unparsed_entity
    guard.ExternalEntityRefHandler = _external_reference
    try:
        for piece in pieces:
            for chunk in _chunks(piece):
                guard.Parse(chunk, False)
        guard.Parse(b"", True)
    except expat.ExpatError as exc:
        err = ParseError(expat.ErrorString(exc.code) + f": line {exc.lineno}, column {exc.offset}")
        err.code, err.position = exc.code, (exc.lineno, exc.offset)
        raise err from None


def _chunks(text: str | bytes):
    """``text`` in pieces of :data:`CHUNK` (views of bytes; slices of a str), the lock given up after each."""
    data = memoryview(text) if isinstance(text, bytes | bytearray) else text
    for start in range(0, len(data), CHUNK):
        yield data[start : start + CHUNK]
        time.sleep(0)  # let a waiting thread (the event loop) run between two C calls that hold the lock


#: elements freed per call of :func:`free` (a few milliseconds)
FREE_SLICE = 4096
_pause_lock = threading.Lock()
_pauses = 0
_was_enabled = False


@contextmanager
def collection_paused() -> Iterator[None]:
    """The cyclic garbage collector off while a document is read (process-wide: counted, so overlapping readings
    turn it back on when the last one ends, and only if it was on). A reading makes millions of objects and frees
    them itself (:func:`free`); the collector's passes over them would hold the interpreter's lock for up to a
    second each and make no garbage of them. Cycles other threads make meanwhile are collected afterwards."""
    global _pauses, _was_enabled
    with _pause_lock:
        if _pauses == 0:
            _was_enabled = gc.isenabled()
            gc.disable()
        _pauses += 1
    try:
        yield
    finally:
        with _pause_lock:
            _pauses -= 1
            if _pauses == 0 and _was_enabled:
                gc.enable()


def free(root: ET.Element) -> None:
    """Free a tree :data:`FREE_SLICE` elements at a time (each a short C call; the interpreter switches threads
    between them) instead of in one C call when the root's last reference goes. The tree is emptied (``root`` is
    left with no children)."""
    stack = [root]
    while stack:
        el = stack.pop()
        while len(el):
            part = el[-FREE_SLICE:]
            del el[-FREE_SLICE:]
            stack.extend(filter(len, part))  # those with children are emptied in turn (filter: a C loop)
            del part  # the leaves go here


def local(tag: str) -> str:
    """An element's tag without its namespace (``{http://...}Curve`` -> ``Curve``)."""
    return tag.rsplit("}", 1)[-1]


def document(
    text: str | bytes,
    root: str,
    label: str,
    error: Callable[[str, str], Exception],
    edit: Edit | None = None,
) -> ET.Element:
    """The root element of a document whose root must be ``<root>`` (any namespace); each refusal raised as
    ``error(message, where)``, ``where`` starting with ``label`` (``"LandXML line 3, column 7"``): the one way the
    readers of LandXML and GPX word them. ``edit``: see :func:`fromstring`."""
    try:
        element = fromstring(text, edit)
    except DefusedXmlException as exc:
        raise error(f"refused: {exc.__class__.__name__} (entities are not allowed)", label) from None
    except ParseError as exc:
        line, col = getattr(exc, "position", (None, None))
        raise error(f"malformed XML: {exc}", f"{label} line {line}, column {col}") from None
    if local(element.tag) != root:
        raise error(f"the root element is <{local(element.tag)}>, not <{root}>", label)
    return element
