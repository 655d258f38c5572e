"""Why each knob's curve has its shape, in a sentence or two of our own words.

Their claims that a computation can decide are worked out in tests/core/accuracy/test_explanations.py.
"""

from __future__ import annotations

EXPLANATIONS: dict[str, str] = {
    "spp": (
        "Each step multiplies the rays (or raster passes) by four, so time grows as N squared, while the "
        "error lives only in the pixels an edge crosses and falls roughly as 1/N: the first step removes "
        "the staircase, later ones buy less and less."
    ),
    "adaptive": (
        "Most pixels lie inside one surface, where the four corners agree and one sample's worth of work "
        "is enough; only pixels on an edge or a sharp highlight get the full grid, so it reaches nearly "
        "the uniform 4x4 error for a fraction of the rays.  A lower threshold refines more pixels."
    ),
    "depth": (
        "Every generation follows the reflected and refracted rays of the last one, but each carries "
        "only its share of the light; with one mirror and one glass ball, rays beyond depth 3 add "
        "almost nothing visible, and a scene without mirrors or glass never spawns them at all."
    ),
    "min-weight": (
        "A ray whose weight in the pixel is below the threshold is not traced; raising it prunes the "
        "faint deep branches of the ray tree first, so the image barely changes until the threshold "
        "starts cutting rays that carry a visible share of the light."
    ),
    "resolution": (
        "Time grows with the number of pixels; a smaller image, shown at the reference size, blurs "
        "and shifts every edge, while a larger one averaged down is supersampling by another name."
    ),
    "tessellation": (
        "A sphere made of triangles has a polygonal silhouette and flat facets; doubling rings and "
        "segments quarters both the silhouette and depth error but quadruples the triangles, and once "
        "the facets are smaller than a pixel nobody can see the difference."
    ),
    "accel": (
        "Bounding spheres, the grid of cuboids and the BVH only skip ray-object tests that cannot "
        "hit; every method finds exactly the same hits, so the error is exactly 0 and only the time "
        "changes (small scenes can even be slower, as building and walking the structure costs more "
        "than it saves)."
    ),
    "depth-format": (
        "Window depth is hyperbolic in distance, so it crowds near 1 for everything far from the "
        "near plane, and moving the near plane closer crowds it more.  With the far plane 100 units "
        "away and the near plane at 0.1 (1:1000), a tenth of a unit in depth 50 units away is only "
        "about a quarter of one of 16-bit depth's 65536 steps, so "
        "two surfaces that close share a stored depth and fight pixel by pixel; 24 bits and floats "
        "have the steps to spare, and reversed-Z puts the float's finest steps where depth crowds.  "
        "A scene whose surfaces are never close in depth shows no fighting at all: the formats then "
        "differ only in bytes per pixel."
    ),
}
