"""The hard-case lab: where the textbook method breaks and the app's robust one holds.

Ten cases, numbered as in the lab's list, each a function returning a
:class:`~core.hard_cases.result.CaseResult` with the naive (textbook)
result, the robust one the app uses, the exact reference and the error of
each:

1. ``tangent``: a ray tangent to a sphere, and rays a hair off it;
2. ``lecture_segment``: the lecture's segment with both ends inside the sphere;
3. ``far_sphere``: a small sphere far away, ``b² - 4ac`` against ``4a(r + |v|)(r - |v|)``;
4. ``shared_edges``: rays through shared edges and vertices of a closed mesh;
5. ``parallel``: rays parallel to a triangle, in its plane, and grazing it;
6. ``z_fighting``: nearly coplanar floors in every depth format;
7. ``behind_eye``: a polygon with a corner behind the eye, clipped or not;
8. ``total_reflection``: total internal reflection in a glass sphere;
9. ``shadow_acne``: fixed ε against the scaled ray offset, far from the origin;
10. ``culling``: back-face culling alone on a non-convex solid.

This package sits outside both halves of the lecture, so it may use both
:mod:`core.object_order` and :mod:`core.image_order`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from core.hard_cases import (
    clipping_cases,
    culling_cases,
    depth_cases,
    optics_cases,
    shadow_acne,
    sphere_cases,
    triangle_cases,
)
from core.hard_cases.result import CaseResult


@dataclass(frozen=True)
class Case:
    """One entry of the lab.

    Attributes
    ----------
    name : the key (``--case NAME``), equal to the result's ``name``.
    run : the case function; called with no arguments it uses its defaults.
    parameter : keyword of ``run`` a slider sweeps, or ``None``.
    options : further keywords and the values a user may pick for them.
    """

    name: str
    run: Callable[..., CaseResult]
    parameter: str | None = None
    options: dict[str, tuple] = field(default_factory=dict)


CASES: dict[str, Case] = {case.name: case for case in (
    Case("tangent", sphere_cases.tangent_rays, "offset"),
    Case("lecture_segment", sphere_cases.lecture_segment),
    Case("far_sphere", sphere_cases.far_sphere, "distance"),
    Case("shared_edges", triangle_cases.shared_edges, "distance"),
    Case("parallel", triangle_cases.parallel_rays, "angle_deg"),
    Case("z_fighting", depth_cases.z_fighting, "ratio"),
    Case("behind_eye", clipping_cases.behind_the_eye, "behind"),
    Case("total_reflection", optics_cases.total_internal_reflection, "angle_deg"),
    Case("shadow_acne", shadow_acne.shadow_acne, "distance", {"epsilon": shadow_acne.EPSILONS}),
    Case("culling", culling_cases.non_convex_culling, "yaw_deg"),
)}


def run_case(name: str, value: float | None = None, **options) -> CaseResult:
    """Run case ``name``, at parameter ``value`` (its default when ``None``) and the given options.

    Raises
    ------
    KeyError
        ``name`` is not a case (the message lists the cases).
    """
    if name not in CASES:
        raise KeyError(f"no hard case {name!r}; the cases are {', '.join(CASES)}")
    case = CASES[name]
    kwargs = dict(options)
    if value is not None and case.parameter is not None:
        kwargs[case.parameter] = value
    return case.run(**kwargs)


def run_all() -> list[CaseResult]:
    """Every case at its defaults, in the lab's order."""
    return [case.run() for case in CASES.values()]
