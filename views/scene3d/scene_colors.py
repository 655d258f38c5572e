"""Colours of the observer's parts in the 3D pane, shared by the pane and its overlays (no VTK needed)."""

FRUSTUM_COLOR = "#ffd34d"
"""The viewing pyramid cut by the near and far planes."""
SCREEN_COLOR = "#6fd0ff"
"""The screen rectangle on the near plane."""
