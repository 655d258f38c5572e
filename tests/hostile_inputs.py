"""Hypothesis strategies for hostile scene files, mesh files and lesson files (issues 11 and 35).

Used by ``tests/app/commands/test_fuzz_inputs.py`` (a few diverse examples) and by the
larger one-off campaigns whose figures the issues' notes give.  Every strategy
draws a :class:`Case`: the files to write into an empty folder and the scene
(or lesson) file to read.
"""

from __future__ import annotations

import json
import os
import re
import signal
import struct
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from checkout import ROOT
from hypothesis import strategies as st

#: After the command's and the file's prefix, a refusal starts with what is wrong: a field
#: path (``objects[2].radius``), an option (``--width``), a place in the text or a
#: file-level reason.
_PREFIX = re.compile(r"^python -m app( \w+)?: error: (scene file .+?: )?(\d+ problems:\s+)?")
_NAMED = re.compile(
    r"((top level|format|version|camera|background|lights|objects)([.\[][^\n]*?)?: "
    r"|[^\n]*?: unknown field |--[a-z-]+: |line \d+, column \d+: |invalid JSON: "
    r"|file not found$|cannot read the file: |too large: |not a text file"
    r"|\d+ × \d+ \w+ of \d+ objects needs about)"
)


def names_a_field(stderr: str) -> bool:
    """Whether a refusal says which field, option or file is wrong."""
    return bool(_NAMED.match(_PREFIX.sub("", stderr.strip(), count=1)))


@dataclass
class Case:
    """Files to write (name -> bytes) and which one is the scene; ``kind`` names the class."""

    kind: str
    files: dict = field(default_factory=dict)
    scene: str = "scene.json"
    special: str | None = None  # "fifo" makes the scene path a FIFO


# --- JSON values -------------------------------------------------------------------

NUMBERS = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.integers(-10**7, 10**7),
    st.sampled_from([0, -1, 1, 1e-300, 5e-324, 1e300, 1e6, 1e6 + 1, 2**63, -(2**63), 0.5, 16385]),
)
ANY_JSON = st.recursive(
    st.one_of(st.none(), st.booleans(), NUMBERS, st.text(max_size=8)),
    lambda inner: st.one_of(st.lists(inner, max_size=4),
                            st.dictionaries(st.text(max_size=6), inner, max_size=3)),
    max_leaves=12,
)


def vec(elements=NUMBERS):
    return st.lists(elements, min_size=3, max_size=3)


SANE = st.floats(-10, 10, allow_nan=False)
POSITIVE = st.floats(0.01, 5, allow_nan=False)


@st.composite
def maybe(draw, good, bad=ANY_JSON, p_bad=0.04):
    """Mostly a good value, sometimes anything at all."""
    return draw(bad) if draw(st.floats(0, 1)) < p_bad else draw(good)


@st.composite
def camera(draw):
    d = {
        "eye": draw(maybe(vec(SANE), vec())),
        "target": draw(maybe(vec(SANE), vec())),
        "up": draw(maybe(st.just([0, 1, 0]), vec())),
        "fov_y_deg": draw(maybe(st.floats(1, 120), NUMBERS)),
        "near": draw(maybe(st.floats(0.01, 1), NUMBERS)),
        "far": draw(maybe(st.floats(10, 100), NUMBERS)),
        "projection": draw(maybe(st.sampled_from(["perspective", "orthographic"]))),
        "ortho_height": draw(maybe(st.floats(0.1, 20), NUMBERS)),
        "width": draw(maybe(st.integers(1, 64), st.sampled_from([0, 16384, 16385, 10**30]))),
        "height": draw(maybe(st.integers(1, 48), st.sampled_from([0, 16384, -5]))),
    }
    keys = draw(st.lists(st.sampled_from(sorted(d)), unique=True, max_size=len(d)))
    return {k: d[k] for k in keys}


@st.composite
def scene_object(draw, mesh_names=()):
    kind = draw(st.sampled_from(["sphere", "box", "cone", "uv_sphere", "quad", "pyramid",
                                 "notched_prism", "mesh", "mesh_file", "nonsense"]))
    o = {"type": kind}
    if kind == "sphere":
        o.update(center=draw(maybe(vec(SANE))), radius=draw(maybe(POSITIVE, NUMBERS)))
    elif kind in ("box", "quad"):
        o.update(center=draw(maybe(vec(SANE))), size=draw(maybe(POSITIVE, NUMBERS)))
    elif kind in ("cone", "uv_sphere"):
        o.update(base_center=draw(maybe(vec(SANE))), radius=draw(maybe(POSITIVE)),
                 height=draw(maybe(POSITIVE)), segments=draw(maybe(st.integers(3, 40),
                                                                   st.integers(-5, 2000))))
        if kind == "uv_sphere":
            o["center"] = o.pop("base_center")
            del o["height"]
            o["rings"] = draw(maybe(st.integers(2, 30), st.sampled_from([1, 1000, 1001])))
    elif kind == "pyramid":
        o.update(base_center=draw(maybe(vec(SANE))), base_size=draw(maybe(POSITIVE)),
                 height=draw(maybe(POSITIVE)))
    elif kind == "notched_prism":
        o.update(base_center=draw(maybe(vec(SANE))), size=draw(maybe(POSITIVE)),
                 notch=draw(maybe(POSITIVE)))
    elif kind == "mesh":
        n = draw(st.integers(0, 6))
        o.update(vertices=draw(st.lists(maybe(vec(SANE)), min_size=n, max_size=n)),
                 triangles=draw(st.lists(st.lists(maybe(st.integers(-1, n)), min_size=3,
                                                  max_size=3), max_size=6)))
    elif kind == "mesh_file":
        names = [*mesh_names, "missing.obj", "/dev/zero.ply", ".", "x.fbx", ""]
        o["path"] = draw(maybe(st.sampled_from(names)))
    if draw(st.booleans()):
        o["material"] = draw(maybe(st.fixed_dictionaries(
            {}, optional={"color": vec(st.floats(0, 1)), "opacity": st.floats(0, 1),
                          "ior": st.floats(1, 3), "shininess": NUMBERS})))
    if draw(st.floats(0, 1)) < 0.1:
        o[draw(st.text(min_size=1, max_size=8))] = draw(ANY_JSON)  # an unknown field or a typo
    return o


@st.composite
def scene_dict(draw, mesh_names=()):
    d = {}
    if draw(st.booleans()):
        d["camera"] = draw(maybe(camera()))
    if draw(st.booleans()):
        d["lights"] = draw(maybe(st.lists(st.fixed_dictionaries(
            {"position": maybe(vec(SANE))}, optional={"intensity": NUMBERS}), max_size=3)))
    d["objects"] = draw(st.lists(scene_object(mesh_names), max_size=4))
    if draw(st.floats(0, 1)) < 0.1:
        d[draw(st.sampled_from(["format", "version", "background", "extra"]))] = draw(ANY_JSON)
    return d


@st.composite
def scene_text(draw, d):
    """The JSON text of ``d``, sometimes damaged the ways hostile files are."""
    text = json.dumps(d, allow_nan=True)
    how = draw(st.sampled_from(["as is"] * 6 + ["truncated", "deep", "huge int", "bom",
                                                "garbage", "duplicate"]))
    if how == "truncated":
        text = text[: draw(st.integers(0, len(text)))]
    elif how == "deep":
        depth = draw(st.sampled_from([40, 900, 990, 5000, 100_000]))
        text = text[:-1] + (', "background": ' if len(d) else '"background": ') + \
            "[" * depth + "]" * depth + "}"
    elif how == "huge int":
        text = text.replace("{", '{"version": ' + "9" * draw(st.integers(4290, 4400)) + ", ", 1)
    elif how == "duplicate":
        text = text.replace("{", '{"objects": [], ', 1)
    data = text.encode("utf-8", errors="surrogatepass")
    if how == "bom":
        data = b"\xef\xbb\xbf" + data
    elif how == "garbage":
        at = draw(st.integers(0, len(data)))
        data = data[:at] + draw(st.binary(min_size=1, max_size=8)) + data[at:]
    return how, data


@st.composite
def scene_cases(draw):
    """Class "scene": a generated scene file (no mesh files of its own)."""
    how, data = draw(scene_text(draw(scene_dict())))
    return Case(f"scene ({how})", {"scene.json": data})


# --- mesh files ----------------------------------------------------------------------

@st.composite
def mesh_bytes(draw):
    """A small mesh file in one of five encodings, often lying about itself."""
    fmt = draw(st.sampled_from(["obj", "stl-ascii", "stl-binary", "ply-ascii", "ply-binary"]))
    n = draw(st.integers(0, 8))
    vertices = draw(st.lists(st.lists(st.floats(-5, 5, width=32), min_size=3, max_size=3),
                             min_size=n, max_size=n))
    faces = draw(st.lists(st.lists(st.integers(-2, n + 2), min_size=3, max_size=5), max_size=6))
    lie = draw(st.sampled_from([0] * 4 + [-1, 1, 3, 2**31, 2_000_000_000, 10**12]))
    if fmt == "obj":
        uv = draw(st.booleans())
        lines = [f"v {x} {y} {z}" for x, y, z in vertices]
        lines += ["f " + " ".join(f"{i + 1}/{i + 7}" if uv else str(i + 1) for i in f) for f in faces]
        data = ("\n".join(lines) + "\n").encode()
    elif fmt == "stl-ascii":
        tris = [vertices[i:i + 3] for i in range(0, len(vertices) - 2, 3)]
        body = "".join("facet normal 0 0 1\nouter loop\n" + "".join(
            f"vertex {x} {y} {z}\n" for x, y, z in t) + "endloop\nendfacet\n" for t in tris)
        data = f"solid x\n{body}endsolid x\n".encode()
    elif fmt == "stl-binary":
        tris = [vertices[i:i + 3] for i in range(0, len(vertices) - 2, 3)]
        data = b"h" * 80 + struct.pack("<I", max(0, len(tris) + lie) % 2**32)
        data += b"".join(struct.pack("<12fH", 0, 0, 1, *[c for v in t for c in v], 0) for t in tris)
    else:
        binary = fmt == "ply-binary"
        header = ("ply\nformat " + ("binary_little_endian" if binary else "ascii") + " 1.0\n"
                  f"element vertex {max(0, n + lie)}\nproperty float x\nproperty float y\n"
                  f"property float z\nelement face {len(faces)}\n"
                  "property list uchar int vertex_indices\nend_header\n")
        if binary:
            body = b"".join(struct.pack("<3f", *v) for v in vertices)
            body += b"".join(struct.pack(f"<B{len(f)}i", len(f), *f) for f in faces)
        else:
            body = "".join(f"{x} {y} {z}\n" for x, y, z in vertices).encode()
            body += "".join(f"{len(f)} " + " ".join(map(str, f)) + "\n" for f in faces).encode()
        data = header.encode() + body
    damage = draw(st.sampled_from(["none"] * 4 + ["truncate", "flip", "bom", "empty"]))
    if damage == "truncate" and data:
        data = data[: draw(st.integers(0, len(data) - 1))]
    elif damage == "flip" and data:
        at = draw(st.integers(0, len(data) - 1))
        data = data[:at] + bytes([data[at] ^ draw(st.integers(1, 255))]) + data[at + 1:]
    elif damage == "bom":
        data = b"\xef\xbb\xbf" + data
    elif damage == "empty":
        data = b""
    ext = fmt.split("-")[0]
    return f"{fmt} ({damage}{', header lies' if lie else ''})", f"mesh.{ext}", data


@st.composite
def mesh_cases(draw):
    """Class "mesh": a valid scene whose one object is a generated mesh file."""
    kind, name, data = draw(mesh_bytes())
    scene = {"camera": {"eye": [3, 4, 6], "target": [0, 0, 0], "width": 16, "height": 12},
             "lights": [{"position": [5, 5, 5]}],
             "objects": [{"type": "mesh_file", "path": name}]}
    return Case(f"mesh {kind}", {name: data, "scene.json": json.dumps(scene).encode()})


@st.composite
def path_cases(draw):
    """Class "path": scene paths that never end or block (FIFO, devices, folders)."""
    special = draw(st.sampled_from(["fifo", "/dev/zero", "/dev/urandom", "/dev/null", "folder",
                                    "missing", "fifo mesh"]))
    if special == "fifo mesh":
        scene = {"objects": [{"type": "mesh_file", "path": "pipe.obj"}]}
        return Case("path fifo mesh", {"scene.json": json.dumps(scene).encode()},
                    special=special)
    return Case(f"path {special}", {}, scene=special, special=special)


# --- lesson files (issue 35) --------------------------------------------------------

SHIPPED_LESSON = ROOT / "core" / "lessons" / "files" / "02_observer.json"


@st.composite
def lesson_cases(draw):
    """Class "lesson": a shipped lesson damaged the ways hostile files are, or a path that never ends."""
    lesson = json.loads(SHIPPED_LESSON.read_text())
    step = lesson["steps"][draw(st.integers(0, len(lesson["steps"]) - 1))]
    how = draw(st.sampled_from(["as is", "view", "camera", "field", "scene", "long text", "many keys",
                                "json", "fifo", "/dev/zero", "folder", "missing"]))
    if how in ("fifo", "/dev/zero", "folder", "missing"):
        return Case(f"lesson path {how}", {}, scene=how if how.startswith("/") else "lesson.json",
                    special=how if how != "missing" else None)
    if how == "view":  # what the 3D pane cannot look from
        step["view"] = {"position": draw(maybe(vec(SANE), vec())),
                        "focal_point": draw(maybe(vec(SANE), vec())),
                        "up": draw(st.sampled_from([[0, 0, 0], [0, 1, 0], [0, 1e-300, 0], [1, 0, 0]]))}
        if draw(st.booleans()):
            step["view"]["focal_point"] = step["view"]["position"]
    elif how == "camera":
        step["camera"] = draw(camera())
    elif how == "field":
        key = draw(st.sampled_from(["pixel", "zbuffer_step", "panes", "overlays", "highlight", "frame",
                                    "image_order", "object_order", "formulas", "title"]))
        step[key] = draw(ANY_JSON)
    elif how == "scene":
        step["scene"] = draw(scene_dict())
    elif how == "long text":
        step["text"] = "x" * draw(st.sampled_from([20_000, 20_001, 5_000_000]))
    elif how == "many keys":  # one of them repeated: reported at once, not after minutes
        n = draw(st.sampled_from([1000, 200_000]))
        text = json.dumps(lesson)[:-1] + "".join(f', "k{i}": {i}' for i in range(n)) + ', "k7": 0}'
        return Case(f"lesson ({n:,} keys)", {"lesson.json": text.encode()}, scene="lesson.json")
    how_text, data = draw(scene_text(lesson))  # truncated, deep, huge int, BOM, garbage, duplicate
    return Case(f"lesson {how} ({how_text})", {"lesson.json": data}, scene="lesson.json")


#: Loads a lesson file as the window's File > Open lesson does; a refusal is one message, exit 2.
_LOAD_LESSON = """
import sys
from core.lessons.lesson_file import LessonFileError, load_lesson
try:
    load_lesson(sys.argv[1])
except LessonFileError as exc:
    print(exc, file=sys.stderr)
    sys.exit(2)
"""

_LESSON_NAMED = re.compile(
    r"^lesson file .+?: (\d+ problems:\s+)?"
    r"((top level|format|version|id|title|figures|questions|summary|steps|k\d+)([.\[][^\n]*?)?: "
    r"|[^\n]*?: unknown field "
    r"|line \d+, column \d+: |invalid JSON: |file not found$|cannot read the file: |too large: "
    r"|not a text file)"
)


def run_lesson(case: Case, folder: Path, timeout: float = 60.0):
    """Write ``case`` into ``folder`` and load its lesson file in a fresh Python; ``(returncode, stderr)``."""
    path = _materialise(case, folder)
    env = {**os.environ, "PYTHONPATH": str(ROOT), "PYTHONDONTWRITEBYTECODE": "1"}
    try:
        result = subprocess.run([sys.executable, "-c", _LOAD_LESSON, str(path)], cwd=ROOT, env=env,
                                capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, ""
    return result.returncode, result.stderr


def lesson_verdict(code, stderr: str) -> str | None:
    """What is wrong with one lesson load, or None if it was handled (also: a message of at most
    10,000 characters, so the window's dialog can show it)."""
    if len(stderr) > 10_000:
        return f"a message of {len(stderr):,} characters"
    return verdict(code, stderr, lambda text: bool(_LESSON_NAMED.match(text.strip())))


def _materialise(case: Case, folder: Path) -> Path:
    """Write the case's files into ``folder``; the path of the file to read."""
    for name, data in case.files.items():
        (folder / name).write_bytes(data)
    scene = folder / case.scene
    if case.special == "fifo":
        os.mkfifo(scene)
    elif case.special == "folder":
        scene.mkdir()
    elif case.special == "fifo mesh":
        os.mkfifo(folder / "pipe.obj")
    elif case.special and case.special.startswith("/dev/"):
        scene = Path(case.special)
    return scene


def run_case(case: Case, folder: Path, *options: str, timeout: float = 60.0):
    """Write ``case`` into ``folder`` and run ``python -m app render`` on it.

    Returns
    -------
    returncode : int (negative: killed by that signal; None: timed out, then killed)
    stderr : str
    peak_kib : int, the command's own peak resident memory (``ru_maxrss``, KiB)
    """
    scene = _materialise(case, folder)
    command = [sys.executable, "-m", "app", "render", str(scene), "--out",
               str(folder / "out.png"), *options]
    env = {**os.environ, "PYTHONPATH": str(ROOT), "PYTHONDONTWRITEBYTECODE": "1"}
    with tempfile.TemporaryFile() as err, tempfile.NamedTemporaryFile("r") as report:
        # A tiny launcher starts the command and reports its own wait4 figures: a child's
        # ru_maxrss starts at its parent's size at fork, so the launcher must be small.
        launcher = [sys.executable, "-I", "-S", "-c", _LAUNCHER, report.name]
        proc = subprocess.Popen(launcher + command, cwd=ROOT, stdout=subprocess.DEVNULL,
                                stderr=err, env=env, start_new_session=True)
        try:
            proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
            err.seek(0)
            return None, err.read().decode(errors="replace"), 0
        status, peak_kib = map(int, report.read().split())
        err.seek(0)
        return os.waitstatus_to_exitcode(status), err.read().decode(errors="replace"), peak_kib


_LAUNCHER = """
import os, sys
pid = os.posix_spawn(sys.argv[2], sys.argv[2:], os.environ)
_, status, usage = os.wait4(pid, 0)
with open(sys.argv[1], "w") as f:
    f.write(f"{status} {usage.ru_maxrss}")
"""


def verdict(code, stderr: str, names_what=names_a_field) -> str | None:
    """What is wrong with one run, or None if it was handled; ``names_what(stderr)``: whether a
    refusal names what is wrong."""
    if code is None:
        return "timed out (a hang)"
    if code < 0:
        return f"killed by signal {-code}"
    if "Traceback" in stderr:
        return "traceback"
    if code not in (0, 2):
        return f"exit status {code}"
    if code == 2 and not names_what(stderr):
        return "message names no field"
    return None
