"""The main window's wiring: its model, tabs, workers, layout, scene editor and session."""
