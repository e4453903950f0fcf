"""The figures of the formulas document, computed here and drawn by LaTeX's own ``picture`` environment (issue 46).

Three figures, in the section "Figures" of ``suslov_formulas.tex`` (``templates/figures.tex.j2`` draws them;
``generated/figures.tex``):

* **angle** -- the scattering angle of Theorem 5.4 over ``p`` for ``d = 1/2, 1, 2, 4`` (case ``I13 = 0``), drawn
  by the build's emitted ``_scattering_angle`` through the run-time route of the module's
  ``scattering_angle`` (float64, proven error bound 1.5e-14), the odd ``p`` (Liouvillian; there
  ``Delta psi = pi`` for every ``d``) marked by squares;
* **general_angle** -- the scattering angle of every body over the entry ``I23`` for ``(I11, I22) = (5, 1)`` and
  ``I13 = 0, 1/10, 1/2``, by the emitted ``_gauss_invariants`` and ``_general_angle`` through the route of
  ``general_scattering_angle``; on ``I13 = 0`` it is the curve ``d = 2`` of the first figure, with ``p = -2/I23``;
* **decisions** -- the exact decisions of :func:`suslov.validated.galois_group` and
  :func:`suslov.validated.local_behaviour` for the bodies ``(5, 1, I13, -2/xi)``, ``xi = j/8`` (``j = 1..64``),
  on the rows ``I13 = 0, 1/10, 1/2`` (``xi = p`` on the row ``I13 = 0``): one cell per body, coloured by the pair
  (group, behaviour), which the two theorems make one of three; another pair is an error.

The emitted functions are the text the build writes into ``suslov_formulas.py`` (and certifies by its round
trip), executed here from that text; the curves are sampled adaptively (midpoints inserted until consecutive
points are at most :data:`GAP` apart on the page), thinned to dots still at most :data:`GAP` apart and rounded
to 0.1 pt, so the figure file is the same bytes at every build (a float64 value would have to fall within
about 1e-14 of a rounding boundary of 0.1 pt to differ between machines).  Cost: some 40 ms in all (the 192 exact
decisions 15 ms of it), computed once per process (:func:`functools.lru_cache`).

Why ``picture``: the CI installs only ``texlive-latex-base`` (``picture``, ``color``; no TikZ, pgfplots or
pict2e) and the build has no matplotlib.  ``picture`` draws only rules and a few slopes of lines, so the axes,
ticks, frames and map cells are rules and a curve is a row of small square dots; nothing is drawn with a font
(the circle and arrow fonts would put glyphs into the PDF's text).
"""
from __future__ import annotations

import functools
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from derivations.output.tree import FIGURES_NEEDS as NEEDS  # noqa: F401 - the derivations the figures draw
from suslov.runtime import angle as _angle
from suslov.runtime import general_angle as _general

WIDTH, HEIGHT = 300.0, 130.0   # the plot area of a curve figure, pt
GAP = 1.8                      # largest distance of consecutive samples, and of consecutive dots, on the page (pt)
PER_LINE = 8                   # dots per line of the figure file

ANGLE_D = (Fraction(1, 2), Fraction(1), Fraction(2), Fraction(4))
ANGLE_P = (0.0, 6.0)
BODY = (Fraction(5), Fraction(1))                    # (I11, I22) of the general-body figures: d = 2
GENERAL_I13 = (Fraction(0), Fraction(1, 10), Fraction(1, 2))
GENERAL_I23 = (-4.0, -0.25)
MAP_XI = tuple(Fraction(j, 8) for j in range(1, 65))   # I23 = -2/xi
COLOURS = ("figblue", "figred", "figgreen", "figblack")

# the pair (Galois group, behaviour at the poles) -> (colour, legend)
CLASSES = {
    ("reducible", "meromorphic"): ("figgreen", r"$\mathrm{Gal}=\mathrm{SO}(2,\mathbb C)$, meromorphic (Liouvillian)"),
    ("SO(3,C)", "logarithmic"): ("figorange", r"$\mathrm{SO}(3,\mathbb C)$, logarithms"),
    ("SO(3,C)", "branching"): ("figgrey", r"$\mathrm{SO}(3,\mathbb C)$, branching"),
}


@dataclass(frozen=True)
class Curve:
    label: str                 # TeX of the legend
    colour: str                # a colour of the preamble
    x: tuple                   # the data: abscissae and values drawn (floats)
    y: tuple
    lines: tuple               # the dots, ``\figdot(X,Y)`` in pt, PER_LINE to a line


@dataclass(frozen=True)
class Figure:
    key: str
    width: float               # the plot area (pt)
    height: float
    xticks: tuple              # (position, TeX label)
    yticks: tuple
    xlabel: str
    ylabel: str
    curves: tuple = ()
    markers: tuple = ()        # lower-left corners "X,Y" of the marker squares
    cells: tuple = ()          # ("X,Y" lower-left corner, width, height, colour) of each map cell
    rows: tuple = ()           # (Y, TeX label) of the map's rows
    legend: tuple = ()         # (colour, TeX) of the map's legend
    formulas: tuple = ()       # keys of the formulas drawn
    certificates: tuple = ()   # keys of their certificates


def emitted_function(source: str):
    """The emitted function ``def _name(ctx, ...)`` from its text (what ``suslov_formulas.py`` holds)."""
    namespace: dict = {}
    exec(compile(source, "<emitted>", "exec"), namespace)   # noqa: S102 (the build's own certified text)
    functions = [v for k, v in namespace.items() if k.startswith("_") and callable(v) and not k.startswith("__")]
    if len(functions) != 1:
        raise ValueError("an emitted text defines exactly one function")
    return functions[0]


def _fmt(v: float) -> str:
    text = f"{round(v, 1):.1f}"
    return "0.0" if text == "-0.0" else text


def _sample(f, lo: float, hi: float, page, n: int = 97, rounds: int = 14) -> tuple[np.ndarray, np.ndarray]:
    """``(x, f(x))`` on ``[lo, hi]``: ``n`` equidistant points, then midpoints where consecutive points are more
    than :data:`GAP` apart on the page (``page(x, y) -> (X, Y)``), up to ``rounds`` times."""
    xs = np.linspace(lo, hi, n)
    ys = np.asarray(f(xs), dtype=float)
    for _ in range(rounds):
        X, Y = page(xs, ys)
        far = np.hypot(np.diff(X), np.diff(Y)) > GAP
        if not far.any():
            break
        mids = (xs[:-1][far] + xs[1:][far]) / 2
        order = np.argsort(np.concatenate([xs, mids]), kind="stable")
        xs = np.concatenate([xs, mids])[order]
        ys = np.concatenate([ys, np.asarray(f(mids), dtype=float)])[order]
    return xs, ys


def _curve(label: str, colour: str, xs, ys, page) -> Curve:
    """The dots of a sampled curve: a sample is left out where the dots on either side of it are still at most
    :data:`GAP` apart, so consecutive dots are never further apart than the samples allowed (the ends kept)."""
    X, Y = page(np.asarray(xs), np.asarray(ys))
    keep = [0]
    for k in range(1, len(X) - 1):
        if np.hypot(X[k + 1] - X[keep[-1]], Y[k + 1] - Y[keep[-1]]) > GAP:
            keep.append(k)
    keep.append(len(X) - 1)
    drawn = {}                 # one dot per rounded position (the last point may round onto the one before)
    for k in keep:
        drawn.setdefault(f"\\figdot({_fmt(X[k])},{_fmt(Y[k])})", k)
    dots = list(drawn)
    lines = tuple("".join(dots[i:i + PER_LINE]) for i in range(0, len(dots), PER_LINE))
    return Curve(label, colour, tuple(float(xs[k]) for k in drawn.values()),
                 tuple(float(ys[k]) for k in drawn.values()), lines)


def _scaler(x0: float, x1: float, y0: float, y1: float, width: float = WIDTH, height: float = HEIGHT):
    return lambda x, y: ((np.asarray(x) - x0) / (x1 - x0) * width, (np.asarray(y) - y0) / (y1 - y0) * height)


_PI_TICKS = ((0.0, "0"), (HEIGHT / 2, r"\pi/2"), (HEIGHT, r"\pi"))


@functools.lru_cache(maxsize=4)
def angle_figure(source: str, certificates: tuple = (), formulas: tuple = ()) -> Figure:
    """Theorem 5.4 over ``p`` for the ``d`` of :data:`ANGLE_D`, by the emitted ``_scattering_angle`` (its text)."""
    emitted = emitted_function(source)
    page = _scaler(*ANGLE_P, 0.0, np.pi)
    curves = []
    for d, colour in zip(ANGLE_D, COLOURS):
        xs, ys = _sample(lambda p, d=float(d): _angle.scattering_angle(emitted, p, d), *ANGLE_P, page)
        curves.append(_curve(f"d={d}", colour, xs, ys, page))
    odd = np.arange(1.0, ANGLE_P[1], 2.0)
    X, Y = page(odd, _angle.scattering_angle(emitted, odd, 1.0))
    markers = tuple(f"{_fmt(a - 2)},{_fmt(b - 2)}" for a, b in zip(X, Y))
    xticks = tuple((_fmt(page(p, 0.0)[0]), str(int(p))) for p in np.arange(ANGLE_P[0], ANGLE_P[1] + 1))
    return Figure("angle", WIDTH, HEIGHT, xticks, _PI_TICKS, "p", r"\Delta\psi", tuple(curves), markers,
                  formulas=formulas, certificates=certificates)


@functools.lru_cache(maxsize=4)
def general_angle_figure(invariants_source: str, angle_source: str, certificates: tuple = (),
                         formulas: tuple = ()) -> Figure:
    """The angle of every body over ``I23`` for the bodies ``(5, 1, I13, I23)``, ``I13`` of :data:`GENERAL_I13`."""
    invariants, emitted = emitted_function(invariants_source), emitted_function(angle_source)
    page = _scaler(GENERAL_I23[0], 0.0, 0.0, np.pi)
    curves = []
    for I13, colour in zip(GENERAL_I13, COLOURS):
        body = (float(BODY[0]), float(BODY[1]), float(I13))
        xs, ys = _sample(lambda I23, b=body: _general.general_scattering_angle(invariants, emitted, *b, I23),
                         *GENERAL_I23, page)
        curves.append(_curve(f"I_{{13}}={I13}", colour, xs, ys, page))
    odd = -2.0 / np.array([p for p in (1.0, 3.0, 5.0, 7.0) if -2.0 / p >= GENERAL_I23[0]])
    X, Y = page(odd, _general.general_scattering_angle(invariants, emitted, *map(float, BODY), 0.0, odd))
    markers = tuple(f"{_fmt(a - 2)},{_fmt(b - 2)}" for a, b in zip(X, Y))
    xticks = tuple((_fmt(page(v, 0.0)[0]), str(v)) for v in range(int(GENERAL_I23[0]), 1))
    return Figure("general_angle", WIDTH, HEIGHT, xticks, _PI_TICKS, "I_{23}", r"\Delta\psi", tuple(curves),
                  markers, formulas=formulas, certificates=certificates)


def decision(I11, I22, I13, I23) -> tuple[str, str]:
    """(group, kind) of a body, decided exactly (:mod:`suslov.validated`); the pair is one of :data:`CLASSES`."""
    # 0.2 s of imports: only when a figure is drawn, not at every import of the pipeline
    from suslov.validated import galois_group, local_behaviour

    pair = (galois_group(I11, I22, I13, I23).group, local_behaviour(I11, I22, I13, I23).kind)
    if pair not in CLASSES:
        raise ValueError(f"body {(I11, I22, I13, I23)}: Galois group {pair[0]} with behaviour {pair[1]} at the "
                         "poles: the two theorems allow no such pair")
    return pair


MAP_ROW, MAP_GAP, MAP_CELL = 16.0, 8.0, 0.8   # row height, gap between rows (pt), cell width / spacing


@functools.lru_cache(maxsize=1)
def decisions() -> tuple:
    """``(I13, xi, (group, kind))`` of every body of the map, in rows of :data:`GENERAL_I13`."""
    return tuple((I13, xi, decision(*BODY, I13, -2 / xi)) for I13 in GENERAL_I13 for xi in MAP_XI)


def decisions_figure(certificates: tuple = (), formulas: tuple = ()) -> Figure:
    """The map of exact decisions over ``xi = -2/I23`` (one cell per body) on the rows of :data:`GENERAL_I13`."""
    step = float(MAP_XI[1] - MAP_XI[0])
    x1 = float(MAP_XI[-1])
    scale = WIDTH / x1
    height = len(GENERAL_I13) * (MAP_ROW + MAP_GAP) + MAP_GAP
    row_y = {I13: height - (k + 1) * (MAP_ROW + MAP_GAP) for k, I13 in enumerate(GENERAL_I13)}
    cells = tuple((f"{_fmt((float(xi) - step * MAP_CELL / 2) * scale)},{_fmt(row_y[I13])}",
                   _fmt(step * MAP_CELL * scale), _fmt(MAP_ROW), CLASSES[pair][0]) for I13, xi, pair in decisions())
    rows = tuple((_fmt(row_y[I13] + MAP_ROW / 2), f"I_{{13}}={I13}") for I13 in GENERAL_I13)
    seen = {pair for _, _, pair in decisions()}
    legend = tuple(CLASSES[pair] for pair in CLASSES if pair in seen)
    xticks = tuple((_fmt(v * scale), str(v)) for v in range(int(x1) + 1))
    return Figure("decisions", WIDTH, height, xticks, (), r"\xi=-2/I_{23}", "", cells=cells, rows=rows,
                  legend=legend, formulas=formulas, certificates=certificates)


def figures(emitted: dict, formulas: dict) -> list[Figure] | None:
    """The three figures of a build: ``emitted`` its emitted formulas by name (:func:`derivations.core.emit.
    emitted_formulas`), ``formulas`` its formulas by key; None when the build lacks what they draw."""
    needed = ("scattering_angle", "gauss_invariants", "general_angle")
    keys = {"angle": ("angle", "angle_stable"), "general_angle": ("general_angle", "general_angle_stable"),
            "decisions": ("general_galois", "pole_theorem")}
    if any(name not in emitted for name in needed) or any(k not in formulas for ks in keys.values() for k in ks):
        return None

    def cited(*keys_):
        return tuple(dict.fromkeys(c for k in keys_ for c in formulas[k].certificates))

    return [
        angle_figure(emitted["scattering_angle"].source(), tuple(emitted["scattering_angle"].certificates),
                     keys["angle"]),
        general_angle_figure(emitted["gauss_invariants"].source(), emitted["general_angle"].source(),
                             tuple(dict.fromkeys((*emitted["gauss_invariants"].certificates,
                                                  *emitted["general_angle"].certificates))), keys["general_angle"]),
        decisions_figure(cited(*keys["decisions"]), keys["decisions"]),
    ]
