"""JSON parsed within the limits rollbench's own readers keep (problems/json_limits.hpp, docs/bad-input.md).

parse() refuses, before json.loads builds anything, text nested deeper than MAX_DEPTH levels (100 000 '[' would
exhaust Python's recursion in the parser or in any walk of the result), and while parsing NaN and Infinity (JSON
has neither; rollbench writes null for a value it did not measure) and numbers beyond a double's range (1e400, an
integer of 5000 digits). JsonError names the input as the caller shows it and the byte; nothing of the text is
quoted but a short, escaped excerpt of a number.
"""
import json
import math
import re

import numpy as np

# no rollbench file nests deeper than 6 levels
MAX_DEPTH = 64
EXCERPT = 40  # characters of a number quoted in a message
_NOT_A_MARK = bytes(c for c in range(256) if c not in b'"[]{}')
_BRACKETS = re.compile(rb'"[^"\\]*(?:\\.[^"\\]*)*"|[\[\]{}]')
# what may be a number beyond a double: an exponent of three digits or more, or 300 digits in a row (or text in a
# string that looks so), found on the text with digits and '.' as 'd', e and E as 'e' and all else but '+' blank
_NUMBER_SHAPES = bytes(ord("d") if chr(c) in "0123456789." else ord("e") if chr(c) in "eE" else c if c == ord("+")
                       else ord(" ") for c in range(256))
_MAYBE_HUGE = (b"deddd", b"de+ddd", b"d" * 300)


class JsonError(ValueError):
    """Text that is not JSON within the limits; the message names the input and what is wrong."""


def parse(text, shown="the input"):
    """The value of JSON text within the limits; shown names the input in messages ("'report.json'")."""
    data = text.encode("utf-8", "surrogatepass")
    at = too_deep_at(data)
    if at > 0:
        raise JsonError(f"{shown} nests deeper than {MAX_DEPTH} levels (at byte {at})")
    # each number checked only where one may be huge (a Python call per number halves the parser's speed)
    shapes = data.translate(_NUMBER_SHAPES)
    checked = {"parse_float": _double, "parse_int": _integer} if any(s in shapes for s in _MAYBE_HUGE) else {}
    try:
        return json.loads(text, parse_constant=_not_json, **checked)
    except json.JSONDecodeError as e:
        raise JsonError(f"{shown} is not JSON: {e}") from None
    except _OutOfRange as e:
        raise JsonError(f"{shown} holds {e}") from None


def too_deep_at(data):
    """The byte (counted from 1, as rollbench counts it) of the first [ or { outside strings nested deeper than
    MAX_DEPTH, or -1."""
    # only quotes and brackets kept (escaped backslashes and quotes dropped first): a bracket is outside the strings
    # where an even number of quotes precedes it; a few passes at C speed over the text
    marks = np.frombuffer(data.replace(b"\\\\", b"").replace(b'\\"', b"").translate(None, _NOT_A_MARK),
                          dtype=np.uint8)
    quotes = marks == ord('"')
    brackets = marks[~quotes & (np.cumsum(quotes) % 2 == 0)]
    if not brackets.size or np.cumsum(np.where((brackets == ord("[")) | (brackets == ord("{")), 1, -1)).max() \
            <= MAX_DEPTH:
        return -1
    depth = 0  # where: found again on the text as it is, bracket by bracket (only for the message)
    for m in _BRACKETS.finditer(data):
        if m.group() in (b"[", b"{"):
            depth += 1
            if depth > MAX_DEPTH:
                return m.start() + 1
        elif m.group() in (b"]", b"}"):
            depth -= 1
    return -1  # not JSON (a string never closed): the parser says so


class _OutOfRange(ValueError):
    pass


def _number_text(text):
    return text[:EXCERPT] + ("..." if len(text) > EXCERPT else "")


def _not_json(name):
    raise _OutOfRange(f"{name}, which is not JSON (rollbench writes null for a value it did not measure)")


def _double(text):
    value = float(text)
    if not math.isfinite(value):
        raise _OutOfRange(f"a number out of range ({_number_text(text)})")
    return value


def _integer(text):
    # beyond a double's range a number cannot be drawn or compared (and int() refuses 4300 digits and more)
    try:
        if len(text) > 320:
            raise OverflowError
        value = int(text)
        float(value)
    except OverflowError:
        raise _OutOfRange(f"a number out of range ({_number_text(text)})") from None
    return value
