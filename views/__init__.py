"""Qt and pyvista views: widgets that draw what core computes and the model holds."""
