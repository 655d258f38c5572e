"""Image files: linear colours written as sRGB PNG or JPEG; outputs checked first, written whole."""

import imageio.v3 as iio
import numpy as np
import pytest
from PySide6.QtGui import QImage

from app.export.image_files import Outputs, write_image


def test_png_holds_srgb_of_the_linear_colours(tmp_path):
    # Published sRGB values: linear 0.5 is 188 (0.7354 x 255), 18 % grey is 118, ends exact.
    linear = np.array([[[0.0, 0.5, 1.0], [0.18, 0.18, 0.18]]])
    path = tmp_path / "img.png"
    write_image(path, linear)
    image = QImage(str(path))  # Qt's own decoder, not the writer's library
    assert (image.width(), image.height()) == (2, 1)
    first, second = image.pixelColor(0, 0), image.pixelColor(1, 0)
    assert (first.red(), first.green(), first.blue()) == (0, 188, 255)
    assert (second.red(), second.green(), second.blue()) == (118, 118, 118)


def test_png_keeps_every_pixel_and_row_order(tmp_path):
    rng = np.random.default_rng(3)
    linear = rng.random((7, 11, 3))
    path = tmp_path / "img.png"
    write_image(path, linear)
    from core.srgb import to_srgb8

    assert np.array_equal(iio.imread(path), to_srgb8(linear))


@pytest.mark.parametrize("name", ["img.jpg", "img.JPEG"])
def test_jpg_and_jpeg_names_write_jpeg(tmp_path, name):
    path = tmp_path / name
    write_image(path, np.full((16, 16, 3), 0.5))
    assert path.read_bytes()[:3] == b"\xff\xd8\xff"
    assert np.abs(iio.imread(path).astype(int) - 188).max() <= 2  # lossy, but close


def test_outputs_refuse_an_output_given_twice(tmp_path):
    outputs = Outputs()
    outputs.add("--out", tmp_path / "a.png", (".png",))
    with pytest.raises(ValueError, match="--depth-out: .* also given to --out"):
        outputs.add("--depth-out", tmp_path / "a.png", (".png",))


def test_outputs_refuse_a_folder_as_the_file(tmp_path):
    (tmp_path / "x.png").mkdir()
    with pytest.raises(ValueError, match="--out: .*x.png is a folder"):
        Outputs().add("--out", tmp_path / "x.png", (".png",))


def test_writing_all_outputs_leaves_no_temporary_files(tmp_path):
    outputs = Outputs()
    outputs.add("--out", tmp_path / "a.png", (".png",))
    outputs.add("--stats-out", tmp_path / "s.json", (".json",))
    outputs.write({"--out": b"png", "--stats-out": b"{}"})
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.png", "s.json"]
    assert (tmp_path / "s.json").read_bytes() == b"{}"
