"""Reading a program file as Python does: bytes, an optional UTF-8 BOM, a PEP 263 coding line.

A file that is not in the encoding it declares (most often a Windows-1250 file with Slovak or Czech
letters saved by an old editor) is a :class:`~plcsim.core.errors.ProgramFileError` naming the file, the line,
the byte and the encoding tried, with the fix.

>>> decode_program(b"\\xef\\xbb\\xbfdef OB1(t):\\n    pass\\n", "lab.py").splitlines()[0]
'def OB1(t):'
>>> decode_program("# coding: cp1250\\nX = 'ľ'\\n".encode("cp1250"), "lab.py").splitlines()[1]
"X = 'ľ'"
"""

from __future__ import annotations

import codecs
import io
import tokenize
from pathlib import Path

from plcsim.core.errors import ProgramFileError


def read_program_text(path: Path) -> str:
    """The text of the program file at ``path``."""
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise ProgramFileError(f"cannot read program {path}: {exc.strerror}") from None
    return decode_program(data, str(path))


def decode_program(data: bytes, filename: str) -> str:
    """Decode a program's bytes the way CPython decodes a source file."""
    try:
        encoding, _ = tokenize.detect_encoding(io.BytesIO(data).readline)
    except SyntaxError as exc:
        raise ProgramFileError(f"{filename}: {exc.msg}; save the file as UTF-8") from None
    try:
        text = data.decode(encoding)
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        column = exc.start - (data.rfind(b"\n", 0, exc.start) + 1) + 1
        raise ProgramFileError(
            f"{filename}, line {line}: byte 0x{data[exc.start]:02x} (column {column}) is not valid "
            f"{codecs.lookup(encoding).name}; the file was read as {encoding} and is probably in another "
            f"encoding (such as Windows-1250). Save it as UTF-8 (in the editor: Save with Encoding -> UTF-8)"
        ) from None
    return text.removeprefix("\ufeff")
