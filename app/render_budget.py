"""The window's memory budget: every tab's render is checked before it starts.

A rendering tab says what its job will cost (``tab.cost(scene, preview)``, a
:class:`core.budget.Estimate` of the renders it makes and the images it
shows).  A job over the budget (half of the memory available when it would
start, or the window's ``--memory-limit``) never starts: the tab says what it
would need and what to reduce, and the window stays as it was.  A full render
estimated to take long is announced before it starts.
"""

from __future__ import annotations

from core import budget

#: What to reduce, after the part of the estimate that takes the most memory.
ADVICE = {
    "image buffers": "choose a smaller Image size (under Lens and frustum)",
    "shown images": "choose a smaller Image size (under Lens and frustum)",
    "triangles": "use fewer objects or triangles (a coarser tessellation)",
}


def check(tab, scene, preview: bool, memory_limit: int | None) -> tuple[str | None, str | None]:
    """``(refusal, warning)`` for ``tab``'s job on ``scene``: why it must not start, or a word before
    a long one.

    Both are ``None`` for a tab without ``cost`` (it renders nothing of the scene's size).
    """
    if not hasattr(tab, "cost"):
        return None, None
    cost = tab.cost(scene, preview)
    cam = scene.camera
    n = len(scene.objects)
    what = (f"{tab.title}{' preview' if preview else ''}: the {cam.width} × {cam.height} image of "
            f"{n:,} object{'s' * (n != 1)}")
    over = budget.refusal(what, cost, *budget.memory_limit(memory_limit, "the window's --memory-limit"))
    if over:
        return f"{over}. Not rendered: {ADVICE[budget.largest_part(cost)]}.", None
    if not preview and cost.seconds > budget.SLOW_SECONDS:
        return None, (f"{tab.title}: estimated about {budget.format_seconds(cost.seconds)} and "
                      f"{budget.format_bytes(cost.bytes)} of memory (Esc cancels)")
    return None, None


def refusals(tabs, scene, memory_limit: int | None) -> dict[str, str]:
    """Tab title -> why its full render of ``scene`` is refused, for every tab that refuses it."""
    found = {}
    for tab in tabs:
        refusal, _ = check(tab, scene, False, memory_limit)
        if refusal:
            found[tab.title] = refusal
    return found
