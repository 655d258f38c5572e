"""What the Compare tab offers File → Export: its two outputs, their difference, the whole comparison.

Each picture is made from the comparison on screen, at the observer's image
size: outputs A and B pixel for pixel, the difference image with its colour
scale and units, and all three with the sentences on why they differ as one
picture, the sheet ``python -m app export --what compare`` writes
(:mod:`app.export.comparison_sheet`).  A preview, or nothing rendered yet, has
nothing to export; the entries say so.
"""

from __future__ import annotations

from app.export.comparison_sheet import comparison_sheet, difference_sheet
from app.export.pane_pictures import PanePicture
from views.panels.compare_panel import ComparisonImages

NOTHING_YET = "Nothing shown yet: show the tab and let it render"
PREVIEW = "The panes show a “preview” image: wait for the full render"


def comparison_pictures(tab: str, shown: ComparisonImages | None) -> list[PanePicture]:
    """The pictures of ``shown`` (the comparison on the tab titled ``tab``), in menu order."""
    c = None if shown is None else shown.comparison
    names = ["Output A", "Output B", "Difference with its colour scale",
             "The whole comparison as one picture"]
    if c is None or shown.preview:
        why = NOTHING_YET if c is None else PREVIEW
        return [PanePicture(tab, name, None, why) for name in names]
    makes = [lambda: c.a.color, lambda: c.b.color, lambda: difference_sheet(c), lambda: comparison_sheet(c)]
    names[:2] = [f"Output A: {c.a.title}", f"Output B: {c.b.title}"]
    return [PanePicture(tab, name, make) for name, make in zip(names, makes, strict=True)]
