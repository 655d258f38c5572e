"""Zooming into a picture: which part of it a pane shows, and how large.

At zoom 1 a pane shows its picture whole, as large as fits with its aspect kept, centred.  At zoom
``z`` every pixel is ``z`` times as large and the pane shows part of the picture, around a *focus*
(a point of the picture, in pixels: x to the right, y down, pixel ``(i, j)`` the square
``[i, i + 1] x [j, j + 1]``) put at the pane's centre.  The focus is kept where the picture still
covers the pane along each side it overfills, so no zoom or pan shows more background than zoom 1.

Presenting at text x2 on a 1280 x 720 projector, the lecture scene's 320 x 240 pixels are drawn in
some 220 x 160 screen pixels: zoomed in, a triangle's pixels are squares the hall can count, with
their centres drawn (:data:`views.images.image_view.GRID_CELL_PX`).

>>> fitted_scale((200, 100), (40, 40))
2.5
>>> shown_rect((200, 100), (40, 40), 1.0, None)
(50.0, 0.0, 100.0, 100.0)
>>> shown_rect((200, 100), (40, 40), 4.0, (0.0, 0.0))  # the focus kept inside: the top-left corner
(0.0, 0.0, 400.0, 400.0)
"""

from __future__ import annotations

STEP = 1.25
"""How much one notch of the mouse wheel (or one + key) zooms in."""
MAX_CELL_PX = 96.0
"""Zoomed in until one pixel of the picture is this large on screen, and no further."""
FRAMED_SHARE = 0.6
"""Framed (:func:`framing`), a box of pixels takes this share of the room's width or height, the
rest shows what lies around it."""

Size = tuple[float, float]


def fitted_scale(room: Size, picture: Size) -> float:
    """Screen pixels per picture pixel at zoom 1: the picture whole in ``room``, its aspect kept."""
    return min(room[0] / picture[0], room[1] / picture[1])


def max_zoom(room: Size, picture: Size) -> float:
    """The largest zoom: one picture pixel :data:`MAX_CELL_PX` on screen (1 if it is larger at 1)."""
    return max(1.0, MAX_CELL_PX / fitted_scale(room, picture))


def kept_focus(room: Size, picture: Size, zoom: float,
               focus: tuple[float, float] | None) -> tuple[float, float]:
    """``focus`` moved the least so that the picture covers the room along each side it overfills
    at ``zoom`` (``None``: the picture's centre); along a side it does not fill, its centre."""
    scale = fitted_scale(room, picture) * zoom
    kept = []
    for k in range(2):
        half = room[k] / (2 * scale)  # half the room, in picture pixels
        if focus is None or 2 * half >= picture[k]:
            kept.append(picture[k] / 2)
        else:
            kept.append(min(max(focus[k], half), picture[k] - half))
    return kept[0], kept[1]


def shown_rect(room: Size, picture: Size, zoom: float,
               focus: tuple[float, float] | None) -> tuple[float, float, float, float]:
    """Where the whole picture is drawn, ``(x, y, width, height)`` relative to the room's top-left
    corner (parts of it may lie outside the room)."""
    scale = fitted_scale(room, picture) * zoom
    fx, fy = kept_focus(room, picture, zoom, focus)
    return room[0] / 2 - fx * scale, room[1] / 2 - fy * scale, picture[0] * scale, picture[1] * scale


def zoomed_about(room: Size, picture: Size, zoom: float, focus: tuple[float, float] | None,
                 factor: float, anchor: tuple[float, float]) -> tuple[float, tuple[float, float]]:
    """``(zoom, focus)`` after zooming by ``factor`` so that the picture's point under ``anchor`` (a
    position relative to the room's top-left corner) stays under it; the zoom kept within 1 and
    :func:`max_zoom`.

    >>> zoomed_about((100, 100), (10, 10), 1.0, None, 2.0, (25.0, 25.0))  # about pixel (2, 2)'s centre
    (2.0, (3.75, 3.75))
    """
    x, y, w, h = shown_rect(room, picture, zoom, focus)
    point = ((anchor[0] - x) / w * picture[0], (anchor[1] - y) / h * picture[1])
    new = min(max(zoom * factor, 1.0), max_zoom(room, picture))
    scale = fitted_scale(room, picture) * new
    wanted = (point[0] - (anchor[0] - room[0] / 2) / scale, point[1] - (anchor[1] - room[1] / 2) / scale)
    return new, kept_focus(room, picture, new, wanted)


def framing(room: Size, picture: Size,
            box: tuple[float, float, float, float]) -> tuple[float, tuple[float, float]]:
    """``(zoom, focus)`` that show ``box`` (``(x0, y0, x1, y1)``, picture pixels, corners) as large as
    takes :data:`FRAMED_SHARE` of the room along its longer side, about its centre; the zoom kept
    within 1 and :func:`max_zoom` (so a box as large as the picture shows it whole).

    >>> framing((100, 100), (100, 100), (40.0, 40.0, 50.0, 50.0))  # 10 pixels in 60 screen pixels
    (6.0, (45.0, 45.0))
    >>> framing((100, 100), (10, 10), (0.0, 0.0, 10.0, 10.0))  # all the picture's pixels: whole
    (1.0, (5.0, 5.0))
    """
    x0, y0, x1, y1 = box
    wanted = FRAMED_SHARE * min(room[0] / max(x1 - x0, 1.0), room[1] / max(y1 - y0, 1.0))
    new = min(max(wanted / fitted_scale(room, picture), 1.0), max_zoom(room, picture))
    return new, kept_focus(room, picture, new, ((x0 + x1) / 2, (y0 + y1) / 2))
