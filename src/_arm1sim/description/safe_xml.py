"""XML that may come from the network, parsed with defusedxml and a bounded tree.

defusedxml refuses DTDs (and with them entity expansion, the "billion laughs")
and external entities (``file:///etc/passwd``) before expat acts on them. On
top of that the tree may hold at most ``max_elements`` elements and nest at
most ``MAX_DEPTH`` deep, so a hostile document costs bounded memory, and the
stdlib's recursive serialiser (``ET.tostring``) cannot overflow the stack.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from typing import Any, Optional, Union

from defusedxml import DTDForbidden, EntitiesForbidden, ExternalReferenceForbidden
from defusedxml.ElementTree import DefusedXMLParser

# URDF and SDF nest about 10 deep; 100 leaves room and stays far from recursion limits.
MAX_DEPTH = 100


class XmlRefused(ValueError):
    """The document is refused; the message names the document and the reason."""


class TooManyElements(XmlRefused):
    """The document holds more elements than its caller allows."""


class _BoundedTreeBuilder(ET.TreeBuilder):
    """A TreeBuilder that stops the parse once the tree gets too big or too deep."""

    def __init__(self, what: str, max_elements: Optional[int], max_depth: int) -> None:
        super().__init__()
        self.what, self.max_elements, self.max_depth = what, max_elements, max_depth
        self.elements = self.depth = 0
        self.line = lambda: 0  # set once the parser exists

    # Comments are dropped (as TreeBuilder drops them) without a Python call or a Comment
    # element each: a C builtin is their handler (50 MB of comments: 4.1 s -> 0.31 s of parsing)
    comment = staticmethod(len)  # type: ignore[assignment]  # its result is ignored

    def start(self, tag: str, attrs: dict) -> ET.Element:
        self.elements += 1
        self.depth += 1
        if self.max_elements is not None and self.elements > self.max_elements:
            raise TooManyElements(
                '%s has more than %d XML elements (line %d)'
                % (self.what, self.max_elements, self.line())
            )
        if self.depth > self.max_depth:
            raise XmlRefused(
                '%s nests XML elements more than %d deep (line %d)'
                % (self.what, self.max_depth, self.line())
            )
        return super().start(tag, attrs)

    def end(self, tag: str) -> ET.Element:
        self.depth -= 1
        return super().end(tag)


# expat holds the interpreter lock for a whole feed() call: fed a piece at a time, a
# 50 MB description lets the physics thread run between pieces (a few ms each).
PIECE = 1 << 18  # characters


def feed_in_pieces(parser: Any, text: Union[str, bytes]) -> ET.Element:
    """``parser.close()`` after feeding ``text`` PIECE characters at a time."""
    for start in range(0, len(text), PIECE):
        parser.feed(text[start : start + PIECE])
    return parser.close()


def utf8_size(text: Union[str, bytes]) -> int:
    """Bytes of ``text`` in UTF-8, encoded PIECE characters at a time (one encode of 50 MB
    holds the interpreter lock for 30-60 ms); lone surrogates count as three bytes."""
    if isinstance(text, bytes):
        return len(text)
    if text.isascii():  # one pass without a copy
        return len(text)
    return sum(
        len(text[start : start + PIECE].encode('utf-8', 'surrogatepass'))
        for start in range(0, len(text), PIECE)
    )


def parse_trusted(text: str) -> ET.Element:
    """A document this process wrote itself (already refused or accepted by parse), parsed
    a piece at a time like parse, without its checks."""
    return feed_in_pieces(ET.XMLParser(), text)


def parse(
    text: Union[str, bytes],
    what: str,
    max_elements: Optional[int] = None,
    max_depth: int = MAX_DEPTH,
) -> ET.Element:
    """The root element of ``text``; raises XmlRefused naming ``what`` and the reason.

    No DTD is accepted (URDF, SDF and xacro's output have none), so no entity
    can be declared, expanded or fetched.
    """
    target = _BoundedTreeBuilder(what, max_elements, max_depth)
    parser = DefusedXMLParser(
        target=target, forbid_dtd=True, forbid_entities=True, forbid_external=True
    )
    target.line = lambda: parser.parser.CurrentLineNumber
    try:
        return feed_in_pieces(parser, text)
    except DTDForbidden:
        raise XmlRefused(
            '%s has a document type declaration (<!DOCTYPE>): refused, since '
            'a DTD can declare entities that expand without bound; URDF and '
            'SDF need none' % what
        ) from None
    except EntitiesForbidden:  # only reachable through a DTD, refused above; kept for safety
        raise XmlRefused('%s declares an XML entity: refused' % what) from None
    except ExternalReferenceForbidden:
        raise XmlRefused('%s refers to an external XML entity: refused' % what) from None
    except ET.ParseError as exc:
        raise XmlRefused('%s is not well-formed XML: %s' % (what, exc)) from None
    except UnicodeError:  # a str with lone surrogates cannot be handed to expat
        raise XmlRefused('%s is not valid Unicode text' % what) from None
