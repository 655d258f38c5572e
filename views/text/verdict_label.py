"""The verdict of a picked pixel: one sentence over its tables, saying what decided the pixel.

Both pipelines' panels show it above the evidence (the z-buffer's pixel history,
the ray tree); the sentence comes from :mod:`core.pixel_verdict`.  It keeps to
the lines its panel can spare (one unless told, :meth:`ElidedLabel.set_max_lines`),
so the tables below keep their rows at every text scale; a sentence longer than
that ends in "…" and is whole in the tooltip.
"""

from __future__ import annotations

from PySide6.QtCore import Qt

from core.pixel_verdict import PixelVerdict
from views.text.elided_label import ElidedLabel


class VerdictLabel(ElidedLabel):
    """"Why this pixel": the picked pixel's verdict in words, hidden while no pixel is picked.

    Attributes
    ----------
    shown : the verdict shown, or ``None``.
    """

    def __init__(self):
        super().__init__()
        self.shown: PixelVerdict | None = None
        self.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        font = self.font()
        font.setBold(True)
        self.setFont(font)
        self.hide()

    def share_room(self, table, need: int) -> None:
        """Take the lines ``table`` (the evidence under the verdict) can spare: the height the two share,
        less the ``need`` pixels of rows the table must keep in view."""
        shared = table.viewport().height() + (0 if self.isHidden() else self.height())
        self.set_max_lines((shared - need) // self.fontMetrics().lineSpacing())

    def show_verdict(self, verdict: PixelVerdict | None, detail: str = "") -> None:
        """Show ``verdict`` (``None``: nothing picked, the label hides), with ``detail`` in its tooltip."""
        self.shown = verdict
        if verdict is None:
            self.setText("")
            self.hide()
            return
        x, y = verdict.pixel
        self.setText(f"Why pixel ({x}, {y}): {verdict.sentence}")
        self.setToolTip(f"{self.text()}\n{detail}" if detail else self.text())
        self.show()
