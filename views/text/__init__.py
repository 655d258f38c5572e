"""Text widgets: typeset formulas, worked math, one-line labels and the window's text scale."""
