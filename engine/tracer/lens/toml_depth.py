"""How deeply a TOML text nests arrays and inline tables, found without parsing it.

Python's ``tomllib`` parses nested values recursively, so a few hundred ``[`` end in a ``RecursionError``
(a traceback, not a message). A lens file nests two deep at most (a ``[[surface]]`` header, the ``notes``
list); anything deeper than ``MAX_DEPTH`` is refused before ``tomllib`` sees it.
"""

from __future__ import annotations

#: Far above what a lens file needs (2), far below where ``tomllib`` runs out of Python's stack (~300).
MAX_DEPTH = 32
_OPEN, _CLOSE = "[{", "]}"


def deepest_nesting(text: str) -> tuple[int, int]:
    """(the deepest nesting of brackets and braces outside strings and comments, the line it is first
    reached on, 1-based)."""
    depth = deepest = 0
    deepest_line = line = 1
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
        elif c == "#":
            end = text.find("\n", i)
            i = n if end < 0 else end
            continue
        elif c in "\"'":
            quote = c * 3 if text.startswith(c * 3, i) else c
            i, line = _after_string(text, i + len(quote), quote, line)
            continue
        elif c in _OPEN:
            depth += 1
            if depth > deepest:
                deepest, deepest_line = depth, line
        elif c in _CLOSE:
            depth = max(depth - 1, 0)
        i += 1
    return deepest, deepest_line


def _after_string(text: str, i: int, quote: str, line: int) -> tuple[int, int]:
    """The index after the string whose body starts at ``i`` and the line there (a string left open runs
    to the end of its line, or of the text for a multi-line one: ``tomllib`` reports it)."""
    escapes = quote[0] == '"'
    while i < len(text):
        c = text[i]
        if escapes and c == "\\":
            line += text.startswith("\n", i + 1)
            i += 2
            continue
        if c == "\n":
            if len(quote) == 1:
                return i, line
            line += 1
        if text.startswith(quote, i):
            return i + len(quote), line
        i += 1
    return i, line
