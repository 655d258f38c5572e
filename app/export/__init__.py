"""Export: pictures, sheets and animations of what the window shows, written atomically."""
