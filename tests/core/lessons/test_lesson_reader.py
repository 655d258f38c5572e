"""Lesson files are read as guardedly as scene files (issue 35): each hostile file below once
hung the window, filled its memory, printed a traceback or reached the 3D pane; each is now one
:class:`LessonFileError` naming the field or the file's problem."""

from __future__ import annotations

import copy
import json
import os

import pytest

from core import presets
from core.files import scene_file
from core.lessons.lesson_file import FILES, MAX_CHARS, MAX_NESTING, LessonFileError, load_lesson

SHIPPED = json.loads((FILES / "02_observer.json").read_text())


def _refusal(tmp_path, text: str) -> str:
    path = tmp_path / "lesson.json"
    path.write_text(text)
    with pytest.raises(LessonFileError) as caught:
        load_lesson(path)
    return str(caught.value)


def _with_step(**fields) -> str:
    lesson = copy.deepcopy(SHIPPED)
    lesson["steps"][0].update(fields)
    return json.dumps(lesson)


def test_an_integer_of_5000_digits_is_a_message_not_a_traceback(tmp_path):
    text = json.dumps(SHIPPED).replace('"version": 1', '"version": ' + "9" * 5000, 1)
    assert "a whole number with 5,000 digits" in _refusal(tmp_path, text)


@pytest.mark.parametrize("kind", ["fifo", "/dev/zero", "folder"])
def test_a_file_that_never_ends_is_refused_before_it_is_opened(tmp_path, kind):
    path = tmp_path / "lesson.json"
    if kind == "fifo":
        os.mkfifo(path)  # opening it to read would block until someone writes
    elif kind == "folder":
        path.mkdir()
    else:
        path = kind
    with pytest.raises(LessonFileError, match="cannot read the file"):
        load_lesson(path)


def test_a_file_over_the_size_limit_is_refused_unread(tmp_path):
    message = _refusal(tmp_path, _with_step(text="x" * 11_000_000))
    assert "too large: " in message and "the limit is 10,000,000" in message


def test_a_step_text_longer_than_a_page_is_refused(tmp_path):
    limit = MAX_CHARS["text"]
    assert "steps[0].text: too long: 20,001 characters (at most 20,000)" in _refusal(
        tmp_path, _with_step(text="x" * (limit + 1)))


def test_a_lesson_nested_past_its_own_limit_is_refused_at_the_top_level(tmp_path):
    def notes_nested(levels: int) -> str:
        notes = "words"
        for _ in range(levels):
            notes = [notes]
        return _with_step(notes=notes)

    # The lesson object, its steps list and the step object are 3 levels; the notes add the rest.
    refused = _refusal(tmp_path, notes_nested(MAX_NESTING - 3 + 1))
    assert refused == f"lesson file {tmp_path / 'lesson.json'}: top level: arrays and objects nested " \
                      f"more than {MAX_NESTING} levels deep"
    read = _refusal(tmp_path, notes_nested(MAX_NESTING - 3))  # at the limit: read, and notes is no string
    assert "steps[0].notes: expected a string, got [[[" in read and "levels deep" not in read


def test_200000_keys_one_repeated_are_answered_with_a_short_message(tmp_path):
    keys = "".join(f', "k{i}": {i}' for i in range(200_000))
    message = _refusal(tmp_path, json.dumps(SHIPPED)[:-1] + keys + ', "k7": 0}')
    lines = message.splitlines()
    assert "  k7: given more than once" in lines
    # Five unknown keys listed (k0 .. k4), the other 199,995 counted in one line.
    assert sum(": unknown field 'k" in line for line in lines) == 5
    assert "  top level: ... and 199,995 more unknown fields" in lines


def test_scene_files_with_200000_keys_one_repeated_get_the_same_short_message(tmp_path):
    path = tmp_path / "scene.json"
    path.write_text('{"objects": []' + "".join(f', "k{i}": {i}' for i in range(200_000)) + ', "k7": 0}')
    with pytest.raises(scene_file.SceneFileError) as caught:
        scene_file.load(path)
    assert "k7: given more than once" in caught.value.problems
    assert len(caught.value.problems) == 1 + 5 + 1  # the repeated key, five unknown ones, the count


@pytest.mark.parametrize("view, field, fragment", [
    ({"position": [1, 2, 3], "focal_point": [0, 0, 0], "up": [0, 0, 0]}, "up", "must not be (0, 0, 0)"),
    ({"position": [0, 5, 0], "focal_point": [0, 1, 0], "up": [0, -2, 0]}, "up", "along the line of sight"),
    ({"position": [1, 2, 3], "focal_point": [1, 2, 3], "up": [0, 1, 0]}, "focal_point", "must differ"),
])
def test_a_view_the_3d_pane_cannot_look_from_is_refused(tmp_path, view, field, fragment):
    message = _refusal(tmp_path, _with_step(view=view))
    assert f"steps[0].view.{field}: " in message and fragment in message


def test_a_camera_whose_up_is_zero_is_refused(tmp_path):
    assert "steps[0].camera.up: " in _refusal(tmp_path, _with_step(camera={"up": [0, 0, 0]}))


def test_more_steps_than_a_lesson_may_have_are_refused_in_one_line(tmp_path):
    lesson = copy.deepcopy(SHIPPED)
    lesson["steps"] = [lesson["steps"][0]] * 201
    message = _refusal(tmp_path, json.dumps(lesson))
    assert message.endswith("steps: at most 200 steps are allowed, got 201")


def test_every_shipped_lesson_still_loads():
    for path in sorted(FILES.glob("*.json")):
        assert load_lesson(path).steps


def test_a_scene_read_as_a_lesson_and_a_lesson_read_as_a_scene_are_each_said_to_be_what_they_are(tmp_path):
    # Read field by field, the shipped lesson opened as a scene gave seven problems ("unknown field
    # 'id'", ... and, last, the format); a scene opened as a lesson gave its missing id, title and
    # steps first.  One line says what the file is.
    scene = tmp_path / "scene.json"
    scene_file.save(presets.lecture_scene(), scene)
    with pytest.raises(LessonFileError) as as_lesson:
        load_lesson(scene)
    assert as_lesson.value.problems == [
        'format: this is a scene file ("render-explorer-scene"), not a lesson file']
    with pytest.raises(scene_file.SceneFileError) as as_scene:
        scene_file.load(FILES / "01_two_orders.json")
    assert as_scene.value.problems == [
        'format: this is a lesson file ("render-explorer-lesson"), not a scene file']
    assert str(as_scene.value).endswith("01_two_orders.json: format: this is a lesson file "
                                        '("render-explorer-lesson"), not a scene file')
