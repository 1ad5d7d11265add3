"""Recognising text that is not UTF-8, so a message can say what it is rather than "binary".

Windows editors (Notepad's "Unicode", Excel's "Unicode text", PowerShell's ``>``) write UTF-16: a byte
order mark and a zero byte beside every ASCII character. Prism reads UTF-8 text files only.
"""

from __future__ import annotations

_UTF16_MARKS = (b"\xff\xfe", b"\xfe\xff")


def utf16_name(head: bytes) -> str | None:
    """``"UTF-16 (little-endian)"`` or ``"UTF-16 (big-endian)"`` when ``head`` (a file's first bytes) looks
    like UTF-16 text, else None. Without a byte order mark, text of ASCII characters in UTF-16 has a zero
    in every other byte."""
    if head.startswith(b"\xff\xfe"):
        return "UTF-16 (little-endian)"
    if head.startswith(b"\xfe\xff"):
        return "UTF-16 (big-endian)"
    sample = head[: len(head) - len(head) % 2][:4096]
    if len(sample) < 8:
        return None
    even, odd = sample[0::2], sample[1::2]
    if odd.count(0) == len(odd) and even.count(0) == 0:
        return "UTF-16 (little-endian)"
    if even.count(0) == len(even) and odd.count(0) == 0:
        return "UTF-16 (big-endian)"
    return None


def utf16_advice(head: bytes) -> str | None:
    """The clause a message gives for a UTF-16 file, or None when ``head`` is not UTF-16."""
    name = utf16_name(head)
    if name is None:
        return None
    return f"is {name} text, which Prism does not read: save it as UTF-8 (e.g. Notepad ▸ Save As ▸ Encoding UTF-8)"
