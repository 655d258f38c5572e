"""Compiled shading of one hit: shadow rays, local Phong colour, and the rays it spawns.

:func:`shade_hit` is the heart of Whitted ray tracing, shared by the full
render (:mod:`core.image_order.kernels.render`) and by the ray tree of one pixel
(:mod:`core.image_order.ray_tree`), so both compute exactly the same numbers.  For a hit
it

1. rebuilds the hit point and the surface normal (see :mod:`core.image_order.ray_offset`
   for why the point is recomputed in the ``scaled`` mode);
2. sends one shadow ray towards every light in front of the surface (unless
   the effects plan says nothing can block that light; from the inside of a sphere it
   tests that sphere first, which it must cross to reach a light outside) and adds the
   light's Lambert and Phong terms if the ray reaches it (:mod:`core.image_order.shading`);
3. prepares the reflected ray (mirror direction) at a reflective or
   transparent surface and the refracted ray (Snell's law) at a transparent
   one, with their coefficients (Fresnel's split, :mod:`core.image_order.optics`) and
   whether they will be traced (depth limit, minimum weight).

Everything is written into a flat record (:mod:`core.image_order.flat_layout`), or, for
the full render (``full`` False, a constant, so the compiler drops the other writes), only
the local colour and the spawned rays the render reads.
:func:`shade_hit` is inlined into the render's loops: as a call it would bind
some thirty arrays anew for every hit.
"""

from __future__ import annotations

import math

from core.image_order import flat_layout
from core.image_order.intersect_sphere import line_terms, outward_normal
from core.image_order.intersect_triangle import barycentric_point, ray_shear
from core.image_order.kernels.accel_spheres import bounding_roots
from core.image_order.kernels.bvh_traverse import bvh_closest
from core.image_order.kernels.closest_hit import BVH, closest_hit
from core.image_order.kernels.intersect import sphere_hit
from core.image_order.kernels.jit import jit, jit_inline
from core.image_order.kernels.primitives import no_hit
from core.image_order.optics import dot, fresnel_dielectric, reflect, refract
from core.image_order.ray_offset import error_bound, offset_ray_origin
from core.image_order.shading import lambert, phong, surface_split


@jit
def _unit(v):
    length = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    return v[0] / length, v[1] / length, v[2] / length


@jit
def surface_point(o, d, hit, scaled, geo):
    """The hit point and the outward unit normal there: ``(point, normal, error)``.

    ``scaled``: the point is rebuilt from the surface (barycentric
    combination, or projection onto the sphere) and ``error`` is the offset
    distance for rays leaving it; otherwise the point is ``o + t d`` and
    ``error`` is 0.
    """
    prim, t, b0, b1, b2 = hit
    rows, n_spheres, _, _, _, normals, magnitude = geo
    p = (o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2])
    if prim < n_spheres:
        c = flat_layout.ROW_CENTER
        cx, cy, cz = rows[prim, c], rows[prim, c + 1], rows[prim, c + 2]
        r = rows[prim, flat_layout.ROW_RADIUS]
        n = outward_normal(p[0], p[1], p[2], cx, cy, cz, d[0], d[1], d[2])
        if scaled:
            p = (cx + r * n[0], cy + r * n[1], cz + r * n[2])
    else:
        k = prim - n_spheres
        n = (normals[k, 0], normals[k, 1], normals[k, 2])
        if scaled:
            p = barycentric_point(rows, prim, b0, b1, b2)
    error = error_bound(magnitude[prim]) if scaled else 0.0
    return p, n, error


@jit
def _write3(rec, at, v):
    rec[at], rec[at + 1], rec[at + 2] = v[0], v[1], v[2]


@jit
def _child(rec, at, origin, direction, weight, k, depth, opts):
    """Record a spawned ray and whether it will be traced."""
    _write3(rec, at + flat_layout.CHILD_ORIGIN, origin)
    _write3(rec, at + flat_layout.CHILD_DIRECTION, direction)
    rec[at + flat_layout.CHILD_WEIGHT] = weight * k
    if k <= 0.0:
        status = flat_layout.CHILD_NONE
    elif depth >= opts[flat_layout.OPT_MAX_DEPTH]:
        status = flat_layout.CHILD_DEPTH_LIMIT
    elif weight * k < opts[flat_layout.OPT_MIN_WEIGHT]:
        status = flat_layout.CHILD_TOO_WEAK
    else:
        status = flat_layout.CHILD_TRACED
    rec[at + flat_layout.CHILD_STATUS] = status


@jit_inline
def may_be_shadowed(lights, light, receiver, geo, o, d, t_min, t_max, counters):
    """Whether the shadow ray ``o + t d`` (``t_min <= t < t_max``), from the outside of object
    ``receiver`` towards ``light``, meets the bounding sphere of an object that may shadow that
    receiver (the effects plan's ``LightPlan.blockers``, laid out in ``lights``).

    Where it meets none, no object can block it: the plan proved the others harmless, and a
    shadow ray from the outside of a convex object never meets that object again (one that is
    not convex is among its own blockers) -- when it starts from the scaled offset
    (:mod:`core.image_order.ray_offset`); from a fixed epsilon it may meet its own surface
    (shadow acne), so the caller asks only in the scaled mode.  Only the BVH asks: the other
    methods do their work as the lecture shows it, so that their figures compare the methods
    alone.  The test is the ``"spheres"`` method's
    (:mod:`core.image_order.kernels.accel_spheres`): a padded sphere around a mesh, which no
    crossing with one of its triangles can lie outside, and an analytic sphere itself; its roots
    are found only for a sphere the line does not clearly pass by (:func:`_far_from_line`).
    Counted as box and sphere tests.
    """
    at = flat_layout.LIGHT_SIZE + receiver * flat_layout.RECEIVER_SIZE
    n = int(lights[light, at])
    if n == flat_layout.BLOCKERS_UNKNOWN:
        return True
    bounding = geo[flat_layout.GEO_BOUNDING]
    for k in range(n):
        counters[flat_layout.BOUNDS_TESTS] += 1
        blocker = int(lights[light, at + 1 + k])
        if _far_from_line(o, d, bounding, blocker):
            continue
        enter, leave = bounding_roots(o, d, bounding, blocker)
        if enter < t_max and leave >= t_min:
            return True
    return False


@jit_inline
def asks_bounds_first(method, scaled, front):
    """Whether a shadow ray asks :func:`may_be_shadowed` before it searches the scene: through the
    BVH, from the scaled offset, leaving the front of its surface (the conditions under which
    that answer is proved; the render and the ray tree of one pixel both ask this)."""
    return method == BVH and scaled and front


@jit_inline
def asks_its_sphere_first(method, front, prim, n_spheres):
    """Whether a shadow ray tests its own sphere before it searches the scene
    (:func:`leaves_its_sphere`): through the BVH, from the inside of an analytic sphere (the render and
    the ray tree of one pixel both ask this)."""
    return method == BVH and not front and prim < n_spheres


@jit_inline
def leaves_its_sphere(geo, prim, o, d, t_min, t_max, counters):
    """The hit ``(prim, t, 0, 0, 0)`` where the shadow ray ``o + t d`` (``t_min <= t < t_max``), sent
    from the inside of the analytic sphere ``prim``, crosses that sphere, or :func:`no_hit`.

    A ray from a point inside a sphere to a light outside it must leave the sphere: a hit seen from
    inside (a glass ball's rays, after refraction) lies in the shadow of its own sphere for every
    light outside it.  This is the sphere's own test (:func:`~core.image_order.kernels.primitives.prim_hit`,
    the same numbers in the same order), which the search of the scene makes too (the crossing lies
    in the sphere's box, so its leaf is entered): where it finds the crossing the search would have
    found a blocker (this one, or another first), so the light's status is the same, and the
    search is not needed.  Where it finds none (a light inside the sphere), the caller searches.
    Counted as one primitive test.
    """
    counters[flat_layout.PRIM_TESTS] += 1
    rows, c = geo[flat_layout.GEO_ROWS], flat_layout.ROW_CENTER
    t = sphere_hit(o[0], o[1], o[2], d[0], d[1], d[2], rows[prim, c], rows[prim, c + 1], rows[prim, c + 2],
                   rows[prim, flat_layout.ROW_RADIUS], t_min, t_max)
    if t < t_max:
        return prim, t, 0.0, 0.0, 0.0
    return no_hit()


#: A sphere is passed by without finding its roots when the squared distance of its centre from
#: the line exceeds ``r^2`` by this share of ``2 (|f|^2 + r^2) >= (|f| + r)^2`` (``f``: the line's
#: start minus the centre): the distance then exceeds ``r`` by about ``1e-9 (|f| + r)`` or more,
#: far beyond the rounding of either computation and the tangent tolerance of ``sphere_roots``
#: (``8 eps (|f| + r)``), so ``sphere_roots`` would have found no roots either.
_CLEAR_MARGIN = 2.0**-30


@jit_inline
def _far_from_line(o, d, bounding, ob):
    """Whether the line ``o + t d`` (``d`` of unit length) clearly passes object ``ob``'s bounding
    sphere by: a dot product and no square root or division, where most shadow rays pass far
    from every possible blocker."""
    _, _, _, _, along, f2, r2 = line_terms(o[0], o[1], o[2], d[0], d[1], d[2], bounding[ob, 0],
                                           bounding[ob, 1], bounding[ob, 2], bounding[ob, 3])
    return f2 - along * along > r2 + _CLEAR_MARGIN * 2.0 * (f2 + r2)


@jit_inline
def shade_hit(o, d, hit, weight, depth, materials, lights, opts, geo, grid, bvh, scratch, counters,
              rec, full):
    """Shade the hit ``hit`` of the unit ray ``o + t d`` and fill the record ``rec``.

    Parameters
    ----------
    o, d : (3,) float tuples, the ray (``d`` unit length), world space.
    hit : ``(prim, t, b0, b1, b2)`` from :func:`core.image_order.kernels.closest_hit.closest_hit`.
    weight : float, the ray's weight in the pixel (1 for a primary ray).
    depth : int, generation of the ray (0 for a primary ray).
    materials, lights, opts : arrays laid out as in :mod:`core.image_order.flat_layout`.
    geo, grid, bvh, scratch, counters : as for ``closest_hit`` (shadow rays).
    rec : (record_size(L),) float64, written.
    full : bool, a constant at each call: True fills the whole record (the ray tree of one pixel
        shows every number); False writes only what the render reads (``REC_LOCAL`` and the two
        spawned rays ``REC_REFLECT``, ``REC_REFRACT``), the same numbers by the same formulas.
    """
    prim = hit[flat_layout.HIT_PRIM]
    ob = geo[flat_layout.GEO_PRIM_OBJECT][prim]
    scaled = opts[flat_layout.OPT_SCALED_OFFSET] > 0.0
    t_start = 0.0 if scaled else opts[flat_layout.OPT_EPSILON]
    method = int(opts[flat_layout.OPT_ACCEL])
    p, n_out, error = surface_point(o, d, hit, scaled, geo)
    front = dot(d, n_out) < 0.0
    n = n_out if front else (-n_out[0], -n_out[1], -n_out[2])
    to_eye = (-d[0], -d[1], -d[2])
    kr = materials[ob, flat_layout.MAT_REFLECTIVITY] if opts[flat_layout.OPT_REFLECTION] > 0.0 else 0.0
    kt = materials[ob, flat_layout.MAT_TRANSPARENCY] if opts[flat_layout.OPT_REFRACTION] > 0.0 else 0.0
    w_local, kr, kt = surface_split(kr, kt)
    color = (materials[ob, flat_layout.MAT_COLOR], materials[ob, flat_layout.MAT_COLOR + 1],
             materials[ob, flat_layout.MAT_COLOR + 2])
    ambient = w_local * materials[ob, flat_layout.MAT_AMBIENT]
    lr, lg, lb = ambient * color[0], ambient * color[1], ambient * color[2]
    if full:
        rec[flat_layout.REC_PRIM] = prim
        rec[flat_layout.REC_OBJECT] = ob
        rec[flat_layout.REC_T] = hit[flat_layout.HIT_T]
        _write3(rec, flat_layout.REC_POINT, p)
        _write3(rec, flat_layout.REC_NORMAL, n)
        rec[flat_layout.REC_FRONT] = 1.0 if front else 0.0
        rec[flat_layout.REC_W_LOCAL] = w_local
        _write3(rec, flat_layout.REC_AMBIENT, (lr, lg, lb))

    # Shadow rays and local shading, light by light.
    for i in range(lights.shape[0]):
        at = flat_layout.REC_LIGHTS + i * flat_layout.LIGHT_REC_SIZE
        lp = flat_layout.LIGHT_POSITION
        lx, ly, lz = lights[i, lp], lights[i, lp + 1], lights[i, lp + 2]
        to_light = (lx - p[0], ly - p[1], lz - p[2])
        distance = math.sqrt(dot(to_light, to_light))
        to_light = (to_light[0] / distance, to_light[1] / distance, to_light[2] / distance)
        if full:
            rec[at + flat_layout.LR_DISTANCE] = distance
            rec[at + flat_layout.LR_BLOCKER] = -1.0
            rec[at + flat_layout.LR_BLOCKER_T] = math.inf
            _write3(rec, at + flat_layout.LR_ORIGIN, p)
            _write3(rec, at + flat_layout.LR_DIRECTION, to_light)
            _write3(rec, at + flat_layout.LR_CONTRIBUTION, (0.0, 0.0, 0.0))
        if dot(n, to_light) <= 0.0:
            if full:
                rec[at + flat_layout.LR_STATUS] = flat_layout.LIGHT_BEHIND
            continue
        status = flat_layout.LIGHT_UNBLOCKABLE
        if lights[i, flat_layout.LIGHT_BLOCKABLE] > 0.0:
            # The origin goes to the side the light is on, which is the side ``n`` faces: the test
            # above found dot(n, to_light) > 0, and where n = -n_out that sum is exactly minus the
            # offset's dot(to_light, n_out) (the same products, negated, added in the same order).
            # So ``n`` picks the very side ``to_light`` would, bit for bit, without waiting for
            # its square root and divisions: a Whitted frame took about 1/1.04 of its time.
            so = offset_ray_origin(p, n_out, error, n) if scaled else p
            sd = (lx - so[0], ly - so[1], lz - so[2])
            s_dist = math.sqrt(dot(sd, sd))
            sd = (sd[0] / s_dist, sd[1] / s_dist, sd[2] / s_dist)
            counters[flat_layout.SHADOW] += 1
            # From the inside of a sphere the ray tests that sphere first; from the outside it may ask
            # the bounding spheres of the objects that may shadow it; it searches the scene unless
            # either answered.
            blocker, searched = no_hit(), True
            if asks_its_sphere_first(method, front, prim, geo[flat_layout.GEO_N_SPHERES]):
                blocker = leaves_its_sphere(geo, prim, so, sd, t_start, s_dist, counters)
                searched = blocker[flat_layout.HIT_PRIM] < 0
            elif asks_bounds_first(method, scaled, front):
                searched = may_be_shadowed(lights, i, ob, geo, so, sd, t_start, s_dist, counters)
            if searched and method == BVH:
                # The any-hit traversal inlined here, as for the render's primary rays: called
                # through closest_hit, every array of the tree is bound anew for each shadow ray.
                blocker = bvh_closest(so, sd, ray_shear(sd[0], sd[1], sd[2]), t_start, s_dist, True, bvh,
                                      geo[flat_layout.GEO_N_SPHERES], scratch[flat_layout.SCRATCH_STACK],
                                      scratch[flat_layout.SCRATCH_STACK_T], counters)
            elif searched:
                blocker = closest_hit(method, so, sd, t_start, s_dist, True, geo, grid, bvh, scratch,
                                      counters)
            if full:
                _write3(rec, at + flat_layout.LR_ORIGIN, so)
                _write3(rec, at + flat_layout.LR_DIRECTION, sd)
                rec[at + flat_layout.LR_DISTANCE] = s_dist
                rec[at + flat_layout.LR_BLOCKER] = blocker[flat_layout.HIT_PRIM]
                rec[at + flat_layout.LR_BLOCKER_T] = blocker[flat_layout.HIT_T]
            status = (flat_layout.LIGHT_BLOCKED if blocker[flat_layout.HIT_PRIM] >= 0
                      else flat_layout.LIGHT_REACHED)
        if full:
            rec[at + flat_layout.LR_STATUS] = status
        if status == flat_layout.LIGHT_BLOCKED:
            continue
        diffuse = w_local * materials[ob, flat_layout.MAT_DIFFUSE] * lambert(n, to_light)
        shininess = materials[ob, flat_layout.MAT_SHININESS]
        highlight = materials[ob, flat_layout.MAT_SPECULAR] * phong(n, to_light, to_eye, shininess)
        cr = lights[i, flat_layout.LIGHT_RGB] * (diffuse * color[0] + highlight)
        cg = lights[i, flat_layout.LIGHT_RGB + 1] * (diffuse * color[1] + highlight)
        cb = lights[i, flat_layout.LIGHT_RGB + 2] * (diffuse * color[2] + highlight)
        if full:
            _write3(rec, at + flat_layout.LR_CONTRIBUTION, (cr, cg, cb))
        lr += cr
        lg += cg
        lb += cb
    _write3(rec, flat_layout.REC_LOCAL, (lr, lg, lb))

    # Reflected and refracted rays: directions, Fresnel split, whether they go on.
    k_reflect, k_refract = kr, 0.0
    fr, ft, tir = math.nan, math.nan, 0.0
    refracted = (0.0, 0.0, 0.0)
    if kt > 0.0:
        ior = materials[ob, flat_layout.MAT_IOR]
        n1, n2 = (1.0, ior) if front else (ior, 1.0)
        ok, bent = refract(d, n, n1 / n2)
        if not ok:
            fr, ft, tir = 1.0, 0.0, 1.0
        else:
            fr, ft = fresnel_dielectric(min(1.0, -dot(d, n)), n1, n2)
            refracted = _unit(bent)
        k_reflect, k_refract = kr + kt * fr, kt * ft
    if full:
        rec[flat_layout.REC_FRESNEL_R] = fr
        rec[flat_layout.REC_FRESNEL_T] = ft
        rec[flat_layout.REC_TIR] = tir
        rec[flat_layout.REC_K_REFLECT] = k_reflect
        rec[flat_layout.REC_K_REFRACT] = k_refract
    mirrored = _unit(reflect(d, n)) if k_reflect > 0.0 else (0.0, 0.0, 0.0)
    origin = offset_ray_origin(p, n_out, error, mirrored) if scaled and k_reflect > 0.0 else p
    _child(rec, flat_layout.REC_REFLECT, origin, mirrored, weight, k_reflect, depth, opts)
    origin = offset_ray_origin(p, n_out, error, refracted) if scaled and k_refract > 0.0 else p
    _child(rec, flat_layout.REC_REFRACT, origin, refracted, weight, k_refract, depth, opts)
