"""``python -m app bench startup``: from a fresh process to the window shown and to its first image.

Each run starts a new Python process that does what ``python -m app`` does
(``app.cli.main([])``, the lecture scene), watched from outside the window's
code: an event filter on the application notes the first time the main
window (or any widget in it) is painted and the first time an image pane that holds an
image (``ImageView.rgb`` set) is painted, then quits.  Times are measured
from just before the process is started, so interpreter start-up and every
import are included.  One untimed run first warms numba's on-disk cache, the
bytecode cache and the operating system's file cache; then the median of ``--runs`` runs is
printed with the lowest and highest.

It needs a display (or ``xvfb-run -a``): the 3D pane gets no OpenGL context
on Qt's off-screen platform.  This is a benchmark, not a test; nothing here
is asserted.
"""

from __future__ import annotations

import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass

from app.usage import UsageError
from app.window.display_check import require_display

#: The watched process.  It prints ``shown <t> <numba>`` and ``image <t> <numba>``: the moment
#: (``time.time()``) and whether numba was imported by then (``True``/``False``).
DRIVER = """
import sys, time
from app import cli  # first, as in python -m app: modules imported after PySide6 cost more
from PySide6.QtCore import QEvent, QObject, QTimer
from PySide6.QtWidgets import QApplication, QMainWindow, QWidget

class Watch(QObject):
    shown = image = None

    def eventFilter(self, obj, event):
        kind = event.type()
        if (self.shown is None and kind == QEvent.Type.Paint and isinstance(obj, QWidget)
                and isinstance(obj.window(), QMainWindow)):
            self.shown = time.time()
            print("shown", self.shown, "numba" in sys.modules, flush=True)
        if (self.image is None and kind == QEvent.Type.Paint and type(obj).__name__ == "ImageView"
                and getattr(obj, "rgb", None) is not None and obj.isVisible()):
            self.image = time.time()
            print("image", self.image, "numba" in sys.modules, flush=True)
        if self.shown is not None and self.image is not None:
            QTimer.singleShot(0, QApplication.instance().quit)
        return False

app = QApplication(sys.argv[:1])
watch = Watch()
app.installEventFilter(watch)
QTimer.singleShot(TIMEOUT_MS, app.quit)
cli.main([])
"""


def add_arguments(parser) -> None:
    """Add the benchmark's options to ``parser`` (the ``bench startup`` subcommand)."""
    parser.add_argument("--runs", type=int, default=5, help="timed start-ups (default 5)")
    parser.add_argument("--cold", action="store_true",
                        help="also start as a second clone (a fresh copy of the code, the user's kernels "
                             "and formulas) and as a fresh machine (kernel and formula caches empty)")
    parser.add_argument("--timeout", type=float, default=120.0,
                        help="seconds to wait for one start-up (default 120)")


ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


@dataclass(frozen=True)
class Moment:
    """When a start-up reached a step, watched from outside the window's code."""

    seconds: float  # since just before the process was started
    numba_loaded: bool  # numba was imported by then


def watched_start(timeout_s: float, root: str = ROOT, env: dict | None = None) -> dict[str, Moment]:
    """Start the window as ``python -m app`` does, in a fresh process, and watch it (:data:`DRIVER`):
    the :class:`Moment` it was ``"shown"`` and the one its first ``"image"`` was.

    ``root``: the checkout that runs; ``env``: added to this process's environment (by default the
    configuration folder is a fresh one: no last session, every start shows the lecture scene).
    Raises :class:`UsageError` when the window shows no image within ``timeout_s`` seconds.
    """
    code = DRIVER.replace("TIMEOUT_MS", str(int(timeout_s * 1000)))
    with tempfile.TemporaryDirectory() as config:
        start = time.time()
        env = {**os.environ, "XDG_CONFIG_HOME": config, "PYTHONPATH": root, **(env or {})}
        out = subprocess.run([sys.executable, "-c", code], cwd=root, capture_output=True, text=True,
                             timeout=timeout_s + 30, env=env)
    stamps = {name: (t, numba) for name, t, numba in
              (line.split() for line in out.stdout.splitlines() if line.startswith(("shown", "image")))}
    if "shown" not in stamps or "image" not in stamps:
        tail = (out.stderr.strip().splitlines() or ["no output"])[-1]
        raise UsageError(f"bench startup: the window did not show an image within {timeout_s:g} s "
                         f"(exit status {out.returncode}: {tail})")
    return {name: Moment(float(t) - start, numba == "True") for name, (t, numba) in stamps.items()}


def _start_once(timeout_s: float, bytecode: str | None, root: str = ROOT, caches: dict | None = None
                ) -> tuple[float, float]:
    """Seconds from process start to the window shown and to the first image; ``bytecode``: the
    folder of the compiled modules (written by the warm-up run, even where the environment says
    PYTHONDONTWRITEBYTECODE: an installed program has its bytecode), or None for the usual
    ``__pycache__`` folders; ``root``: the checkout that runs; ``caches``: environment variables
    that point the caches elsewhere."""
    where = {"PYTHONPYCACHEPREFIX": bytecode} if bytecode is not None else {}
    moments = watched_start(timeout_s, root, {**where, "PYTHONDONTWRITEBYTECODE": "", **(caches or {})})
    return moments["shown"].seconds, moments["image"].seconds


def _start_fresh(timeout_s: float, kernels_too: bool) -> tuple[float, float]:
    """One start of a fresh copy of the code, without its bytecode (the installed packages keep
    theirs, as pip compiled it).  With ``kernels_too`` every cache is empty: kernels and formulas (a
    fresh machine); else both are the user's, as a second clone on the same machine finds them."""
    with tempfile.TemporaryDirectory() as fresh:
        for package in ("app", "core", "views"):
            shutil.copytree(os.path.join(ROOT, package), os.path.join(fresh, "checkout", package),
                            ignore=shutil.ignore_patterns("__pycache__"))
        if kernels_too:
            caches = {"XDG_CACHE_HOME": os.path.join(fresh, "cache"),
                      "NUMBA_CACHE_DIR": os.path.join(fresh, "kernels")}
        else:
            from core.compiling.kernel_cache import cache_root

            caches = {"NUMBA_CACHE_DIR": str(cache_root())}
        return _start_once(timeout_s, None, os.path.join(fresh, "checkout"), caches)


def run(args) -> int:
    """Run the benchmark and print its figures; returns the exit status."""
    if args.runs < 1:
        raise UsageError(f"--runs must be at least 1, got {args.runs}")
    require_display("bench startup")
    print(f"bench startup: python -m app on the lecture scene, fresh processes, numba and bytecode "
          f"caches warm; median of {args.runs} after one warm-up start [lowest .. highest]")
    shown, image = [], []
    with tempfile.TemporaryDirectory() as bytecode:
        _start_once(args.timeout, bytecode)
        for _ in range(args.runs):
            s, i = _start_once(args.timeout, bytecode)
            shown.append(s)
            image.append(i)
    for name, ts in (("window shown", shown), ("first image shown", image)):
        print(f"  {name:<18} {statistics.median(ts):6.2f} s [{min(ts):.2f} .. {max(ts):.2f}]")
    print(f"goals: window <= 1.5 s {'met' if statistics.median(shown) <= 1.5 else 'missed'}; "
          f"first image <= 2.5 s {'met' if statistics.median(image) <= 2.5 else 'missed'}")
    if args.cold:
        for title, kernels_too, goal in (
                ("a second clone: a fresh copy of the code, the user's kernels and formulas", False, 2.5),
                ("cold: a fresh machine, a fresh copy of the code, nothing compiled or cached", True, 10)):
            print(f"{title}; median of {args.runs} [lowest .. highest]")
            starts = [_start_fresh(args.timeout, kernels_too) for _ in range(args.runs)]
            for name, ts in (("window shown", [s for s, _ in starts]),
                             ("first image shown", [i for _, i in starts])):
                print(f"  {name:<18} {statistics.median(ts):6.2f} s [{min(ts):.2f} .. {max(ts):.2f}]")
            first = statistics.median(i for _, i in starts)
            print(f"goal: first image <= {goal:g} s {'met' if first <= goal else 'missed'}")
    return 0
