"""A terminal that cannot show the lecture's notation gets it spelled out, not a traceback."""

import json
import os
import subprocess
import sys

import pytest
from checkout import ROOT

# The lecture's exercise: the segment from (2, 1, 2) to (10, 6, 6) against the sphere about (6, 4, 6)
# of radius 10. Its worked solution prints r², Δ, √ and ±.
SEGMENT = ["intersect", "sphere", "--origin", "2,1,2", "--end", "10,6,6", "--center", "6,4,6",
           "--radius", "10"]


def _app(args, encoding):
    env = {**os.environ, "PYTHONIOENCODING": encoding}
    return subprocess.run([sys.executable, "-m", "app", *args], cwd=ROOT, env=env, capture_output=True,
                          timeout=120)


@pytest.mark.parametrize("encoding", ["ascii", "latin-1"])
def test_the_worked_solution_reads_on_a_terminal_without_its_symbols(encoding):
    done = _app(SEGMENT, encoding)
    assert done.returncode == 0, done.stderr.decode(encoding, "replace")[-2000:]
    text = done.stdout.decode(encoding)  # every byte is the terminal's own
    assert "Traceback" not in done.stderr.decode(encoding)
    # b² - 4ac for the segment: d = (8, 5, 4), o - c = (-4, -3, -4): a = 105, b = 2(-32 - 15 - 16) = -126,
    # c = 16 + 9 + 16 - 100 = -59, so Δ = 126² + 4 * 105 * 59 = 15876 + 24780 = 40656.
    assert "Delta = b" in text and "= 40656" in text
    assert "sqrt Delta" in text
    if encoding == "ascii":
        assert "= r^2," in text and "(-b +/- sqrt Delta)" in text
    else:  # what Latin-1 has ("²", "±") stays as it is
        assert "= r²," in text and "(-b ± sqrt Delta)" in text


def test_json_answers_are_plain_ascii_anyway():
    done = _app([*SEGMENT, "--json"], "ascii")
    assert done.returncode == 0
    assert json.loads(done.stdout)  # one JSON object, whatever the terminal
