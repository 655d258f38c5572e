"""The 3D pane: the scene, the observer and its viewing pyramid, drawn with pyvista."""
