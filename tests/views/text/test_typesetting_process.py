"""Formulas are typeset in a helper process, so that mathtext's Python never holds the window's
interpreter; the pictures are those this process would typeset."""

import numpy as np
import pytest

from views.text import typesetting_process

QUADRATIC = r"$t = \frac{-b \pm \sqrt{b^2 - 4ac}}{2a}$"


@pytest.fixture
def typeset_here(monkeypatch):
    """The formulas this process typesets itself, from now on."""
    here, ink = [], typesetting_process.ink
    monkeypatch.setattr(typesetting_process, "ink", lambda *args: (here.append(args[0]), ink(*args))[1])
    return here


def test_the_process_typesets_the_same_picture_this_process_would(typeset_here):
    args = (QUADRATIC, 14.0, "#1f77b4", 144.0)
    picture = typesetting_process.typeset(*args)
    assert typeset_here == []  # typeset elsewhere
    reference = typesetting_process.ink(*args)
    assert picture.dtype == np.uint8 and picture.shape == reference.shape and picture.shape[2] == 4
    assert np.array_equal(picture, reference)
    assert (picture[..., :3][picture[..., 3] > 0] == (31, 119, 180)).all()  # the colour asked for


def test_a_formula_that_is_not_mathtext_is_refused_with_where(typeset_here):
    with pytest.raises(ValueError, match=r"\\frac"):
        typesetting_process.typeset(r"$\frac{a$", 12.0, "#000000", 96.0)
    assert typeset_here == []
    assert typesetting_process.typeset("$a$", 12.0, "#000000", 96.0).shape[2] == 4  # and it goes on
