"""``python -m app hardcases``: run the hard-case lab and say whether every robust method holds.

Examples::

    python -m app hardcases
    python -m app hardcases --case shadow_acne
    python -m app hardcases --json

Without ``--json`` it prints one table line per case (its parameter, the
naive and robust headline result with the error of each, the tolerance and
whether the robust method passed).  With ``--json`` it prints one JSON object
per case, one per line, with ``null`` for numbers that do not exist (a NaN
error of the naive method is ``null`` and ``naive_result`` says why).  The
exit status is 0 only when every robust method passes, 1 otherwise, and 2 for
a bad argument.  Only :mod:`core` is imported, so it answers without Qt.
"""

from __future__ import annotations

import argparse
import json
import math

from app.usage import UsageError
from core import hard_cases
from core.hard_cases.result import CaseResult


def add_parser(sub) -> argparse.ArgumentParser:
    """Add the ``hardcases`` command to ``sub``."""
    parser = sub.add_parser(
        "hardcases",
        help="put textbook methods beside the robust ones on numerically hard cases",
        description="Run the hard-case lab: each case's naive and robust error against an exact "
                    "reference. Exit status 0 only when every robust method passes.",
        epilog="Cases: " + ", ".join(hard_cases.CASES),
    )
    parser.add_argument("--case", metavar="NAME", help="run only this case")
    parser.add_argument("--json", action="store_true", help="print one JSON object per case")
    parser.set_defaults(run=run)
    return parser


def _number(x):
    """A JSON number, or ``None`` for NaN/inf and missing values."""
    if x is None or isinstance(x, str):
        return x
    x = float(x)
    return x if math.isfinite(x) else None


def _text(x) -> str:
    if x is None:
        return "-"
    if isinstance(x, str):
        return x
    return f"{x:.6g}"


def as_json(r: CaseResult) -> dict:
    """The result as a JSON-ready dict (no NaN: ``null`` instead)."""
    headline = r.rows[0]
    return {
        "case": r.name,
        "title": r.title,
        "parameter": None if r.parameter is None else {"name": r.parameter.name, "value": r.parameter.value},
        "naive_method": r.naive_method,
        "robust_method": r.robust_method,
        "reference_method": r.reference_method,
        "naive_result": _text(headline.naive),
        "robust_result": _text(headline.robust),
        "exact_result": _text(headline.exact),
        "naive_error": _number(r.naive_error),
        "robust_error": _number(r.robust_error),
        "error_unit": r.error_unit,
        "tolerance": r.tolerance,
        "tolerance_reason": r.tolerance_reason,
        "passed": r.passed,
        "rows": [{"label": row.label, "naive": _number(row.naive), "robust": _number(row.robust),
                  "exact": _number(row.exact)} for row in r.rows],
    }


COLUMNS = (("case", 16), ("parameter", 20), ("naive result", 22), ("naive error", 12),
           ("robust result", 22), ("robust error", 12), ("tolerance", 9), ("unit", 30), ("robust", 6))


def _cell(text: str, width: int) -> str:
    return text if len(text) <= width else text[:width - 1] + "…"


def table_line(r: CaseResult) -> str:
    """One line of the table for result ``r``."""
    headline = r.rows[0]
    parameter = "-" if r.parameter is None else f"{r.parameter.name}={r.parameter.value:g}"
    cells = (r.name, parameter, _text(headline.naive), _text(r.naive_error), _text(headline.robust),
             _text(r.robust_error), f"{r.tolerance:.3g}", r.error_unit, "pass" if r.passed else "FAIL")
    return "  ".join(_cell(c, w).ljust(w) for c, (_, w) in zip(cells, COLUMNS, strict=True)).rstrip()


def run(args) -> int:
    if args.case is not None and args.case not in hard_cases.CASES:
        raise UsageError(f"--case: no hard case {args.case!r}; choose one of {', '.join(hard_cases.CASES)}")
    names = [args.case] if args.case is not None else list(hard_cases.CASES)
    results = []
    if not args.json:
        print("  ".join(name.ljust(w) for name, w in COLUMNS).rstrip())
    for name in names:
        r = hard_cases.run_case(name)
        results.append(r)
        print(json.dumps(as_json(r), ensure_ascii=False, allow_nan=False) if args.json else table_line(r),
              flush=True)
    if not args.json:
        failed = [r.name for r in results if not r.passed]
        print(f"{len(results) - len(failed)} of {len(results)} robust methods pass"
              + (f"; failing: {', '.join(failed)}" if failed else ""))
    return 0 if all(r.passed for r in results) else 1
