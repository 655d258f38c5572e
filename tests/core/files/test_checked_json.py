"""The checked-JSON reader that scene and lesson files share: every problem with its field path, one
error class whose message names the kind of file, nesting counted without recursion."""

from __future__ import annotations

import json

import pytest

from core.files.checked_json import (
    MAX_PROBLEMS_SHOWN,
    CheckedFileError,
    Reader,
    join,
    nesting_depth,
    read_json,
    show,
)
from core.files.scene_file import SceneFileError
from core.lessons.lesson_file import LessonFileError


def test_one_error_class_names_the_kind_of_file_and_lists_its_problems():
    assert str(SceneFileError(["radius: must be > 0, got -1"], "a.json")) == \
        "scene file a.json: radius: must be > 0, got -1"
    assert str(LessonFileError(["id: expected a string, got 3"])) == "lesson: id: expected a string, got 3"
    two = LessonFileError(["a: x", "b: y"], "l.json")
    assert str(two) == "lesson file l.json: 2 problems:\n  a: x\n  b: y"
    assert isinstance(two, CheckedFileError) and two.problems == ["a: x", "b: y"] and two.where == "l.json"


def test_a_long_list_of_problems_is_cut_to_a_count():
    problems = [f"objects[{k}]: bad" for k in range(MAX_PROBLEMS_SHOWN + 7)]
    lines = str(SceneFileError(problems)).splitlines()
    assert lines[0] == f"scene: {MAX_PROBLEMS_SHOWN + 7} problems:"
    assert len(lines) == 1 + MAX_PROBLEMS_SHOWN + 1 and lines[-1] == "  ... and 7 more problems"


def test_nesting_is_counted_exactly_up_to_one_past_the_limit():
    # {"a": [[{"b": 1}]]}: the object, two lists and the inner object are four levels.
    assert nesting_depth({"a": [[{"b": 1}]]}, 10) == 4
    assert nesting_depth(7, 10) == 0 and nesting_depth([], 10) == 1
    deep = []
    for _ in range(100_000):  # far past Python's recursion limit
        deep = [deep]
    assert nesting_depth(deep, 40) == 41


def test_paths_and_shown_values_read_as_the_file_wrote_them():
    assert join("", "camera") == "camera" and join("camera", "eye") == "camera.eye"
    assert join("objects[0]", "a\nb") == 'objects[0]."a\\nb"'  # a control character is not echoed
    assert show([1, 2.5, "x"]) == '[1, 2.5, "x"]'
    assert show("y" * 100) == json.dumps("y" * 100)[:56] + " ..."


def test_the_reader_collects_every_problem_instead_of_stopping():
    r = Reader()
    assert r.number(-1, "radius", gt=0) is None
    assert r.choice("zbufer", "panes[0]", ("object order", "zbuffer"), "pane") is None
    assert r.string("x" * 11, "title", max_chars=10) is None
    assert r.choices(["a", 3], "overlays", ("a",), "overlay") is None
    assert r.vector([1, 2, 3], "eye") == (1.0, 2.0, 3.0)
    r.header({"format": "other", "version": 2}, "render-explorer-scene", 1)
    assert r.problems == [
        "radius: must be > 0, got -1",
        "panes[0]: unknown pane 'zbufer' (did you mean 'zbuffer'?)",
        "title: too long: 11 characters (at most 10)",
        "overlays[1]: expected a string, got 3",
        'format: expected "render-explorer-scene", got "other"',
        "version: unsupported version 2; this program reads version 1",
    ]


def test_read_json_raises_the_error_class_it_is_given(tmp_path):
    path = tmp_path / "broken.json"
    path.write_text('{"a": 1,\n "b": }')
    with pytest.raises(LessonFileError) as caught:
        read_json(path, 1000, LessonFileError)
    assert str(caught.value) == f"lesson file {path}: line 2, column 7: invalid JSON: Expecting value"
    path.write_text('{"a": 1, "a": 2}')
    assert read_json(path, 1000).duplicates == ("a",)
