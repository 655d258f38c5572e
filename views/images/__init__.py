"""Image widgets: rendered images, depth and colour scales, and figures drawn off the GUI thread."""
