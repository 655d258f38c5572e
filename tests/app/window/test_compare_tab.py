"""The Compare tab as a user works it: choose two outputs, read their difference, pick one pixel in all."""

import numpy as np
from PySide6.QtCore import QRect, Qt
from PySide6.QtWidgets import QLabel
from window_helpers import RENDER_TIMEOUT_MS

from core.compare import DIFFERENCE_UNITS, OUTPUTS
from views.panels.compare_panel import IMAGE_SHARE, PICK_HINT


def _compare(qtbot, window):
    window.show_tab("compare")
    qtbot.waitUntil(lambda: window.showing_full("compare"), timeout=RENDER_TIMEOUT_MS)
    return window.tab("compare").widget


def _choose(qtbot, window, panel, a: str, b: str) -> None:
    """Pick outputs A and B in the selectors and wait for their comparison."""
    for combo, key in zip(panel.selectors, (a, b), strict=True):
        combo.setCurrentIndex(combo.findData(key))
    qtbot.waitUntil(lambda: window.showing_full("compare")
                    and panel.boxes["b"].title() == f"B: {OUTPUTS[b]}"
                    and panel.boxes["a"].title() == f"A: {OUTPUTS[a]}", timeout=RENDER_TIMEOUT_MS)


def _click(qtbot, view, x: int, y: int) -> None:
    qtbot.mouseClick(view, Qt.MouseButton.LeftButton, pos=view.widget_pos(x, y).toPoint())


def _read(qtbot, panel, view: str, x: int, y: int) -> tuple[int, int]:
    """Click pixel (x, y) in image ``view``, wait until it is read in both outputs; the pixel picked.

    A pane smaller than the image shows fewer screen pixels than image pixels, so
    the click may land on a neighbour of (x, y).
    """
    _click(qtbot, panel.views[view], x, y)
    qtbot.waitUntil(lambda: panel.readout[0].rgb is not None, timeout=RENDER_TIMEOUT_MS)
    picked = panel.views[view].picked
    assert abs(picked[0] - x) <= 1 and abs(picked[1] - y) <= 1
    return picked


def _blue(rgb: np.ndarray) -> np.ndarray:
    """Where an image shows the cone, the lecture scene's one blue object: blue well above red.

    The cone's colour is (0.15, 0.55, 0.75); the cube is orange, the ground grey and the
    background (0.05, 0.07, 0.12) too dark to pass.
    """
    return rgb[..., 2] > 3 * rgb[..., 0] + 0.05


def test_a_pixel_picked_in_one_image_is_read_in_every_output(qtbot, window):
    panel = _compare(qtbot, window)
    a, b = panel.views["a"].rgb, panel.views["b"].rgb
    ys, xs = np.nonzero(_blue(a) & _blue(b))
    assert len(xs) > 100, "the cone is in view in both outputs"
    x, y = _read(qtbot, panel, "difference", int(xs[len(xs) // 2]), int(ys[len(ys) // 2]))
    assert _blue(a)[y, x] and _blue(b)[y, x]

    assert [view.picked for view in panel.views.values()] == [(x, y)] * 3
    np.testing.assert_allclose(panel.readout[0].rgb, a[y, x])
    np.testing.assert_allclose(panel.readout[1].rgb, b[y, x])
    np.testing.assert_allclose(panel.readout[2].rgb, np.abs(a[y, x] - b[y, x]))
    assert panel.readout[0].numbers.text() == " ".join(f"{c:.3f}" for c in a[y, x])
    assert panel.pixel_box.title() == f"Picked pixel ({x}, {y}), linear RGB"
    zbuffer, tracer = panel.readout[0].found.text(), panel.readout[1].found.text()
    assert "of cone is kept by the z-buffer at distance" in zbuffer and "fragment" in zbuffer
    assert tracer.startswith("The primary ray hits cone at t = ")
    why = panel.readout[2].found.text()  # flat against per-point shading, unless the colours agree here
    assert "Both show cone here; they differ by flat shading" in why or why.startswith("no difference")
    assert "colours from the last hits back to the first" in panel.readout[1].toolTip()


def test_a_pixel_where_both_see_the_background_says_so(qtbot, window):
    panel = _compare(qtbot, window)
    background = np.asarray(window.model.scene.background)
    a, b = panel.views["a"].rgb, panel.views["b"].rgb
    assert np.array_equal(a[0, 0], background) and np.array_equal(b[0, 0], background)
    _read(qtbot, panel, "a", 0, 0)
    assert "No polygon covers this pixel" in panel.readout[0].found.text()
    assert "misses everything" in panel.readout[1].found.text()
    assert panel.readout[2].rgb == (0.0, 0.0, 0.0)
    assert "no difference" in panel.readout[2].found.text()


def test_the_difference_of_an_output_with_itself_is_zero_everywhere(qtbot, window):
    panel = _compare(qtbot, window)
    _choose(qtbot, window, panel, "perspective", "perspective")
    assert np.array_equal(panel.views["a"].rgb, panel.views["b"].rgb)
    assert not panel.shown.comparison.difference.delta.any()
    shown = panel.views["difference"].rgb
    assert np.array_equal(shown, np.broadcast_to(shown[0, 0], shown.shape)), "one colour: the scale's zero"
    assert (panel.scale.low.text(), panel.scale.high.text()) == ("0", "0")
    assert "linear RGB" in panel.scale.units.text()
    _read(qtbot, panel, "b", 40, 200)
    assert panel.readout[2].rgb == (0.0, 0.0, 0.0)


def test_the_two_projections_differ_where_their_images_do_and_agree_on_shared_background(qtbot, window):
    panel = _compare(qtbot, window)
    _choose(qtbot, window, panel, "orthographic", "perspective")
    a, b = panel.views["a"].rgb, panel.views["b"].rgb
    background = np.asarray(window.model.scene.background)
    both_background = np.all(a == background, axis=2) & np.all(b == background, axis=2)
    differ = np.any(a != b, axis=2)
    assert both_background.any() and differ.any()
    delta = panel.shown.comparison.difference.delta
    np.testing.assert_array_equal(delta, np.abs(a - b))
    assert not delta[both_background].any()
    assert (delta.max(axis=2)[differ] > 0).all()
    assert panel.scale.high.text() == f"{np.abs(a - b).max():.3g}"
    zero = panel.views["difference"].rgb[both_background]
    assert np.array_equal(zero, np.broadcast_to(zero[0], zero.shape))
    assert np.any(panel.views["difference"].rgb[differ] != zero[0], axis=1).all()
    assert "parallel" in panel.explanation.text() and "converge" in panel.explanation.text()


def test_the_explanation_names_the_effects_only_the_tracer_computes(qtbot, window):
    panel = _compare(qtbot, window)
    assert panel.pair() == ("perspective", "raytrace")
    text = panel.explanation.text()
    assert "Only the tracer casts shadows" in text and "effects plan" in text
    assert "z-test" in text and "first hit" in text


def test_the_tracer_is_timed_with_the_acceleration_chosen_and_its_caption_says_which(qtbot, window):
    # The first lesson's "Where the work goes" traces with no acceleration ("each ray is tested
    # against every triangle of the scene") and points at Compare's times: Compare traced with the
    # BVH whatever was chosen, and its caption showed the BVH's time.  The lecture scene's meshes hold
    # 110 triangles: without acceleration each primary ray tests all of them.
    from dataclasses import replace

    panel = _compare(qtbot, window)
    assert panel.pair() == ("perspective", "raytrace")
    assert sum(len(o.triangles) for o in window.model.scene.objects) == 110
    for accel, words in (("none", "no acceleration"), ("bvh", "BVH")):
        window.model.set_trace_settings(replace(window.model.trace_settings, accel=accel))
        qtbot.waitUntil(lambda accel=accel: window.showing_full("compare") and not panel.shown.preview
                        and panel.shown.comparison.b.settings.accel == accel, timeout=RENDER_TIMEOUT_MS)
        stats = panel.shown.comparison.b.trace.stats
        assert f"rays, {words}, " in panel.captions["b"].text()
        primary = window.model.scene.camera.width * window.model.scene.camera.height
        if accel == "none":
            assert stats["accel"]["prim_tests"] >= 110 * primary
        else:
            assert stats["accel"]["prim_tests"] < 10 * primary


def test_changing_the_pair_renders_again_and_reads_the_picked_pixel_in_the_new_output(qtbot, window):
    panel = _compare(qtbot, window)
    tab = window.tab("compare")
    jobs = []
    job = tab.job
    tab.job = lambda scene, preview: jobs.append(preview) or job(scene, preview)
    before = panel.views["b"].rgb
    x, y = _read(qtbot, panel, "a", 100, 150)
    _choose(qtbot, window, panel, "perspective", "orthographic")
    assert jobs == [False]
    after = panel.views["b"].rgb
    assert after.shape == before.shape and np.any(after != before)
    qtbot.waitUntil(lambda: panel.readout[1].title.text() == "<b>B: orthographic z-buffer</b>",
                    timeout=RENDER_TIMEOUT_MS)
    np.testing.assert_allclose(panel.readout[1].rgb, after[y, x])
    assert panel.views["b"].picked == (x, y)


def test_moving_the_observer_shows_a_preview_then_reads_the_picked_pixel_again(qtbot, window):
    panel = _compare(qtbot, window)
    x, y = _read(qtbot, panel, "b", 160, 120)
    with qtbot.waitSignal(window.image_shown, timeout=RENDER_TIMEOUT_MS,
                          check_params_cb=lambda title, preview: title == "Compare" and preview):
        window.model.set_camera(window.model.camera.orbit(window.model.camera.yaw_deg + 10, 20.0))
    assert panel.views["a"].note == "preview"
    assert panel.readout[0].rgb is None
    qtbot.waitUntil(lambda: window.showing_full("compare") and panel.readout[0].rgb is not None,
                    timeout=RENDER_TIMEOUT_MS)
    np.testing.assert_allclose(panel.readout[0].rgb, panel.views["a"].rgb[y, x])


def test_presenting_at_x2_on_1920x1080_the_sentences_read_whole_and_the_images_keep_their_share(
        qtbot, window):
    # At x2 the "Why they differ" sentences showed three lines of eight and needed scrolling.
    window.setGeometry(window.screen().availableGeometry())
    window.presentation.set_presenting(True)
    window.presentation.set_scale(2.0)
    panel = _compare(qtbot, window)
    scroll = panel.explanation_scroll
    assert panel.explanation.text().startswith("<b>Why they differ</b>")
    assert panel.explanation.text().count("•") >= 2  # the lecture scene: several differences to read
    qtbot.waitUntil(lambda: scroll.verticalScrollBar().maximum() == 0
                    and panel.explanation.height() <= scroll.viewport().height(), timeout=5000)
    images, pixel, words = panel.split.sizes()
    assert images >= IMAGE_SHARE * (images + pixel + words) - 1  # the images keep their share
    assert pixel >= panel.pixel_box.minimumSizeHint().height()  # and the picked pixel its rows
    window.presentation.set_presenting(False)


def test_at_1280x720_presenting_the_captions_the_units_and_the_pick_hint_read_whole(qtbot, monkeypatch):
    # The images kept 35 % of the height whatever their captions needed: at text x1.5 the difference's
    # units (then "max(|ΔR|, |ΔG|, |ΔB|), linear RGB units (1 = black against white)") showed a line
    # and a half.
    # Under empty A and B rows, "Click a pixel in any image to read it in both outputs." showed a line
    # and a half too.
    from window_helpers import presenting_on_1280x720

    window = presenting_on_1280x720(qtbot, monkeypatch)
    panel = _compare(qtbot, window)
    labels = [panel.scale.units, *panel.captions.values()]
    qtbot.waitUntil(lambda: _hint_whole(panel), timeout=5000)

    def whole(label) -> bool:  # every word shown (the units not shortened), every line in the label
        return label.isVisible() and _shown(label).replace("\n", " ") == label.text() and _fits(label)

    qtbot.waitUntil(lambda: all(whole(label) for label in labels), timeout=5000)
    images, pixel, words = panel.split.sizes()
    assert images >= IMAGE_SHARE * (images + pixel + words) - 1  # and the images keep their share
    window.presentation.set_presenting(False)


def _hint_whole(panel) -> bool:
    """Whether the pick hint shows all its lines inside the picked pixel's box, unscrolled."""
    hint = next(label for label in panel.pixel_box.findChildren(QLabel) if label.text() == PICK_HINT)
    viewport = hint.parentWidget().parentWidget().parentWidget()  # row, rows, the scroll area's view
    bottom = hint.mapTo(viewport, hint.rect().bottomLeft()).y()
    return (hint.isVisible() and hint.height() >= hint.heightForWidth(hint.width())
            and bottom < viewport.height())


def test_at_1280x720_presenting_at_x2_the_pick_hint_is_the_first_line_of_its_box_and_reads_whole(
        qtbot, monkeypatch):
    # With nothing picked, the empty line for a pixel's numbers stayed above the hint: at x2 the box
    # had room for its two lines, but they began a line down and the second was cut in half.
    from window_helpers import presenting_on_1280x720

    window = presenting_on_1280x720(qtbot, monkeypatch, 2.0)
    panel = _compare(qtbot, window)
    hint = next(label for label in panel.pixel_box.findChildren(QLabel) if label.text() == PICK_HINT)
    viewport = hint.parentWidget().parentWidget().parentWidget()

    def read() -> None:
        top = hint.mapTo(viewport, hint.rect().topLeft()).y()
        assert top < hint.fontMetrics().height() / 2, top  # no blank line above it
        assert _hint_whole(panel)

    qtbot.waitUntil(read, timeout=5000)
    window.presentation.set_presenting(False)


def _shown(label) -> str:
    """The text ``label`` draws (a shortened label's ``text()`` is its whole text)."""
    return QLabel.text(label)


def _fits(label) -> bool:
    """Whether each line ``label`` draws lies whole inside it (none cut at its top or bottom)."""
    flags = Qt.TextFlag.TextWordWrap if label.wordWrap() else 0
    drawn = label.fontMetrics().boundingRect(QRect(0, 0, label.width(), 10_000), flags, _shown(label))
    return drawn.height() <= label.height()


def test_at_1280x720_presenting_at_x2_the_difference_units_read_whole_in_three_lines_at_most(
        qtbot, monkeypatch):
    # At x2 the units took four lines, more than the difference image above them, and the room
    # there was, so they were cut at their top and bottom ("max(|ΔR|, |" half hidden); then, held
    # to three lines, they ended in "units (1 = black …" with the rest in the tooltip.  Now they say
    # it in fewer words, all of it on the label.
    from window_helpers import presenting_on_1280x720

    window = presenting_on_1280x720(qtbot, monkeypatch, 2.0)
    panel = _compare(qtbot, window)
    units = panel.scale.units

    def read() -> None:
        shown = _shown(units)
        assert units.isVisible() and _fits(units), (shown, units.height())
        assert len(shown.splitlines()) <= 3, shown
        words = shown.replace("\n", " ")
        assert words == DIFFERENCE_UNITS, shown  # whole, not shortened with "…"
        assert words.startswith("max(|ΔR|, |ΔG|, |ΔB|)") and "linear RGB" in words and "white" in words

    qtbot.waitUntil(read, timeout=5000)
    window.presentation.set_presenting(False)


def test_at_1280x720_presenting_at_x2_a_picked_pixels_numbers_read_whole(qtbot, monkeypatch):
    # The picked pixel's box kept the height of the hint: A's and B's numbers showed a line and a
    # half ("linear RGB 0.032 0.119" and half of "0.162").  Now each output's title and numbers are
    # whole in the box, and what was found under them scrolls (the box is larger than the pane).
    from window_helpers import presenting_on_1280x720

    window = presenting_on_1280x720(qtbot, monkeypatch, 2.0)
    panel = _compare(qtbot, window)
    panel.pick(160, 150)
    qtbot.waitUntil(lambda: panel.readout[2].rgb is not None, timeout=RENDER_TIMEOUT_MS)
    labels = [label for row in panel.readout[:2] for label in (row.title, row.numbers)]
    viewport = labels[0].parentWidget().parentWidget().parentWidget()  # row, rows, the scroll area's view

    def whole() -> bool:
        for label in labels:
            bottom = label.mapTo(viewport, label.rect().bottomLeft()).y()
            assert label.isVisible() and label.height() >= label.heightForWidth(label.width()), label.text()
            assert label.heightForWidth(label.width()) < 1.5 * label.fontMetrics().lineSpacing()  # one line
            assert bottom < viewport.height(), label.text()
        return True

    qtbot.waitUntil(whole, timeout=5000)
    window.presentation.set_presenting(False)
