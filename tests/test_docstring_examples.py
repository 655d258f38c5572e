"""The examples written in docstrings (``>>>``) hold: a formula's example is read by the student of
the code as a fact, so it is checked like one.  Each module of core, views and app whose source has
an example is imported and its examples run with :mod:`doctest`."""

import doctest
import importlib

import pytest
from checkout import ROOT

MODULES = sorted(
    ".".join(path.relative_to(ROOT).with_suffix("").parts)
    for package in ("core", "views", "app")
    for path in (ROOT / package).rglob("*.py")
    if ">>>" in path.read_text(encoding="utf-8"))


def test_the_examples_are_found():
    assert "core.object_order.zbuffer" in MODULES and "core.camera" in MODULES


@pytest.mark.parametrize("name", MODULES)
def test_a_modules_examples_give_what_they_say(name):
    results = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS,
                              report=False)
    assert results.attempted > 0, f"{name}: its '>>>' lines are not examples doctest can run"
    assert results.failed == 0, f"{name}: {results.failed} of {results.attempted} examples fail"
