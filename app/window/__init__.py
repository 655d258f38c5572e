"""The main window's wiring: its model, tabs, layout, scene editor and session (its renders: app.renders)."""
