"""Lists written as a sentence writes them: the names in the explanations the window and the
command line give ("cube, cone and ground may shadow ...", "lit by light 0 and light 1")."""

from __future__ import annotations


def listed(names, most: int | None = None) -> str:
    """``a``, ``a and b``, ``a, b and c``: each name once, in order; past ``most`` names, the first
    ``most`` and how many more.

    >>> listed(["cube"]), listed(["cube", "cone", "cube"]), listed(["a", "b", "c"])
    ('cube', 'cube and cone', 'a, b and c')
    >>> listed(["a", "b", "c", "d", "e", "f"], most=4)
    'a, b, c, d and 2 more'
    """
    names = list(dict.fromkeys(names))
    if most is not None and len(names) > most:
        names = names[:most] + [f"{len(names) - most} more"]
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]
