"""Checked JSON: read a JSON file guardedly and its values field by field, collecting every problem.

The scene files (:mod:`core.files.scene_file`) and the lesson files
(:mod:`core.lessons.lesson_file`) are JSON objects read the same way:

* :func:`read_json` parses a file as guardedly as a hostile one deserves: only a
  regular file under a size limit (never a FIFO or a device, see
  :mod:`core.files.safe_files`), UTF-8 (a BOM is skipped), whole numbers of at
  most :data:`MAX_DIGITS` digits, and objects that remember the keys their text
  gave more than once;
* a :class:`Reader` turns the parsed values into Python values, and instead of
  stopping at the first problem records each one with the path of its field
  (``objects[2].radius: must be > 0, got -1``);
* :class:`CheckedFileError` reports them all at once, one per line.

Each problem is ``"<field path>: <what is wrong>"``; a path joins keys with
``.`` and list positions with ``[k]`` (:func:`join`), and values are quoted as
the file wrote them, shortened (:func:`show`).  Limits keep a small file from
making a long message or a long run: at most :data:`MAX_LISTED` problems of one
kind per list or object, :data:`MAX_PROBLEMS_SHOWN` in a message, numbers
within ±:data:`MAX_MAGNITUDE`.
"""

from __future__ import annotations

import difflib
import json
import math
import numbers

import numpy as np

from core.files import safe_files

MAX_MAGNITUDE = 1e6  # of any number, so that squares and products stay finite
MAX_LISTED = 5  # problems of one kind listed per list or object; the rest are counted
MAX_DIGITS = 100  # of a whole number in the JSON text; any longer one is out of range anyway
MAX_PROBLEMS_SHOWN = 50  # in a message; the rest are counted


SCENE_FORMAT, LESSON_FORMAT = "render-explorer-scene", "render-explorer-lesson"
#: The program's kinds of JSON file by their ``format``, as a message names them.
FILE_KINDS = {SCENE_FORMAT: "a scene file", LESSON_FORMAT: "a lesson file"}


def other_kind(value, fmt: str) -> str | None:
    """The one problem of a file of another of the program's kinds (:data:`FILE_KINDS`) read as a
    ``fmt`` file, or None.  (Read field by field, a lesson opened as a scene gave seven problems,
    the one that said what it was last.)

    >>> other_kind({"format": LESSON_FORMAT, "steps": []}, SCENE_FORMAT)
    'format: this is a lesson file ("render-explorer-lesson"), not a scene file'
    >>> other_kind({"format": "render-explorer-scene"}, SCENE_FORMAT) is None
    True
    """
    got = value.get("format") if isinstance(value, dict) else None
    if isinstance(got, str) and got != fmt and got in FILE_KINDS:
        return f"format: this is {FILE_KINDS[got]} ({json.dumps(got)}), not {FILE_KINDS[fmt]}"
    return None


class CheckedFileError(ValueError):
    """A checked file (or its parsed JSON) that cannot be loaded.

    Each kind of file has its own subclass, which names the file in the
    message by :attr:`thing` (``"scene file x.json: ..."``).

    Attributes
    ----------
    problems : every problem found, each ``"<field path>: <what is wrong>"``.
    where : the file, if the data came from one.
    """

    #: What the file holds, as the message names it.
    thing = "data"

    def __init__(self, problems: list[str], where: str | None = None):
        self.problems = list(problems)
        self.where = where
        super().__init__(self.headed(f"{self.thing} file {where}" if where else self.thing))

    def headed(self, head: str) -> str:
        """The problems after ``head`` (what is wrong, say the file's name): ``"head: problem"``, or
        their number and then one a line."""
        if len(self.problems) == 1:
            return f"{head}: {self.problems[0]}"
        return f"{head}: {len(self.problems)} problems:\n{problem_lines(self.problems)}"


def problem_lines(problems: list[str]) -> str:
    """The problems one per line, indented; past :data:`MAX_PROBLEMS_SHOWN`, only their number."""
    lines = [f"  {p}" for p in problems[:MAX_PROBLEMS_SHOWN]]
    if len(problems) > MAX_PROBLEMS_SHOWN:
        lines.append(f"  ... and {len(problems) - MAX_PROBLEMS_SHOWN:,} more problems")
    return "\n".join(lines)


# --- values ------------------------------------------------------------------


def show(value) -> str:
    """A value as the file wrote it, shortened."""
    try:
        text = json.dumps(value)
    except (TypeError, ValueError, RecursionError):
        try:
            text = repr(value)
        except (ValueError, RecursionError):  # an int too long to print, or nested too deeply
            text = f"a {type(value).__name__} too large to show"
    return text if len(text) <= 60 else text[:56] + " ..."


def join(path: str, key: str) -> str:
    """The path of field ``key`` of the object at ``path`` (``""``: the top level)."""
    if not key.isprintable() or not key:  # control characters are not echoed to a terminal
        key = json.dumps(key)
    return f"{path}.{key}" if path else key


def is_number(v) -> bool:
    """A JSON number (true and false are not numbers)."""
    return isinstance(v, numbers.Real) and not isinstance(v, (bool, np.bool_))


def is_integer(v) -> bool:
    """A JSON whole number (true and false are not numbers)."""
    return isinstance(v, numbers.Integral) and not isinstance(v, (bool, np.bool_))


def finite(v) -> bool:
    """A number that is neither infinite nor NaN (an int too large for a float is not finite)."""
    try:
        return math.isfinite(v)
    except OverflowError:
        return False


def too_big(values) -> bool:
    """Some of ``values`` lies outside ±:data:`MAX_MAGNITUDE`."""
    return any(abs(v) > MAX_MAGNITUDE for v in values)


def nesting_depth(value, limit: int) -> int:
    """How deeply arrays and objects nest in ``value`` (counted up to ``limit + 1``, without recursion)."""
    deepest, stack = 0, [(value, 0)]
    while stack:
        v, depth = stack.pop()
        if isinstance(v, (dict, list)):
            depth += 1
            deepest = max(deepest, depth)
            if depth <= limit:
                stack.extend((c, depth) for c in (v.values() if isinstance(v, dict) else v))
    return deepest


# --- reading values, collecting problems ------------------------------------


class Reader:
    """Reads JSON values into Python values; every problem goes to ``problems``.

    Each method takes the value and the path of its field, and returns the
    Python value, or None (and a problem) when the value is not what the field
    needs.
    """

    def __init__(self):
        self.problems: list[str] = []

    def add(self, path: str, message: str) -> None:
        self.problems.append(f"{path}: {message}")

    def header(self, data: dict, fmt: str, version: int) -> None:
        """Report a top-level ``format`` other than ``fmt`` and a ``version`` other than ``version``."""
        if "format" in data and data["format"] != fmt:
            self.add("format", f"expected {json.dumps(fmt)}, got {show(data['format'])}")
        if "version" in data and (not is_integer(data["version"]) or data["version"] != version):
            self.add("version", f"unsupported version {show(data['version'])}; "
                                f"this program reads version {version}")

    def fields(self, value, path: str, known, required=()) -> dict | None:
        """``value`` as a dict, after reporting unknown, repeated and missing fields."""
        if not isinstance(value, dict):
            self.add(path or "top level", f"expected an object {{...}}, got {show(value)}")
            return None
        duplicates = getattr(value, "duplicates", ())
        self.capped_fields(path, [(key, "given more than once") for key in duplicates[:MAX_LISTED + 1]],
                           len(duplicates), "keys given more than once")
        suggested, unknown = set(), [key for key in value if key not in known]
        reported = []
        for key in unknown[:MAX_LISTED + 1]:  # a file may have 200,000 of them: a few say enough
            close = difflib.get_close_matches(str(key), known, n=1)
            hint = f"did you mean {close[0]!r}?" if close else f"known: {', '.join(known)}"
            reported.append((str(key), f"unknown field {key!r} ({hint})"))
            suggested.update(close)
        self.capped_fields(path, reported, len(unknown), "unknown fields")
        for key in required:
            if key not in value and key not in suggested:  # a typo is reported once
                self.add(join(path, key), "required field is missing")
        return value

    def number(self, v, path, *, gt=None, ge=None, le=None) -> float | None:
        if not is_number(v):
            self.add(path, f"expected a number, got {show(v)}")
        elif not finite(v):
            self.add(path, f"must be a finite number, got {show(v)}")
        elif too_big([v]):
            self.add(path, f"must be within ±{MAX_MAGNITUDE:,.0f}, got {show(v)}")
        elif gt is not None and not v > gt:
            self.add(path, f"must be > {gt}, got {show(v)}")
        elif ge is not None and le is not None and not ge <= v <= le:
            self.add(path, f"must be in [{ge}, {le}], got {show(v)}")
        elif ge is not None and not v >= ge:
            self.add(path, f"must be >= {ge}, got {show(v)}")
        else:
            return float(v)
        return None

    def integer(self, v, path) -> int | None:
        if not is_integer(v):
            self.add(path, f"expected a whole number, got {show(v)}")
        elif too_big([v]):
            self.add(path, f"must be within ±{MAX_MAGNITUDE:,.0f}, got {show(v)}")
        else:
            return int(v)
        return None

    def string(self, v, path, max_chars: int | None = None) -> str | None:
        """A string, of at most ``max_chars`` characters if given (a longer one is a problem)."""
        if not isinstance(v, str):
            self.add(path, f"expected a string, got {show(v)}")
        elif max_chars is not None and len(v) > max_chars:
            self.add(path, f"too long: {len(v):,} characters (at most {max_chars:,})")
        else:
            return v
        return None

    def choice(self, v, path: str, names, what: str) -> str | None:
        """One of ``names`` (a string); ``what`` names the kind in the message (``unknown pane 'x'``)."""
        if not isinstance(v, str):
            self.add(path, f"expected a string, got {show(v)}")
            return None
        if v not in names:
            close = difflib.get_close_matches(v, list(names), n=1)
            hint = f"did you mean {close[0]!r}?" if close else f"known: {', '.join(names)}"
            self.add(path, f"unknown {what} {v!r} ({hint})")
            return None
        return v

    def choices(self, v, path: str, names, what: str) -> tuple[str, ...] | None:
        """A list of :meth:`choice` items; None if it or any item is bad."""
        if not isinstance(v, list):
            self.add(path, f"expected a list [...], got {show(v)}")
            return None
        got = [self.choice(item, f"{path}[{k}]", names, what) for k, item in enumerate(v)]
        return None if None in got else tuple(got)

    def vector(self, v, path, n=3, scalar_ok=False) -> tuple[float, ...] | None:
        what = f"a number or {n} numbers" if scalar_ok else f"{n} numbers"
        if scalar_ok and is_number(v):
            v = [v] * n
        if not (isinstance(v, list) and len(v) == n and all(is_number(c) for c in v)):
            self.add(path, f"expected {what}, got {show(v)}")
        elif not all(finite(c) for c in v):
            self.add(path, f"expected {n} finite numbers, got {show(v)}")
        elif too_big(v):
            self.add(path, f"numbers must be within ±{MAX_MAGNITUDE:,.0f}, got {show(v)}")
        else:
            return tuple(float(c) for c in v)
        return None

    def color(self, v, path) -> tuple[float, ...] | None:
        rgb = self.vector(v, path)
        if rgb is not None and not all(0.0 <= c <= 1.0 for c in rgb):
            self.add(path, f"colour components must be in [0, 1], got {show(v)}")
            return None
        return rgb

    def listing(self, v, path) -> list:
        if isinstance(v, list):
            return v
        self.add(path, f"expected a list [...], got {show(v)}")
        return []

    def capped_fields(self, path: str, items: list[tuple[str, str]], total: int, what: str) -> None:
        """Report problems of fields ``path.key``, at most MAX_LISTED of the ``total``."""
        for key, message in items[:MAX_LISTED]:
            self.add(join(path, key), message)
        if total > MAX_LISTED:
            self.add(path or "top level", f"... and {total - MAX_LISTED:,} more {what}")

    def capped(self, path: str, items: list[tuple[int, str]]) -> None:
        """Report per-element problems ``path[k]``, at most MAX_LISTED of them."""
        for k, message in items[:MAX_LISTED]:
            self.add(f"{path}[{k}]", message)
        if len(items) > MAX_LISTED:
            self.add(path, f"... and {len(items) - MAX_LISTED} more like these")


# --- reading a file ----------------------------------------------------------


class _JsonObject(dict):
    """A parsed JSON object that remembers the keys its text gave more than once."""

    duplicates: tuple[str, ...] = ()


def _json_object(pairs: list[tuple[str, object]]) -> _JsonObject:
    d = _JsonObject(pairs)
    if len(d) < len(pairs):  # found in one pass: a file may have 200,000 keys
        seen, repeated = set(), {}
        for key, _ in pairs:
            if key in seen:
                repeated[key] = None
            seen.add(key)
        d.duplicates = tuple(repeated)
    return d


def _parse_int(text: str) -> int:
    if len(text.lstrip("-")) > MAX_DIGITS:
        raise ValueError(f"a whole number with {len(text.lstrip('-')):,} digits "
                         f"(numbers must be within ±{MAX_MAGNITUDE:,.0f})")
    return int(text)


def read_json(path, limit_bytes: int, error: type[CheckedFileError] = CheckedFileError):
    """The parsed JSON of the file ``path``, read guardedly.

    Only a regular file of at most ``limit_bytes`` is read (checked before it
    is opened, see :mod:`core.files.safe_files`), as UTF-8 (a BOM is skipped);
    whole numbers longer than :data:`MAX_DIGITS` digits are refused while
    parsing, and objects remember their repeated keys (``duplicates``) for
    :meth:`Reader.fields` to report.

    Raises
    ------
    error
        (a :class:`CheckedFileError`) With the one problem (the file's place in
        the text, where JSON is invalid) and ``where`` = the path.
    """
    problem = safe_files.input_file_problem(path, limit_bytes)
    if problem is not None:
        raise error([problem], str(path))
    try:
        text = safe_files.read_bytes_limited(path, limit_bytes).decode("utf-8-sig")
    except UnicodeDecodeError:
        raise error(["not a text file (UTF-8 JSON expected)"], str(path)) from None
    except OSError as exc:
        raise error([f"cannot read the file: {exc.strerror or exc}"], str(path)) from None
    try:
        return json.loads(text, object_pairs_hook=_json_object, parse_int=_parse_int)
    except json.JSONDecodeError as exc:
        problem = f"line {exc.lineno}, column {exc.colno}: invalid JSON: {exc.msg}"
        raise error([problem], str(path)) from None
    except RecursionError:
        raise error(["invalid JSON: nested too deeply"], str(path)) from None
    except ValueError as exc:  # from _parse_int
        raise error([f"invalid JSON: {exc}"], str(path)) from None
