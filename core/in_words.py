"""Lists and counts written as a sentence writes them: the names in the explanations the window and
the command line give ("cube, cone and ground may shadow ...", "lit by light 0 and light 1"), and
how many of a thing ("1 fragment", "12,500 fragments")."""

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


def counted(n: int, noun: str) -> str:
    """``n`` and ``noun``, plural unless ``n`` is one, with thousands separated.

    >>> counted(1, "fragment"), counted(12500, "fragment"), counted(0, "ray")
    ('1 fragment', '12,500 fragments', '0 rays')
    """
    return f"{n:,} {noun}" if n == 1 else f"{n:,} {noun}s"
