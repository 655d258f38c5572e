"""Benchmarks (``python -m app bench ...``): our figure beside the peer's from the same run, and the ratio."""
