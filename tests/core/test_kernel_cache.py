"""The stale-cache guard drops a half's cached kernels exactly when one of its sources changed."""

from core.kernel_cache import drop_stale_cache


def test_cached_kernels_go_when_a_source_changes_and_stay_otherwise(tmp_path):
    kernels = tmp_path / "kernels"
    (kernels / "sub").mkdir(parents=True)
    (kernels / "loop.py").write_text("x = 1\n")
    (kernels / "sub" / "simd.py").write_text("y = 2\n")
    formula = tmp_path / "formula.py"
    formula.write_text("def f(): return 1\n")
    sources = [kernels / "loop.py", kernels / "sub" / "simd.py", formula]

    def cache_file(folder):
        path = folder / "__pycache__" / "loop.f-1.py311.nbi"
        path.parent.mkdir(exist_ok=True)
        path.write_bytes(b"machine code")
        return path

    assert drop_stale_cache(kernels, sources, "t") is False  # nothing cached yet: nothing to drop
    cached = [cache_file(kernels), cache_file(kernels / "sub")]
    assert drop_stale_cache(kernels, sources, "t") is False and all(p.exists() for p in cached)
    formula.write_text("def f(): return 2\n")  # the formula compiled into the kernels changed
    assert drop_stale_cache(kernels, sources, "t") is True
    assert not any(p.exists() for p in cached)
