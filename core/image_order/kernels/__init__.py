"""Compiled (numba) hot loops of the image-order pipeline."""
