"""Reflection, Snell's law and the Fresnel equations, checked against independent formulas."""

import math

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from core.image_order.optics import critical_angle_deg, dot, fresnel_dielectric, reflect, refract
from core.image_order.shading import WHOLE_POWERS, lambert, phong, power, surface_split

PAIRS = [(1.0, 1.5), (1.5, 1.0), (1.0, 1.33), (1.33, 1.0), (1.0, 2.42), (2.42, 1.0), (1.2, 1.7)]


def unit(v):
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


def incident(theta_deg, normal=(0.0, 1.0, 0.0), azimuth_deg=30.0):
    """A unit direction arriving at angle theta to ``normal`` (towards the surface), and the normal."""
    n = unit(normal)
    tangent = unit(np.cross(n, [0.3, 0.1, 0.9]))
    bitangent = np.cross(n, tangent)
    a = math.radians(azimuth_deg)
    along = math.cos(a) * tangent + math.sin(a) * bitangent
    t = math.radians(theta_deg)
    return tuple(math.sin(t) * along - math.cos(t) * n), tuple(n)


def sin_angle(u, n):
    """sin of the angle between a direction and the normal line, from the cross product."""
    return float(np.linalg.norm(np.cross(unit(u), n)))


# --- reflection -----------------------------------------------------------------------------


@pytest.mark.parametrize("theta", [0.0, 10.0, 45.0, 80.0, 89.9])
def test_angle_of_reflection_equals_angle_of_incidence(theta):
    d, n = incident(theta)
    r = np.array(reflect(d, n))
    assert np.linalg.norm(r) == pytest.approx(1.0, abs=1e-15)
    assert dot(r, n) == pytest.approx(-dot(d, n), abs=1e-15)  # same angle, other side
    assert np.linalg.norm(np.cross(r - np.array(d), n)) == pytest.approx(0.0, abs=1e-15)  # in the plane


# --- Snell's law ----------------------------------------------------------------------------


@pytest.mark.parametrize(("n1", "n2"), PAIRS)
@pytest.mark.parametrize("theta", [0.0, 5.0, 20.0, 35.0, 40.0, 60.0, 85.0])
def test_snell_law_holds_or_total_internal_reflection(n1, n2, theta):
    d, n = incident(theta)
    ok, t = refract(d, n, n1 / n2)
    sin1 = math.sin(math.radians(theta))
    if n1 * sin1 > n2:  # no real angle of refraction
        assert not ok
        return
    assert ok
    t = np.array(t)
    assert np.linalg.norm(t) == pytest.approx(1.0, abs=1e-14)
    assert n1 * sin_angle(d, n) == pytest.approx(n2 * sin_angle(t, n), abs=1e-13)
    assert dot(t, n) < 0  # goes on through the surface
    assert np.dot(np.cross(d, n), t) == pytest.approx(0.0, abs=1e-14)  # plane of incidence


def test_refraction_bends_towards_the_normal_entering_a_denser_medium():
    d, n = incident(45.0)
    _, t = refract(d, n, 1 / 1.5)
    assert sin_angle(t, n) == pytest.approx(math.sin(math.radians(45.0)) / 1.5, rel=1e-14)


def test_critical_angle():
    assert critical_angle_deg(1.5, 1.0) == pytest.approx(math.degrees(math.asin(1 / 1.5)), rel=1e-15)
    assert critical_angle_deg(1.0, 1.5) is None
    c = critical_angle_deg(1.5, 1.0)
    assert refract(*incident(c - 0.01), 1.5)[0]
    assert not refract(*incident(c + 0.01), 1.5)[0]


# --- Fresnel --------------------------------------------------------------------------------


@pytest.mark.parametrize(("n1", "n2"), PAIRS)
def test_normal_incidence_reflectance(n1, n2):
    r, t = fresnel_dielectric(1.0, n1, n2)
    assert r == pytest.approx(((n1 - n2) / (n1 + n2)) ** 2, rel=1e-14)
    assert t == pytest.approx(4 * n1 * n2 / (n1 + n2) ** 2, rel=1e-14)


@pytest.mark.parametrize(("n1", "n2"), PAIRS)
@pytest.mark.parametrize("theta", np.linspace(0.0, 89.0, 30))
def test_reflectance_plus_transmittance_is_one(n1, n2, theta):
    r, t = fresnel_dielectric(math.cos(math.radians(theta)), n1, n2)
    assert 0.0 <= r <= 1.0 and 0.0 <= t <= 1.0
    assert r + t == pytest.approx(1.0, abs=1e-14)


@pytest.mark.parametrize(("n1", "n2"), PAIRS)
@pytest.mark.parametrize("theta", [10.0, 30.0, 50.0, 70.0, 85.0])
def test_reflectance_matches_the_sine_and_tangent_forms(n1, n2, theta):
    # Fresnel's own forms: R_s = sin²(θ1 - θ2) / sin²(θ1 + θ2), R_p = tan²(θ1 - θ2) / tan²(θ1 + θ2).
    t1 = math.radians(theta)
    s2 = n1 / n2 * math.sin(t1)
    r, _ = fresnel_dielectric(math.cos(t1), n1, n2)
    if s2 >= 1.0:
        assert r == 1.0
        return
    t2 = math.asin(s2)
    rs = (math.sin(t1 - t2) / math.sin(t1 + t2)) ** 2
    rp = (math.tan(t1 - t2) / math.tan(t1 + t2)) ** 2
    assert r == pytest.approx((rs + rp) / 2, rel=1e-12)


@pytest.mark.parametrize(("n1", "n2"), [(1.5, 1.0), (1.33, 1.0), (2.42, 1.0)])
def test_beyond_the_critical_angle_everything_reflects(n1, n2):
    critical = critical_angle_deg(n1, n2)
    for theta in np.linspace(critical + 0.001, 89.9, 20):
        assert fresnel_dielectric(math.cos(math.radians(theta)), n1, n2) == (1.0, 0.0)
    r, _ = fresnel_dielectric(math.cos(math.radians(critical - 0.5)), n1, n2)
    assert r < 1.0


# --- local shading --------------------------------------------------------------------------


def test_lambert_and_phong_by_hand():
    n = (0.0, 1.0, 0.0)
    light = tuple(unit([1.0, 1.0, 0.0]))
    assert lambert(n, light) == pytest.approx(math.cos(math.radians(45)), rel=1e-15)
    assert lambert(n, (0.0, -1.0, 0.0)) == 0.0
    viewer = tuple(unit([-1.0, 1.0, 0.0]))  # the mirror direction: full highlight
    assert phong(n, light, viewer, 50.0) == pytest.approx(1.0, rel=1e-15)
    off = tuple(unit([0.0, 1.0, 0.0]))  # 45° off the mirror direction: cos(45°)^n
    assert phong(n, light, off, 4.0) == pytest.approx(math.cos(math.radians(45)) ** 4, rel=1e-14)
    assert phong(n, (0.0, -1.0, 0.0), viewer, 4.0) == 0.0
    # Viewer on the far side of the mirror direction (R . V = -cos 45°): max(0, R . V)^n is 0 for n > 0,
    # and 0^0 = 1, a surface whose highlight does not narrow at all.
    away = tuple(unit([1.0, 0.0, 0.0]))
    assert phong(n, light, away, 4.0) == 0.0
    assert phong(n, light, away, 0.0) == 1.0


@settings(max_examples=400, deadline=None)
@given(x=st.floats(0.0, 1.0), n=st.integers(0, WHOLE_POWERS))
def test_a_whole_power_by_repeated_squaring_is_within_n_units_in_the_last_place(x, n):
    """Phong's ``max(0, R.V)^n`` for a whole ``n`` is raised by repeated squaring; each product
    rounds once and the error of ``x^(2^k)`` at most doubles per squaring, so the result lies
    within ``n`` units of 2^-53 of the exact power (mpmath, 60 digits), above the range where
    doubles lose precision (2^-1000)."""
    exact = mpmath.mpf(x) ** n
    got = power(x, float(n))
    if exact > mpmath.mpf(2) ** -1000:
        assert abs(mpmath.mpf(got) - exact) <= max(n, 1) * mpmath.mpf(2) ** -53 * exact
    else:
        assert 0.0 <= got <= 2.0**-990


def test_a_power_that_is_not_whole_is_the_c_librarys():
    for x, n in [(0.3, 2.5), (0.9, 1e-3), (0.5, WHOLE_POWERS + 1.0), (0.999, 4096.0)]:
        assert power(x, n) == x**n
    assert power(0.0, 0.0) == 1.0 and power(0.0, 3.0) == 0.0 and power(1.0, 1000.0) == 1.0


def test_surface_split_adds_up_to_one():
    for kr, kt in [(0.0, 0.0), (0.3, 0.5), (1.0, 0.0), (0.7, 0.9)]:
        w, r, t = surface_split(kr, kt)
        assert w + r + t == pytest.approx(1.0, abs=1e-15)
        assert min(w, r, t) >= 0.0
