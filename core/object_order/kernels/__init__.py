"""Compiled (numba) hot loops of the object-order pipeline."""
