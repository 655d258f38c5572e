"""Four slab tests at once: where a ray enters each of the four child boxes of a wide BVH node.

A ray enters an axis-aligned box where it has crossed the near plane of all
three slabs (x, y, z) and leaves it where it crosses the first far plane; it
hits the box when the entry comes before the exit.  The four boxes of a node
(:mod:`core.image_order.bvh`) are stored as six rows of four float32 numbers (``lo x``,
``lo y``, ``lo z``, ``hi x``, ``hi y``, ``hi z``), so one vector load brings
the same side of all four boxes and every step of the test runs on the four
boxes in one instruction (SIMD), the way Embree tests its wide nodes.

:func:`slab_test4` widens the float32 sides to float64 exactly and computes
in float64, as the scalar test would (see :mod:`core.image_order.kernels.intrinsics.simd`).
The comparisons keep pbrt's rule for a ray lying in a slab's plane:
``0 * inf`` is NaN, which fails every comparison and leaves the bound
unchanged.

:func:`slab_mask4` is the same test for a shadow ray, which only asks which
boxes it enters: one bit per box from one vector comparison, where reading
the four entries back out of the vector and comparing each costs an any-hit
walk about a tenth of its time (``bench trace``'s 10,000-triangle ball).

:func:`slab_interval4` is the same test for a packet of rays that share an
origin (:mod:`core.image_order.kernels.bvh_packet`): one test of a node for
all of them, never missing a box that one of them would enter.
:func:`slab_rays_mask` turns the vector the other way: one box, the sixteen
rays of a packet (from one origin or not), each lane computing exactly what
:func:`slab_test4` computes for that ray and that box; :func:`slab_half_mask`
is the same for half a packet.  :func:`slab_cone_mask4` is the interval test
for the shadow rays of neighbouring points to one light, which share no
origin: the rays from the light back to their origins do, and their cone,
its boxes grown a little, holds every ray's segment.
"""

from __future__ import annotations

import math

from llvmlite import ir
from numba import types
from numba.extending import intrinsic

from core.image_order.kernels.intrinsics.simd import F64, FOUR_F32, FOUR_F64, constant, lanes, load, splat


@intrinsic
def slab_test4(typingctx, rows, near_x, near_y, near_z, far_x, far_y, far_z, ox, oy, oz, ix, iy, iz,
               t_min, t_max):
    """Entry distances of the ray into four boxes, ``inf`` where it misses one.

    Parameters
    ----------
    rows : 1-D float32 array of the wide nodes, flattened.
    near_x ... far_z : int
        Flat indices of the rows holding the four boxes' near and far sides
        per axis (``lo`` is near where the direction is positive, ``hi``
        where it is negative).
    ox, oy, oz : float, the ray origin; ``ix, iy, iz`` : ``1 / d``.
    t_min, t_max : float, the part of the ray that counts.

    Returns
    -------
    (t0, t1, t2, t3) : floats, where the ray enters each box in ``[t_min, t_max]``.
    """
    signature = types.UniTuple(types.float64, 4)(rows, near_x, near_y, near_z, far_x, far_y, far_z, ox, oy,
                                                 oz, ix, iy, iz, t_min, t_max)

    def codegen(context, builder, sig, args):
        return lanes(context, builder, sig.return_type, _one_ray_entries(context, builder, sig, args))

    return signature, codegen


def _one_ray_entries(context, builder, sig, args):
    """The four entries of :func:`slab_test4` and :func:`slab_mask4` (same arguments) as one vector."""
    def near_and_far(distance, axis):
        inverse = splat(builder, args[10 + axis])
        return (builder.fmul(distance(1 + axis), inverse), builder.fmul(distance(4 + axis), inverse))

    return _entries(builder, _box_sides(context, builder, sig, args, near_and_far), splat(builder, args[13]),
                    splat(builder, args[14]))


@intrinsic
def slab_mask4(typingctx, rows, near_x, near_y, near_z, far_x, far_y, far_z, ox, oy, oz, ix, iy, iz, t_min,
               t_max):
    """Which of the four boxes the ray enters, as :func:`slab_test4` decides it: bit ``c`` of the
    result is set where its entry into box ``c`` is finite (an any-hit walk needs no more)."""
    signature = types.int64(rows, near_x, near_y, near_z, far_x, far_y, far_z, ox, oy, oz, ix, iy, iz, t_min,
                            t_max)

    def codegen(context, builder, sig, args):
        return _mask(builder, _one_ray_entries(context, builder, sig, args))

    return signature, codegen


@intrinsic
def slab_interval4(typingctx, rows, near_x, near_y, near_z, far_x, far_y, far_z, ox, oy, oz, ax, ay, az,
                   bx, by, bz, t_min, t_max):
    """For a packet of rays from one origin: a lower bound of where any of them enters each of four
    boxes, ``inf`` where none can enter one.

    The rays' ``1 / d`` lie between ``(ax, ay, az)`` and ``(bx, by, bz)``, one sign per axis
    for all of them, and their admissible parts of ``t`` inside ``[t_min, t_max]``.  Per axis
    the test takes the smaller of the two slab distances ``(side - o) * a`` and ``(side - o) * b``
    for the near side and the larger for the far side.  Rounding is monotonic, so each ray's own
    rounded distance (:func:`slab_test4`, the same subtraction, a multiplier in between) lies
    between the two: a ray that would enter a box by its own test makes this test enter it too.
    """
    signature = types.UniTuple(types.float64, 4)(rows, near_x, near_y, near_z, far_x, far_y, far_z, ox, oy,
                                                 oz, ax, ay, az, bx, by, bz, t_min, t_max)

    def codegen(context, builder, sig, args):
        entry = _interval_entries(context, builder, sig, args[:10] + args[7:])
        return lanes(context, builder, sig.return_type, entry)

    return signature, codegen


@intrinsic
def slab_cone_mask4(typingctx, rows, near_x, near_y, near_z, far_x, far_y, far_z, nx, ny, nz, fx, fy, fz,
                    ax, ay, az, bx, by, bz, t_min, t_max):
    """Which of four boxes, each grown by a margin on every side, a cone of rays from one apex may
    enter: :func:`slab_interval4` with the near sides' distances taken from ``(nx, ny, nz)`` and
    the far sides' from ``(fx, fy, fz)``, the apex moved away from the near sides and towards the
    far ones by the margin (:func:`~core.image_order.kernels.bvh_packet._cone`).  Bit ``c`` of
    the result is set where box ``c`` may be entered."""
    signature = types.int64(rows, near_x, near_y, near_z, far_x, far_y, far_z, nx, ny, nz, fx, fy, fz, ax,
                            ay, az, bx, by, bz, t_min, t_max)

    def codegen(context, builder, sig, args):
        return _mask(builder, _interval_entries(context, builder, sig, args))

    return signature, codegen


def _interval_entries(context, builder, sig, args):
    """:func:`slab_interval4`'s four entries as one vector, from ``args``: the rows and the six
    indices, the origin of the near sides' and of the far sides' distances, ``a``, ``b``, ``t_min``
    and ``t_max``."""
    data = context.make_array(sig.args[0])(context, builder, args[0]).data

    def distance(k, origin):
        side = builder.fpext(load(builder, data, args[k], FOUR_F32), FOUR_F64)
        return builder.fsub(side, splat(builder, args[origin]))

    def near_and_far(axis):
        low, high = splat(builder, args[13 + axis]), splat(builder, args[16 + axis])
        near, far = distance(1 + axis, 7 + axis), distance(4 + axis, 10 + axis)
        near_a, near_b = builder.fmul(near, low), builder.fmul(near, high)
        far_a, far_b = builder.fmul(far, low), builder.fmul(far, high)
        return (builder.select(builder.fcmp_ordered("<", near_a, near_b), near_a, near_b),
                builder.select(builder.fcmp_ordered(">", far_a, far_b), far_a, far_b))

    return _entries(builder, near_and_far, splat(builder, args[19]), splat(builder, args[20]))


def _mask(builder, entry):
    """Bit ``c`` set where entry ``c`` of the four is finite."""
    entered = builder.bitcast(builder.fcmp_ordered("<", entry, constant(math.inf)), ir.IntType(4))
    return builder.zext(entered, ir.IntType(64))


#: Rays of :func:`slab_rays_mask` (a packet of 4 x 4), and of :func:`slab_half_mask`.
RAYS = 16
HALF = RAYS // 2


@intrinsic
def slab_rays_mask(typingctx, rows, near_x, near_y, near_z, far_x, far_y, far_z, rays, ox_at, oy_at, oz_at,
                   ix_at, iy_at, iz_at, t_min_at, t_max_at, below_at):
    """Which of ``RAYS`` rays enter one box: bit ``r`` set where ray ``r``'s :func:`slab_test4`
    entry into the box is finite and below its bound at ``below_at``.

    Parameters
    ----------
    rows, near_x ... far_z : as for :func:`slab_test4`, but each index names the one number of
        the one box (a single float32), the same side for all the rays (their signs agree).
    rays : 1-D float64 array; ``ox_at, oy_at, oz_at`` the flat indices of the rays' origins per
        axis, ``ix_at, iy_at, iz_at`` of their ``1 / d``, ``t_min_at, t_max_at`` of their
        admissible ranges of ``t`` and ``below_at`` of the bounds the entry must lie below,
        ``RAYS`` numbers side by side at each.  A closest-hit walk bounds the entry by the
        closest hit so far (its ``t_max``), as its lone walk drops a box entered there; an
        any-hit walk by ``inf``, as :func:`slab_mask4` keeps a box entered at ``t_max``.

    Returns
    -------
    int64 : the mask; lane ``r`` computes bit for bit :func:`slab_test4`'s entry of ray ``r``.
    The caller then visits only the rays whose bit is set, in a loop with no branch per ray (a
    packet of the 1,000,000-triangle benchmark meets about 22 leaf boxes, and each of its rays
    enters about 6 of them).
    """
    signature = types.int64(rows, near_x, near_y, near_z, far_x, far_y, far_z, rays, ox_at, oy_at, oz_at,
                            ix_at, iy_at, iz_at, t_min_at, t_max_at, below_at)
    return signature, _rays_mask(RAYS)


@intrinsic
def slab_half_mask(typingctx, rows, near_x, near_y, near_z, far_x, far_y, far_z, rays, ox_at, oy_at, oz_at,
                   ix_at, iy_at, iz_at, t_min_at, t_max_at, below_at):
    """:func:`slab_rays_mask` for ``HALF`` rays, the ones whose numbers start at the given flat
    indices (half a packet: an any-hit walk where only one half of the packet's rays still
    entered the node pays for the test of those alone)."""
    signature = types.int64(rows, near_x, near_y, near_z, far_x, far_y, far_z, rays, ox_at, oy_at, oz_at,
                            ix_at, iy_at, iz_at, t_min_at, t_max_at, below_at)
    return signature, _rays_mask(HALF)


def _rays_mask(width):
    """The code of :func:`slab_rays_mask` for ``width`` rays."""
    vector = ir.VectorType(F64, width)

    def codegen(context, builder, sig, args):
        data = context.make_array(sig.args[0])(context, builder, args[0]).data
        per_ray = context.make_array(sig.args[7])(context, builder, args[7]).data

        def row(at):
            pointer = builder.bitcast(builder.gep(per_ray, [at]), vector.as_pointer())
            return builder.load(pointer, align=8)

        def distance(k):  # the one side minus each ray's origin: slab_test4's subtraction
            side = builder.fpext(builder.load(builder.gep(data, [args[k]])), F64)
            return builder.fsub(splat(builder, side, width), row(args[8 + (k - 1) % 3]))

        enter, leave = row(args[14]), row(args[15])
        for axis in range(3):
            inverse = row(args[11 + axis])
            t_near = builder.fmul(distance(1 + axis), inverse)
            t_far = builder.fmul(distance(4 + axis), inverse)
            enter = builder.select(builder.fcmp_ordered(">", t_near, enter), t_near, enter)
            leave = builder.select(builder.fcmp_ordered("<", t_far, leave), t_far, leave)
        entered = builder.and_(builder.fcmp_ordered("<=", enter, leave),
                               builder.fcmp_ordered("<", enter, row(args[16])))
        return builder.zext(builder.bitcast(entered, ir.IntType(width)), ir.IntType(64))

    return codegen


def _box_sides(context, builder, sig, args, near_and_far):
    """``near_and_far(axis)`` for the four boxes of a node, given ``near_and_far(distance, axis)``
    on ``distance(k)`` (side ``args[k]`` minus the origin's coordinate, four lanes)."""
    data = context.make_array(sig.args[0])(context, builder, args[0]).data

    def distance(k):
        side = builder.fpext(load(builder, data, args[k], FOUR_F32), FOUR_F64)
        return builder.fsub(side, splat(builder, args[7 + (k - 1) % 3]))

    return lambda axis: near_and_far(distance, axis)


def _entries(builder, near_and_far, enter, leave):
    """The four entries as one vector, given ``near_and_far(axis)``, the four lanes' slab distances
    of an axis, and the four lanes' admissible range ``enter, leave``."""
    for axis in range(3):
        t_near, t_far = near_and_far(axis)
        enter = builder.select(builder.fcmp_ordered(">", t_near, enter), t_near, enter)
        leave = builder.select(builder.fcmp_ordered("<", t_far, leave), t_far, leave)
    return builder.select(builder.fcmp_ordered("<=", enter, leave), enter, constant(math.inf))
