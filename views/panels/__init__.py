"""The panels of the window's tabs and docks: settings, steps, tables and their layout."""
