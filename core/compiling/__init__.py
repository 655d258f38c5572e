"""Compiling the kernels: ``jitable`` formulas, the shared kernel cache and the warm-up."""
