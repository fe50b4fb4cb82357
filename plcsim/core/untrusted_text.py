"""Text a submission chose, made safe for the medium it is written to: a terminal, XML 1.0, CSV, JSON.

A submission chooses more of its report than its score: its file name, the labels and names a
compile error echoes, the message of the error it raised. Such a string may hold control characters
(a screen clear, a forged coloured verdict, an OSC-8 link), bidirectional overrides that reorder what a
reader sees, characters XML 1.0 forbids (one of them makes a whole class's ``junit.xml`` unreadable), a
spreadsheet formula, or a megabyte. Every report writer passes each string through the function of its
medium, here and nowhere else:

- :func:`for_terminal`: control and format characters shown as visible escapes (``\\x1b`` is printed as
  the four characters ``\\x1b``, never sent), cut to a length a screen can hold;
- :func:`for_xml`: the same escapes, which leave only characters XML 1.0 allows;
- :func:`for_csv`: one line, visible escapes, and a leading ``'`` before what a spreadsheet would run as
  a formula;
- :func:`for_json`: the text as it is (JSON escapes any character), only lone surrogates, which are not
  Unicode and which a strict parser refuses, shown as escapes.

>>> for_terminal("\\x1b[2J\\x1b[32mPASSED\\u202e")
'\\\\x1b[2J\\\\x1b[32mPASSED\\\\u202e'
>>> for_csv("=HYPERLINK(\\"http://x\\")")
'\\'=HYPERLINK("http://x")'
>>> for_terminal("x" * 30, limit=10)
'xxxxxxxxxx… [20 more characters cut]'
"""

from __future__ import annotations

import re
import unicodedata

TERMINAL_LIMIT = 4_000
"""Most characters of one string a terminal report prints (a message of 3 MB would fill the screen)."""
XML_LIMIT = 20_000
"""Most characters of one string in a JUnit file (CI viewers choke on megabytes in one attribute)."""
CSV_LIMIT = 200
"""Most characters of one gradebook cell (its first line)."""

_ESCAPED_CATEGORIES = frozenset({"Cc", "Cf", "Zl", "Zp", "Cs"})
"""Control and format characters (bidirectional overrides, zero-width spaces), line and paragraph
separators, and lone surrogates: what moves the cursor, reorders or hides text, or is not Unicode."""
_NONCHARACTERS = frozenset("\ufffe\uffff")
"""Not characters, and forbidden by XML 1.0."""
_FORMULA_STARTS = ("=", "+", "-", "@", "\t", "\r")

# Printable ASCII and Latin to Hebrew (which hold no control or format character but the soft hyphen)
# are left alone without a look-up; every other character is looked up once.
_SUSPECT = re.compile(r"[^\x20-\x7e\u00a0-\u00ac\u00ae-\u05ff]")
_SUSPECT_BUT_NEWLINE = re.compile(r"[^\n\x20-\x7e\u00a0-\u00ac\u00ae-\u05ff]")
_SURROGATE = re.compile(r"[\ud800-\udfff]")


def escape(ch: str) -> str:
    r"""The visible escape of one character, as Python writes it (``\x1b``, ``\u202e``, ``\U000e0001``)."""
    code = ord(ch)
    if code < 0x100:
        return f"\\x{code:02x}"
    return f"\\u{code:04x}" if code < 0x10000 else f"\\U{code:08x}"


def _escape_if_unsafe(match: re.Match[str]) -> str:
    ch = match.group()
    return escape(ch) if ch in _NONCHARACTERS or unicodedata.category(ch) in _ESCAPED_CATEGORIES else ch


def visible(text: str, *, newlines: bool = True) -> str:
    """``text`` with every control or format character, separator, surrogate and non-character written as
    its escape; ``newlines`` keeps line feeds (a multi-line message), otherwise they are escaped too."""
    pattern = _SUSPECT_BUT_NEWLINE if newlines else _SUSPECT
    return pattern.sub(_escape_if_unsafe, str(text))


def visible_cut(text: str, limit: int, *, newlines: bool = True) -> str:
    """:func:`visible` ``text``, at most ``limit`` characters of it once escaped, saying how many of its
    own characters were cut (nothing is dropped silently)."""
    text = str(text)
    shown = visible(text[:limit], newlines=newlines)[:limit]
    kept = len(text) if len(text) <= limit and len(shown) < limit else _kept(text, shown, newlines)
    return shown if kept == len(text) else f"{shown}… [{len(text) - kept:,} more characters cut]"


def clip(text: str, limit: int) -> str:
    """``text``, or if it is longer than ``limit`` its head and how many characters were cut, at most
    ``limit`` characters in all: a message a bounded channel can carry (the grading child's result).

    >>> clip("a.py, line 1: " + "x" * 100, 60)
    'a.py, line 1: xxxxxxxxxxxxxxxxxxx… [81 more characters cut]'
    """
    text = str(text)
    if len(text) <= limit:
        return text
    note = f"… [{len(text):,} more characters cut]"
    head = limit - len(note)
    return f"{text[:head]}… [{len(text) - head:,} more characters cut]"


def _kept(text: str, shown: str, newlines: bool) -> int:
    """How many characters of ``text`` the escaped prefix ``shown`` shows in full."""
    kept = length = 0
    for ch in text:
        length += len(visible(ch, newlines=newlines))
        if length > len(shown):
            break
        kept += 1
    return kept


def for_terminal(text: str, *, newlines: bool = False, limit: int = TERMINAL_LIMIT) -> str:
    """A string for the terminal: every control and format character visible (line feeds kept only with
    ``newlines``: the boxed text of an error), cut to ``limit``. Print it as plain text, never as markup."""
    return visible_cut(text, limit, newlines=newlines)


def for_xml(text: str, *, limit: int = XML_LIMIT) -> str:
    """A string for an XML 1.0 attribute or element (ElementTree escapes ``<``, ``&`` and quotes): every
    character XML 1.0 forbids, and every control and format character, visible; cut to ``limit``."""
    return visible_cut(text, limit)


def for_csv(text: str, *, limit: int = CSV_LIMIT) -> str:
    """A gradebook cell: its first line cut to ``limit``, escapes visible, never a spreadsheet formula
    (a cell starting with ``=``, ``+``, ``-``, ``@``, tab or CR gets a leading ``'``, as OWASP advises)."""
    lines = str(text).strip().splitlines() or [""]
    first = lines[0].strip()
    shown = visible_cut(first, limit, newlines=False)
    if len(lines) > 1 and shown == visible(first, newlines=False):
        shown += " …"
    return spreadsheet_safe(shown)


def spreadsheet_safe(cell: str) -> str:
    """A CSV cell a spreadsheet shows as text: one starting like a formula gets a leading quote (OWASP);
    a lone ``-`` (the gradebook's "did not run") is no formula.

    >>> spreadsheet_safe("=1+1.py"), spreadsheet_safe("alice.py"), spreadsheet_safe("-")
    ("'=1+1.py", 'alice.py', '-')
    """
    return "'" + cell if cell.startswith(_FORMULA_STARTS) and cell != "-" else cell


def for_json(text: str) -> str:
    """A string for JSON: as it is (the JSON writer escapes what it must), only lone surrogates (a file
    name of bytes that are not UTF-8) written as visible escapes, so that the file is valid UTF-8."""
    return _SURROGATE.sub(lambda m: escape(m.group()), str(text))
