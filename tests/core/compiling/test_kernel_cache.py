"""The shared kernel cache: one compile serves every copy of the same code, and never a changed formula.

Each test builds a tiny kernel package of its own (a formula file and a kernel file that
compiles it in, as the two halves' kernels do) and runs it in fresh processes, so that what
is compiled and what is loaded from the cache is numba's own count, not a guess.
"""

import json
import subprocess
import sys
from pathlib import Path

from checkout import ROOT

from core.compiling.kernel_cache import KEEP, group_folder_name, share_cache

FORMULA = """
from numba.extending import register_jitable

@register_jitable
def twice(x):
    return 2.0 * x
"""

KERNEL_INIT = """
from pathlib import Path
from core.compiling.kernel_cache import share_cache
HERE = Path(__file__).parent
share_cache(HERE, [HERE / "loop.py", HERE.parent / "formula.py"], "tiny")
"""

KERNEL = """
from numba import njit
from formula import twice

@njit(cache=True)
def apply(x):
    return twice(x) + 1.0
"""

RUN = f"""
import json, sys
sys.path[:0] = [sys.argv[1], {str(ROOT)!r}]
from kernels.loop import apply
value = apply(20.0)
stats = apply.stats
print(json.dumps({{"value": value, "hits": sum(stats.cache_hits.values()),
                  "misses": sum(stats.cache_misses.values()), "file": apply.py_func.__code__.co_filename}}))
"""


def checkout(folder: Path, formula: str = FORMULA) -> Path:
    """A copy of the tiny kernel package in ``folder``."""
    (folder / "kernels").mkdir(parents=True)
    (folder / "formula.py").write_text(formula)
    (folder / "kernels" / "__init__.py").write_text(KERNEL_INIT)
    (folder / "kernels" / "loop.py").write_text(KERNEL)
    return folder


def run(folder: Path, cache: Path) -> dict:
    env = {"NUMBA_CACHE_DIR": str(cache), "PATH": "/usr/bin:/bin"}
    done = subprocess.run([sys.executable, "-c", RUN, str(folder)], env=env, capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    return json.loads(done.stdout.splitlines()[-1])


def test_a_second_checkout_of_the_same_code_loads_the_kernels_the_first_compiled(tmp_path):
    cache = tmp_path / "cache"
    first = run(checkout(tmp_path / "clone1"), cache)
    second = run(checkout(tmp_path / "clone2"), cache)
    assert first["value"] == second["value"] == 41.0
    assert (first["misses"], first["hits"]) == (1, 0)  # compiled once...
    assert (second["misses"], second["hits"]) == (0, 1)  # ...and the copy elsewhere loads it
    assert "clone2" in second["file"]
    assert not list((tmp_path / "clone1").rglob("*.nbi"))  # nothing cached beside the sources


def test_a_changed_formula_is_never_served_from_the_old_kernel(tmp_path):
    cache = tmp_path / "cache"
    assert run(checkout(tmp_path / "old"), cache)["value"] == 41.0
    changed = run(checkout(tmp_path / "new", FORMULA.replace("2.0 * x", "3.0 * x")), cache)
    # The kernel's own file is the same, only the formula it compiles in changed: numba alone would
    # load the old machine code and answer 41.
    assert changed["value"] == 61.0
    assert changed["misses"] == 1
    assert len(list(cache.glob("tiny-*"))) == 2  # one folder per version of the sources


def test_the_group_folder_names_the_sources_not_where_they_are(tmp_path):
    a, b = checkout(tmp_path / "a"), checkout(tmp_path / "b")
    sources = [Path("kernels") / "loop.py", Path("formula.py")]
    name_a = group_folder_name("tiny", [a / s for s in sources])
    assert name_a == group_folder_name("tiny", [b / s for s in sources])
    (b / "formula.py").write_text(FORMULA + "\n# a comment changes the hash too\n")
    assert name_a != group_folder_name("tiny", [b / s for s in sources])
    assert name_a.startswith("tiny-") and "numba" in name_a


def test_only_the_newest_versions_of_a_group_are_kept(tmp_path, monkeypatch):
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "cache"))
    folders = []
    for k in range(KEEP + 2):
        v = checkout(tmp_path / f"v{k}", FORMULA.replace("2.0", f"{k + 2}.0"))
        folders.append(share_cache(v / "kernels", [v / "kernels" / "loop.py", v / "formula.py"], "tiny"))
    kept = set((tmp_path / "cache").glob("tiny-*"))
    assert kept == set(folders[-KEEP:])  # the newest, the one in use among them


def test_an_unwritable_cache_folder_still_renders_and_writes_nothing_beside_the_sources(tmp_path):
    blocker = tmp_path / "not-a-folder"
    blocker.write_text("a file where the cache folder would be")
    folder = checkout(tmp_path / "clone")
    result = run(folder, blocker / "cache")
    assert result["value"] == 41.0
    assert not list(folder.rglob("*.nbi")) and not list(folder.rglob("*.nbc"))
