"""The monodromy of one body as plain data, for the build's worker processes (paper: Conclusion, eq:whole).

``derivations/sections/fuchsian.py`` certifies the Galois group of representative bodies from
:func:`suslov.validated.monodromy` (validated Taylor steps along complex loops in x = e^t, python-flint
balls; the method is in ``suslov/kernel/fuchsian_flow.py`` and ``suslov/kernel/monodromy.py``).  That
computation needs no other result, so a cold build starts it in worker processes before the symbolic
derivations (``PREFETCH``).  It lives here, apart from the derivation, because this module imports
neither SymPy nor the derivations' symbolic core: a spawned worker that only runs it starts in about
0.2 s instead of 1 s (balls do not pickle, hence the plain-data summary).
"""
from __future__ import annotations

from flint import acb_mat

from derivations.core.certificates import stopwatch


def _math(value) -> str:
    """A ball's midpoint to 4 digits as LaTeX mathematics (python-flint prints ``1.000j``)."""
    text = value.str(4, radius=False).replace(" ", "")
    return text.replace("j", "i")


def monodromy_summary(item: tuple) -> dict:
    """The run-time :func:`suslov.validated.monodromy` of one body at ``digits``, ``item = ((I11, I22, I13, I23),
    digits)``, as plain data (balls do not pickle): verdict, certificates, the table's entries, and whether the
    loop about x = i excludes the identity.  A top-level function: the build runs it in a worker process,
    started before the symbolic derivations (``PREFETCH``)."""
    from suslov.validated import monodromy  # python-flint balls; the run-time code, exactly as users call it

    body, digits = item
    with stopwatch() as elapsed:
        mono = monodromy(*body, dps=digits)
    identity = acb_mat([[1, 0, 0], [0, 1, 0], [0, 0, 1]])
    at_i = mono.matrices.get("x=i")
    return {"verdict": mono.verdict, "liouvillian": mono.liouvillian, "radius": mono.radius,
            "digits": mono.digits + mono.guard, "certificates": [tuple(c) for c in mono.certificates],
            "exponents": {name: _math(mono.exponents[name][1]) for name in ("x=0", "x=i")},
            "not_identity_at_i": at_i is not None and any(not (at_i[r, c] - identity[r, c]).contains(0)
                                                          for r in range(3) for c in range(3)),
            "re_trace_at_i": at_i.trace().real.str(10, radius=False) if at_i is not None else "",
            "seconds": elapsed[0]}
