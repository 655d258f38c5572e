"""Numbers shown to students: six significant digits, never ``-0``, the same on screen and in print."""

from core.image_order.intersect_sphere import explain, intersect_sphere
from core.shown_numbers import shown_number, shown_vector


def test_six_significant_digits_worked_by_hand():
    assert shown_number(1 / 3) == "0.333333"  # 0.333333|33...: six threes, the seventh digit rounds down
    assert shown_number(2 / 3) == "0.666667"  # 0.666666|66...: rounds up
    assert shown_number(1234567.0) == "1.23457e+06"  # seven digits do not fit: 1.23456|7 rounds up
    assert shown_number(123456.0) == "123456"  # six digits fit exactly, no exponent
    assert shown_number(2.0) == "2"  # no trailing zeros


def test_a_negative_zero_reads_zero_but_a_tiny_negative_keeps_its_sign():
    assert shown_number(-0.0) == "0"
    assert shown_number(-1e-9) == "-1e-09"


def test_a_vector_is_its_numbers_in_parentheses():
    assert shown_vector((1.0, -0.0, 2 / 3)) == "(1, 0, 0.666667)"


def test_the_intersect_command_writes_its_numbers_so():
    # The ray from the origin along +z meets the sphere of radius 1 around (0, 0, 3) at t = 2 and t = 4;
    # a = 1, b = 2 d.(o - c) = -6, c = |o - c|² - r² = 8, Δ = 36 - 32 = 4: all exact in binary.
    lines = "\n".join(explain(intersect_sphere((0.0, 0.0, 0.0), (0.0, 0.0, 1.0), (0.0, 0.0, 3.0), 1.0)))
    assert "= (0, 0, 0)" in lines
    assert "t_near = 2" in lines and "t_far = 4" in lines
