"""What a terminal that cannot show a character gets instead: the worked math still reads.

The command line's answers use the lecture's notation (``r²``, ``Δ``, ``√``, ``α``, ``→``).  Where
the terminal's encoding has no such character (an ASCII or Latin-1 locale, or
``PYTHONIOENCODING=ascii``), Python's ``print`` raised ``UnicodeEncodeError``: the command
printed part of its answer and ended with a traceback.  :func:`spell_out_what_the_terminal_cannot_show` makes
standard output and standard error write such a character in plain letters instead
(:data:`SPELLED`: ``r^2``, ``Delta``, ``sqrt``, ``alpha``, ``->``), and ``?`` for any other.
Files are not affected: every file the program writes names its encoding (UTF-8).

>>> "Δ = b² - 4ac ≥ 0".encode("ascii", errors=ERRORS)
b'Delta = b^2 - 4ac >= 0'
"""

from __future__ import annotations

import codecs
import sys

#: The plain spelling of each character of the lecture's notation the program prints.
SPELLED = {
    "²": "^2", "³": "^3", "Δ": "Delta", "θ": "theta", "α": "alpha", "β": "beta", "γ": "gamma",
    "ε": "eps", "…": "...", "→": "->", "·": "*", "×": "x", "±": "+/-", "∓": "-/+", "—": "--",
    "–": "-", "−": "-", "√": "sqrt ", "′": "'", "°": " deg", "“": '"', "”": '"', "≈": "~",
    "≤": "<=", "≥": ">=", "≠": "!=", "∞": "inf", "ö": "o",
}
#: The name of the codec error handler that spells them out.
ERRORS = "render-explorer-spelled"


def _spelled(error: UnicodeEncodeError) -> tuple[str, int]:
    text = error.object[error.start:error.end]
    return "".join(SPELLED.get(ch, "?") for ch in text), error.end


codecs.register_error(ERRORS, _spelled)


def spell_out_what_the_terminal_cannot_show() -> None:
    """Make ``sys.stdout`` and ``sys.stderr`` spell out what their encoding cannot write (process-wide)."""
    for stream in (sys.stdout, sys.stderr):
        if stream is not None and hasattr(stream, "reconfigure"):
            stream.reconfigure(errors=ERRORS)
