"""Output files: images and animations encoded as sRGB, and every output written atomically.

Renderers produce *linear* RGB; :func:`encode_image` turns it into 8-bit sRGB
with :func:`core.srgb.to_srgb8` (the one place that happens) and encodes it
with imageio: PNG for ``.png``, JPEG (quality 95) for ``.jpg`` and ``.jpeg``;
:func:`encode_animation` makes a GIF, or an MP4 with imageio-ffmpeg.

An :class:`Outputs` set checks its paths *before* the work (the folder exists
and is writable, the extension matches the format, no output names an input
or another output), so a bad path does not waste a long render, and then
writes all files at once with :func:`core.files.safe_files.write_atomic_all`: a
failed write, or Ctrl-C, leaves every old file byte-for-byte as it was.
"""

from __future__ import annotations

import io
import os
import signal
import tempfile
from pathlib import Path

import numpy as np

from core.files.safe_files import OutputError, write_atomic, write_atomic_all
from core.srgb import to_srgb8

IMAGE_EXTENSIONS = {".png": "PNG", ".jpg": "JPEG", ".jpeg": "JPEG"}
ANIMATION_EXTENSIONS = (".gif", ".mp4")

__all__ = ["ANIMATION_EXTENSIONS", "IMAGE_EXTENSIONS", "OutputError", "Outputs", "encode_animation",
           "encode_image", "write_image"]


def encode_image(rgb: np.ndarray, extension: str) -> bytes:
    """The bytes of an image file holding ``rgb``.

    Parameters
    ----------
    rgb : (H, W, 3) float, linear RGB in [0, 1] (clipped), row 0 at the top.
    extension : ``".png"``, ``".jpg"`` or ``".jpeg"``.

    Returns
    -------
    bytes
        An 8-bit sRGB PNG or JPEG file.
    """
    import imageio.v3 as iio

    kind = IMAGE_EXTENSIONS[extension.lower()]
    pixels = to_srgb8(rgb)
    options = {"quality": 95} if kind == "JPEG" else {}
    buffer = io.BytesIO()
    iio.imwrite(buffer, pixels, extension=extension.lower(), **options)
    return buffer.getvalue()


def write_image(path, rgb: np.ndarray) -> None:
    """Write ``rgb`` (linear RGB) as an sRGB PNG or JPEG, chosen by the extension, atomically."""
    write_atomic(path, encode_image(rgb, Path(path).suffix))


def encode_animation(frames, extension: str, fps: int, limit: int) -> bytes:
    """The bytes of a GIF or MP4 of ``frames`` (each (H, W, 3) linear RGB, written as sRGB).

    The file is encoded in memory (GIF) or by ffmpeg into a private temporary
    folder (MP4) and returned as bytes, so the caller writes it into place
    atomically.  Frames are taken one at a time: an MP4 holds one, a GIF all
    of them until it is written, and a GIF whose frames would exceed
    ``limit`` bytes is refused (:class:`app.usage.UsageError`) as soon as they do.

    Raises
    ------
    OutputError
        When the encoder fails (ffmpeg's exit status is not 0, its file is
        empty, or writing its file fails, e.g. over a file-size limit); the
        message says why.
    """
    import imageio.v3 as iio

    from app.usage import UsageError
    from core import budget

    if extension == ".mp4":
        return _encode_mp4(frames, fps)
    pixels, held = [], 0
    for frame in frames:
        pixels.append(to_srgb8(frame))
        held += pixels[-1].nbytes
        if held > limit:
            raise UsageError(f"the GIF's frames need more than {budget.format_bytes(limit)}; "
                             "use a smaller image, fewer frames, or MP4")
    buffer = io.BytesIO()
    try:
        iio.imwrite(buffer, pixels, extension=".gif", duration=1000 / fps, loop=0)
    except (OSError, ValueError) as exc:  # a GIF of no frames, or the encoder's own failure
        raise OutputError(f"the GIF encoder failed: {exc}") from None
    return buffer.getvalue()


def _encode_mp4(frames, fps: int) -> bytes:
    """An H.264 MP4 of ``frames`` by ffmpeg (imageio-ffmpeg's), its exit status and file checked."""
    import subprocess

    import imageio_ffmpeg

    with tempfile.TemporaryDirectory(prefix="render-explorer-export-") as folder:
        path = os.path.join(folder, "animation.mp4")
        encoder = None
        try:
            for frame in frames:
                pixels = to_srgb8(frame)
                h, w = pixels.shape[:2]
                pixels = np.pad(pixels, ((0, h % 2), (0, w % 2), (0, 0)), mode="edge")  # H.264: even sizes
                if encoder is None:
                    command = [imageio_ffmpeg.get_ffmpeg_exe(), "-loglevel", "error", "-y", "-f", "rawvideo",
                               "-pix_fmt", "rgb24", "-s", f"{pixels.shape[1]}x{pixels.shape[0]}",
                               "-r", str(fps), "-i", "-",
                               "-an", "-vcodec", "libx264", "-pix_fmt", "yuv420p", "-crf", "25", path]
                    encoder = subprocess.Popen(command, stdin=subprocess.PIPE, stdout=subprocess.DEVNULL,
                                               stderr=subprocess.PIPE)
                encoder.stdin.write(np.ascontiguousarray(pixels).tobytes())
            if encoder is None:
                raise OutputError("an MP4 needs at least one frame")
            encoder.stdin.close()
            status = encoder.wait()
        except BrokenPipeError:  # ffmpeg stopped reading: it failed, and says why below
            status = encoder.wait()
        except BaseException:  # Ctrl-C or any failure: ffmpeg must not outlive the export
            if encoder is not None:
                encoder.kill()
                encoder.wait()
            raise
        finally:
            if encoder is not None:
                why = encoder.stderr.read().decode(errors="replace").strip().splitlines()
                encoder.stderr.close()
        if status != 0:
            if status < 0:
                reason = f"killed by {signal.Signals(-status).name}"
            else:
                reason = f"exit status {status}: {why[-1] if why else 'no message'}"
            raise OutputError(f"the MP4 encoder (ffmpeg) failed ({reason})")
        try:
            with open(path, "rb") as f:
                data = f.read()
        except OSError as exc:
            raise OutputError(f"the MP4 encoder's file cannot be read: {exc.strerror or exc}") from None
        if not data:
            raise OutputError("the MP4 encoder (ffmpeg) wrote an empty file")
        return data


def _same_file(a: str, b: str) -> bool:
    try:
        return os.path.samefile(a, b)
    except OSError:
        return os.path.realpath(a) == os.path.realpath(b)


class Outputs:
    """The output files of one command: checked up front, written atomically.

    Parameters
    ----------
    inputs : paths the command reads; no output may name one of them.

    Examples
    --------
    >>> outputs = Outputs(inputs=["scene.json"])
    >>> outputs.add("--out", "scene.json", (".png",))
    Traceback (most recent call last):
    ...
    ValueError: --out: scene.json is an input of this command; writing it would destroy it
    """

    def __init__(self, inputs=()):
        self.inputs = [os.fspath(p) for p in inputs]
        self.paths: dict[str, str] = {}

    def add(self, option: str, path, extensions: tuple[str, ...]) -> None:
        """Check the output ``path`` given by ``option``; raises ``ValueError`` naming both."""
        path = os.fspath(path)
        self.check_inputs(option, path, self.inputs)
        ext = os.path.splitext(path)[1].lower()
        if ext not in extensions:
            raise ValueError(f"{option}: {path} must end in {' or '.join(extensions)}"
                             f" (got {ext or 'no extension'!r})")
        for other_option, other in self.paths.items():
            if _same_file(path, other):
                raise ValueError(f"{option}: {path} is also given to {other_option}")
        folder = os.path.dirname(os.path.abspath(path))
        if not os.path.isdir(folder):
            raise ValueError(f"{option}: the folder {folder} does not exist")
        if not os.access(folder, os.W_OK | os.X_OK):
            raise ValueError(f"{option}: the folder {folder} is not writable")
        if os.path.isdir(path):
            raise ValueError(f"{option}: {path} is a folder")
        if os.path.exists(path) and not os.access(path, os.W_OK):
            raise ValueError(f"{option}: {path} exists and is read-only")
        self.paths[option] = path

    def check_inputs(self, option: str, path: str, inputs) -> None:
        """Refuse an output that is one of ``inputs`` (also called once the mesh files are known)."""
        for source in inputs:
            if _same_file(path, source):
                raise ValueError(f"{option}: {path} is an input of this command; "
                                 "writing it would destroy it")

    def write(self, contents: dict[str, bytes]) -> None:
        """Write ``{option: bytes}`` to the checked paths, each atomically.

        Raises
        ------
        OutputError
            Naming the file that failed; then every file keeps its old contents.
        """
        write_atomic_all({self.paths[option]: data for option, data in contents.items()})
