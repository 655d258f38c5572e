"""The pictures of a comparison: the difference image with its colour scale, and the whole comparison.

What ``python -m app export --what compare`` writes and what the Compare
tab's File → Export entries write, from one :class:`core.compare.Comparison`:

- :func:`difference_sheet`: the difference image at full resolution, its
  colour scale under it (0 on the left, the largest difference on the
  right) and a line naming its units;
- :func:`comparison_sheet`: outputs A and B beside the difference image
  with its scale, the units and the sentences that say why they differ.

Built on :mod:`app.export.picture_sheet`; imports neither Qt nor VTK.
"""

from __future__ import annotations

import numpy as np

from app.export.picture_sheet import Panel, compose
from core.compare import DIFFERENCE_UNITS, Comparison, Difference

BAR_ROWS = 10
"""Height in pixels of the colour scale under the difference image."""


def difference_panel(diff: Difference) -> Panel:
    """The difference image with its colour scale, as wide as the image, labelled at both ends."""
    bar = diff.colorbar(diff.colored.shape[1], BAR_ROWS)
    return Panel("Difference |A − B|", diff.colored, bar, ("0", f"{diff.scale:.3g}"))


def units_sentence(comparison: Comparison) -> str:
    """What the difference image's colours mean, for the outputs compared."""
    diff = comparison.difference
    what = f"{comparison.a.title} against {comparison.b.title}"
    if diff.scale == 0:
        return f"{what}: no difference at any pixel, so the whole image is the scale's left end (0)."
    return (f"{what}; colour: {DIFFERENCE_UNITS}, from 0 (left end of the scale) to {diff.scale:.3g}, "
            "the largest difference in this image (right end).")


def difference_sheet(comparison: Comparison) -> np.ndarray:
    """The difference image with its colour scale and units, (H, W, 3) linear RGB."""
    return compose([difference_panel(comparison.difference)], 1, [units_sentence(comparison)])


def comparison_sheet(comparison: Comparison) -> np.ndarray:
    """Outputs A and B, their difference with its scale, the units and why they differ (linear RGB)."""
    panels = [Panel(f"A: {comparison.a.title}", comparison.a.color),
              Panel(f"B: {comparison.b.title}", comparison.b.color),
              difference_panel(comparison.difference)]
    return compose(panels, 3, [units_sentence(comparison), *comparison.explanation])
