"""How the tracer's inputs and per-hit records are laid out in flat float64 arrays.

Compiled kernels take plain arrays, so every structured value the tracer
needs (a material, a light, the camera, the settings, a closest hit, the
record of one shaded hit, the work counters) is a row of numbers.  The
column names live here, once, for both the Python side that fills and reads
them and the kernels that use them.
"""

from __future__ import annotations

from core.compiling.jitable import jitable

# --- materials: (O, MAT_SIZE), one row per scene object ----------------------------------
MAT_COLOR = 0  # 3 columns, RGB
MAT_REFLECTIVITY = 3
MAT_TRANSPARENCY = 4
MAT_IOR = 5
MAT_AMBIENT = 6
MAT_DIFFUSE = 7
MAT_SPECULAR = 8
MAT_SHININESS = 9
MAT_SIZE = 10

# --- lights: (L, LIGHT_SIZE + O * RECEIVER_SIZE), O the scene's objects ----------------------
LIGHT_POSITION = 0  # 3 columns, world space
LIGHT_RGB = 3  # 3 columns, colour times intensity
LIGHT_BLOCKABLE = 6  # 1.0 when something might cast a shadow from it (see core.image_order.effects_plan)
LIGHT_SIZE = 7
# Then RECEIVER_SIZE columns per object, as a receiver of shadows from this light: how many objects
# may shadow it (BLOCKERS_UNKNOWN: not worked out, a shadow ray searches the whole scene), and
# their indices (effects_plan's LightPlan.blockers).
RECEIVER_SIZE = 8
BLOCKERS_UNKNOWN = -1

# --- camera: (CAM_SIZE,) -----------------------------------------------------------------
CAM_EYE = 0  # 3
CAM_ROTATION = 3  # 9, world_from_view[:3, :3] row by row
CAM_FORWARD = 12  # 3, unit viewing direction
CAM_HALF_WIDTH = 15  # half extent of the image at distance 1 (perspective) or absolute (ortho)
CAM_HALF_HEIGHT = 16
CAM_WIDTH = 17  # pixels
CAM_HEIGHT = 18
CAM_ORTHOGRAPHIC = 19  # 1.0 for parallel projection
CAM_NEAR = 20
CAM_FAR = 21
CAM_SIZE = 22

# --- options: (OPT_SIZE,) ----------------------------------------------------------------
OPT_ACCEL = 0  # index into ACCEL_CODES
OPT_MAX_DEPTH = 1
OPT_MIN_WEIGHT = 2
OPT_SCALED_OFFSET = 3  # 1.0: pbrt-style offset; 0.0: fixed epsilon
OPT_EPSILON = 4
OPT_REFLECTION = 5  # 1.0 when reflection rays may be traced (mode and effects plan)
OPT_REFRACTION = 6
OPT_BACKGROUND = 7  # 3, RGB
OPT_PACKETS = 10  # 1.0: primary rays walk the BVH in packets (core.image_order.bvh.Bvh.packets_pay)
OPT_STOP = 11  # raised (1.0) by another thread while the render runs: stop now (core.stopping)
OPT_SIZE = 12

#: Acceleration method names in the order of their codes in ``OPT_ACCEL``.
ACCEL_CODES = ("none", "spheres", "grid", "grid+spheres", "bvh")

# --- the closest hit of a ray: ``(prim, t, b0, b1, b2)`` as the kernels return it, and one row
# of the render's hits array (ny, nx, HIT_SIZE) ------------------------------------------------
HIT_PRIM = 0  # primitive index (see core.image_order.kernels.primitives), -1: nothing hit
HIT_T = 1  # ray parameter of the crossing
HIT_B0, HIT_B1, HIT_B2 = 2, 3, 4  # a triangle's barycentric weights of its corners A, B, C
HIT_SIZE = 5

# --- primitives: (P, ROW_SIZE), see core.image_order.kernels.primitives ----------------------
ROW_CENTER = 0  # a sphere: 3 columns, its centre, world space
ROW_RADIUS = 3  # and its radius (the rest of the row is 0)
ROW_A, ROW_B, ROW_C = 0, 3, 6  # a triangle: 3 columns per corner, world space
ROW_SIZE = 9

# --- the kernel tuples: positions in core.image_order.flat_scene.Geometry.kernel_tuple() ------
GEO_ROWS = 0  # (P, 9) primitive rows
GEO_N_SPHERES = 1  # primitives below this index are analytic spheres
GEO_PRIM_OBJECT = 2  # (P,) object of each primitive
GEO_OBJECT_PRIMS = 3  # (O, 2) first primitive and count per object
GEO_BOUNDING = 4  # (O, 4) bounding sphere per object
GEO_NORMALS = 5  # (T, 3) outward unit normal per triangle
GEO_MAGNITUDE = 6  # (P,) largest coordinate magnitude per primitive
# ... and in the per-thread scratch of core.image_order.kernels.render.make_scratch
SCRATCH_GRID = 4  # the first four: the grid walk's mailbox, object stamps, object spans, stamp
SCRATCH_STACK = 4  # the BVH traversal's stack of nodes
SCRATCH_STACK_T = 5  # and the distances where the ray enters them

# --- work counters: (N_COUNTERS,) int64, one array per thread ------------------------------
PRIMARY, SHADOW, REFLECTION, REFRACTION = 0, 1, 2, 3  # rays traced, by kind
PRIM_TESTS = 4  # ray-primitive tests
BOUNDS_TESTS = 5  # bounding-sphere or box tests
CELLS = 6  # grid cells walked
N_COUNTERS = 7

# --- heat map: (ny, nx, HEAT_SIZE) int64, the work of each pixel's rays (optional) ---------------
HEAT_PRIM_TESTS = 0  # ray-primitive tests of all the pixel's rays
HEAT_BOUNDS_TESTS = 1  # their bounding-sphere, BVH-box and grid-cell tests (each cuboid a ray enters)
HEAT_SIZE = 2

# --- the rays a hit spawns: the render's children array (ny, nx, N_SPAWNED, CHILD_SIZE) --------
SPAWN_REFLECT, SPAWN_REFRACT = 0, 1
N_SPAWNED = 2

# --- the record of one hit, written by core.image_order.kernels.shade.shade_hit ----------------
REC_PRIM = 0
REC_OBJECT = 1
REC_T = 2
REC_POINT = 3  # 3
REC_NORMAL = 6  # 3, unit, facing the incoming ray
REC_FRONT = 9  # 1.0 when the ray arrives from outside (against the outward normal)
REC_W_LOCAL = 10  # share of ambient + diffuse light that is the surface's own colour
REC_AMBIENT = 11  # 3, w_local k_a C
REC_LOCAL = 14  # 3, the local colour (Phong with the unblocked lights)
REC_FRESNEL_R = 17  # reflectance R, NaN when no Fresnel term was needed
REC_FRESNEL_T = 18  # transmittance T, NaN likewise
REC_TIR = 19  # 1.0 at total internal reflection
REC_K_REFLECT = 20  # coefficient of the reflected ray's colour
REC_K_REFRACT = 21  # coefficient of the refracted ray's colour
REC_REFLECT = 22  # CHILD_SIZE columns
REC_REFRACT = 30  # CHILD_SIZE columns
REC_LIGHTS = 38  # LIGHT_REC_SIZE columns per light
# A child ray: origin (3), direction (3), weight in the pixel, status.
CHILD_ORIGIN = 0
CHILD_DIRECTION = 3
CHILD_WEIGHT = 6
CHILD_STATUS = 7
CHILD_SIZE = 8
CHILD_NONE, CHILD_TRACED, CHILD_DEPTH_LIMIT, CHILD_TOO_WEAK = 0, 1, 2, 3
# A light seen from the hit point: status, shadow ray origin (3), direction (3), distance
# to the light, blocker (prim, t), the light's contribution to the local colour (3).
LR_STATUS = 0
LR_ORIGIN = 1
LR_DIRECTION = 4
LR_DISTANCE = 7
LR_BLOCKER = 8
LR_BLOCKER_T = 9
LR_CONTRIBUTION = 10
LIGHT_REC_SIZE = 13
LIGHT_BEHIND, LIGHT_UNBLOCKABLE, LIGHT_REACHED, LIGHT_BLOCKED = 0, 1, 2, 3

# --- a secondary ray waiting on the render's stack: a child ray, then its generation and kind --
STACK_GENERATION = CHILD_SIZE
STACK_KIND = CHILD_SIZE + 1  # SPAWN_REFLECT or SPAWN_REFRACT
STACK_SIZE = CHILD_SIZE + 2


@jitable
def record_size(n_lights: int) -> int:
    """Length of a hit record for a scene with ``n_lights`` lights."""
    return REC_LIGHTS + LIGHT_REC_SIZE * n_lights
