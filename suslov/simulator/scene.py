"""Scene files (TOML): what body, which motion, which window, which effects (docs/design.md, "Scenes").

A scene is declarative: it names the effects wanted, never the method.  Schema::

    name = "fig2_gamma_ss"                 # optional, default: the file name
    title = "Fig. 2: ..."                  # optional: figure titles (matplotlib mathtext), default: the name
    description = "..."                    # optional

    [body]                                 # exactly one of: inertia | p and d | kind = "sleigh"
    inertia = [[I11, I12, I13], [I12, I22, I23], [I13, I23, I33]]   # constraint axis a = e3
    p = 2.5                                # case I13 = 0 (eq:necc1 corrected), any real p > 0
    d = "0.7"                              # d > 0, d^2 = I11/I22 - 1
                                           # p, d and the inertia entries: integers, decimal or "a/b" strings
                                           # (exact: "0.7" is 7/10) or floats (their binary value: 0.7 is
                                           # Fraction(0.7)); the exact effects are computed for these numbers
                                           # (suslov.simulator.exact), the numerics with their floats
    # Chaplygin sleigh (section 4): kind = "sleigh", mass, inertia (about the centre of mass),
    # offset (blade to centre of mass, > 0)

    [motion]
    time = [-10.0, 10.0]                   # window, t0 < t1
    samples = 1001                         # >= 2
    energy = 1.0                           # optional: kinetic energy (default: rate 1)
    initial = "ss"                         # or gamma0 = [g1, g2, g3] (unit vector at time[0])
    speed = 1.0                            # sleigh only: limit speed of the blade

    [effects]
    compute = ["omega", "gamma", "orientation", "integral_drift", "scattering_angle", "scattering_angle_integrated",
               "scattering_angle_enclosure", "galois_group", "local_behaviour"]
                                           # scattering_angle: a certified closed form for every body;
                                           # scattering_angle_integrated: the same angle by integrating ss
                                           # (the [numerics] integrator family), a cross-check beside it;
                                           # scattering_angle_enclosure: a rigorous ball (python-flint);
                                           # galois_group: decided exactly (Kimura; suslov.validated.galois_group)
                                           # local_behaviour: meromorphic / logarithmic / branching at the poles
                                           # (the theorem for every p; suslov.validated.local_behaviour)
    figures = ["omega_plane", "gamma_components", "basis_sphere"]
    figures_format = ["png", "pdf"]        # optional, default ["png"]; also "svg"

    [numerics]                             # optional
    rtol = 1e-10                           # the Taylor integrator's tolerance, or SciPy's rtol
    atol = 1e-12                           # SciPy only
    method = "taylor"                      # heyoka's Taylor integrator (default); SciPy as cross-check:
                                           # "scipy:DOP853", "scipy:RK45", "scipy:Radau", "scipy:LSODA"
                                           # (a bare "DOP853" means "scipy:DOP853")
    gamma_route = "gauss_2f1"              # gamma, orientation: Gauss's 2F1 closed form of every body (default;
                                           # suslov.kernel.gauss_gamma), or "integrate": the integrator above,
                                           # as a cross-check (odd p with a certified basis: that basis either way)

A *sweep scene* has a ``[sweep]`` table instead of ``[body]`` (schema: :mod:`suslov.simulator.sweep_spec`):
many bodies, scalar effects only (``SWEEP_EFFECTS``), one row per point in ``results.csv``, and
the figures ``map`` (a scalar effect over the sweep's two varying fields) or ``histogram``.
``[motion]`` is optional there (energies are a sweep field).

Every error names the file, the field and the reason (:class:`SceneError`).

Validation is written here rather than with a schema library (issue 36 asked about pydantic and
jsonschema): the rules are mostly semantic (exactly one of three body forms, effects and figures
the body kind allows, an ordered time window, sizes bounded by the memory they cost), and each error
must name the dotted field in the scene's own terms; a schema would check the types and leave these
rules here anyway.  ``parse_scene`` takes a dict, so ``suslov.simulate`` validates Python scenes
with the same rules and messages.
"""
from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path

import numpy as np

from suslov.kernel.validate import shown
from suslov.loader import gf
from suslov.simulator.exact import exact_number
from suslov.simulator.scene_errors import SceneError
from suslov.simulator.sweep_spec import parse_sweep

EFFECTS = ("omega", "gamma", "orientation", "integral_drift", "scattering_angle", "scattering_angle_integrated",
           "scattering_angle_enclosure", "contact_point", "galois_group", "local_behaviour")
FIGURES = {  # figure -> effect it draws
    "omega_plane": "omega",
    "gamma_components": "gamma",
    "gamma_sphere": "gamma",
    "basis_sphere": "orientation",
    "sleigh_path": "contact_point",
}
SLEIGH_EFFECTS = ("omega", "contact_point")
SLEIGH_FIGURES = ("sleigh_path",)   # the other figures draw a Suslov body's omega (paper frame) or gamma
SWEEP_EFFECTS = ("scattering_angle", "scattering_angle_integrated", "scattering_angle_enclosure", "galois_group",
                 "local_behaviour")
SWEEP_FIGURES = ("map", "histogram")
SCIPY_METHODS = ("RK45", "DOP853", "Radau", "LSODA")
GAMMA_ROUTES = ("gauss_2f1", "integrate")
METHODS = ("taylor", *(f"scipy:{m}" for m in SCIPY_METHODS))
MAX_SAMPLES = 1_000_000
FIGURE_FORMATS = ("png", "pdf", "svg")


@dataclass
class Scene:
    path: Path
    name: str
    description: str
    body: dict
    time: tuple
    samples: int
    energy: float | None
    initial: str | np.ndarray
    speed: float
    effects: list = field(default_factory=list)
    figures: list = field(default_factory=list)
    rtol: float = 1e-10
    atol: float = 1e-12
    method: str = "taylor"
    title: str = ""
    figures_format: tuple = ("png",)
    sweep: object = None           # a suslov.simulator.sweep_spec.Sweep for a sweep scene
    gamma_route: str = "gauss_2f1"   # gamma, orientation: "gauss_2f1" (closed form) or "integrate" (cross-check)

    @property
    def is_sweep(self) -> bool:
        return self.sweep is not None

    @property
    def is_sleigh(self) -> bool:
        return self.body.get("kind") == "sleigh"

    def times(self) -> np.ndarray:
        t0, t1 = self.time
        if math.isfinite(t1 - t0):
            return np.linspace(t0, t1, self.samples)
        # a window wider than float64 ([-1e308, 1e308]: t1 - t0 overflows, linspace gave NaN): weighted ends
        weights = np.linspace(0.0, 1.0, self.samples)
        return (1.0 - weights) * t0 + weights * t1


def _number(path, name, value, *, positive=False, allow_zero=True):
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise SceneError(path, name, f"{shown(value)} is not a number")
    try:
        value = float(value)
    except OverflowError:   # a Python int beyond float64 (10**400 in a dict scene)
        raise SceneError(path, name, f"{shown(value)} is beyond float64's range (|x| <= 1.8e308)") from None
    if not math.isfinite(value):
        raise SceneError(path, name, f"{value!r} is not finite")
    if positive and (value < 0 or (value == 0 and not allow_zero)):
        raise SceneError(path, name, f"{value!r} must be > 0")
    return value


def _body_number(path, name, value, *, positive=False):
    """A body's number as a float for the numerics; strings (decimals, "a/b") and Fractions are accepted too,
    and the exact effects read the number as written (:func:`suslov.simulator.exact.exact_number`)."""
    if isinstance(value, (str, Fraction)):
        try:
            exact, _ = exact_number(name, value)
            number = float(exact)
        except ValueError as exc:
            raise SceneError(path, name, str(exc).split(": ", 1)[-1]) from None
        except OverflowError:
            raise SceneError(path, name, f"{shown(value)} is beyond float64's range (|x| <= 1.8e308)") from None
        if positive and exact <= 0:
            raise SceneError(path, name, f"{value!r} must be > 0")
        return number
    return _number(path, name, value, positive=positive, allow_zero=not positive)


def _drift_in_float64(path, body, energy):
    """integral_drift evaluates F1 = <I omega, omega>/2 in float64 with the representative tensor of (p, d)
    (:func:`suslov.simulator.body.tensor_from_pd`: I22 = 1, I11 = 1 + d^2, I23 = -d/p, I33 = 1 + d^2/p^2): refused
    by name when that tensor or F1 is beyond float64 (d = 1e300, p = 1e-300, or p = 1e300 at rate 1), which
    otherwise came out as NaN.  The other effects of such a body run (the closed forms take p and d)."""
    from suslov.simulator.body import tensor_from_pd

    p, d = body["p"], body["d"]
    with np.errstate(over="ignore", under="ignore", invalid="ignore"):
        tensor = tensor_from_pd(p, d)
        speed = p * math.hypot(1.0, 1.0 / d) if d >= 1.0 else (p / d) * math.hypot(d, 1.0)   # |omega(0)|, rate 1
        f1 = energy if energy is not None else 0.5 * speed * speed
    if not np.all(np.isfinite(tensor)):
        raise SceneError(path, "effects.compute", f"integral_drift: F1 = <I omega, omega>/2 is evaluated in float64 with "
                         f"the representative tensor of p = {p!r}, d = {d!r} (I11 = 1 + d^2, I23 = -d/p, I33 = 1 + "
                         "d^2/p^2), whose entries are beyond float64's range here; the other effects run for this "
                         "body")
    if not math.isfinite(f1):
        raise SceneError(path, "effects.compute", f"integral_drift: F1 = |omega(0)|^2/2 at rate 1, |omega(0)| = "
                         f"{speed:.3g}, is beyond float64's range for p = {p!r}, d = {d!r}; give motion.energy (the "
                         "rate follows from it) or leave out integral_drift")


def _table(path, data, name, allowed):
    table = data.get(name, {})
    if not isinstance(table, dict):
        raise SceneError(path, name, f"must be a table ([{name}])")
    unknown = sorted(set(table) - set(allowed))
    if unknown:
        raise SceneError(path, f"{name}.{unknown[0]}", f"unknown field; allowed: {', '.join(allowed)}")
    return table


def _body(path, table):
    if table.get("kind", "suslov") not in ("suslov", "sleigh"):
        raise SceneError(path, "body.kind", f"{table['kind']!r}: must be 'suslov' or 'sleigh'")
    if table.get("kind") == "sleigh":
        body = {"kind": "sleigh"}
        for key in ("mass", "inertia", "offset"):
            if key not in table:
                raise SceneError(path, f"body.{key}", "missing (a sleigh needs mass, inertia, offset)")
            body[key] = _number(path, f"body.{key}", table[key], positive=True, allow_zero=False)
        return body
    has_tensor, has_pd = "inertia" in table, ("p" in table or "d" in table)
    if has_tensor == has_pd:
        raise SceneError(path, "body", "give exactly one of 'inertia' or 'p' and 'd'")
    if has_tensor:
        rows = table["inertia"]
        if (not isinstance(rows, list) or len(rows) != 3
                or not all(isinstance(r, list) and len(r) == 3 for r in rows)):
            raise SceneError(path, "body.inertia", "must be a 3x3 array of numbers")
        tensor = np.array([[_body_number(path, f"body.inertia[{i}][{j}]", rows[i][j]) for j in range(3)]
                           for i in range(3)])
        try:  # the generated module's validation: symmetric, positive definite, a not an eigenvector
            gf.canonical_frame(tensor)
        except ValueError as exc:
            raise SceneError(path, "body.inertia", str(exc)) from None
        # written: the numbers as the user wrote them, for the exact effects (suslov.simulator.exact)
        return {"kind": "suslov", "inertia": tensor, "written": {"inertia": [list(r) for r in rows]}}
    for key in ("p", "d"):
        if key not in table:
            raise SceneError(path, f"body.{key}", "missing (p and d go together)")
    return {"kind": "suslov", "p": _body_number(path, "body.p", table["p"], positive=True),
            "d": _body_number(path, "body.d", table["d"], positive=True),
            "written": {"p": table["p"], "d": table["d"]}}


def _motion(path, motion, sweep):
    """(time window, samples, energy, initial, speed); a sweep's motion is optional."""
    window = motion.get("time", [-1.0, 1.0] if sweep else None)
    if not isinstance(window, list) or len(window) != 2:
        raise SceneError(path, "motion.time", "must be [t0, t1]")
    t0, t1 = (_number(path, f"motion.time[{i}]", window[i]) for i in range(2))
    if not t0 < t1:
        raise SceneError(path, "motion.time", f"[{t0}, {t1}] is empty: need t0 < t1")
    samples = motion.get("samples", 501)
    if isinstance(samples, bool) or not isinstance(samples, int) or not 2 <= samples <= MAX_SAMPLES:
        raise SceneError(path, "motion.samples", f"{samples!r}: must be an integer in [2, {MAX_SAMPLES}]")
    energy = motion.get("energy")
    if energy is not None:
        if sweep:
            raise SceneError(path, "motion.energy", "a sweep takes its energies from sweep.energy")
        energy = _number(path, "motion.energy", energy, positive=True, allow_zero=False)
    speed = _number(path, "motion.speed", motion.get("speed", 1.0), positive=True, allow_zero=False)
    if "gamma0" in motion and "initial" in motion:
        raise SceneError(path, "motion", "give either initial = \"ss\" or gamma0, not both")
    if "gamma0" in motion:
        g = motion["gamma0"]
        if not isinstance(g, list) or len(g) != 3:
            raise SceneError(path, "motion.gamma0", "must be [g1, g2, g3]")
        initial = np.array([_number(path, f"motion.gamma0[{i}]", g[i]) for i in range(3)])
        if abs(np.linalg.norm(initial) - 1.0) > 1e-9:
            raise SceneError(path, "motion.gamma0", f"|gamma0| = {np.linalg.norm(initial):.12g}: must be a unit vector")
    else:
        initial = motion.get("initial", "ss")
        if initial != "ss":
            raise SceneError(path, "motion.initial", f"{initial!r}: the only named condition is \"ss\"")
    return (t0, t1), samples, energy, initial, speed


def _effects(path, effects, body, sweep):
    """(compute, figures, formats) checked against what the body (or sweep) supports."""
    compute = effects.get("compute", [])
    figures = effects.get("figures", [])
    known_figures = SWEEP_FIGURES if sweep else tuple(FIGURES)
    for key, values, known in (("effects.compute", compute, EFFECTS), ("effects.figures", figures, known_figures)):
        if not isinstance(values, list) or not all(isinstance(v, str) for v in values):
            raise SceneError(path, key, "must be a list of names")
        for v in values:
            if v not in known:
                raise SceneError(path, key, f"unknown {'figure' if 'fig' in key else 'effect'} {v!r}; "
                                 f"known: {', '.join(known)}")
    if not compute and not figures:
        raise SceneError(path, "effects", "nothing requested: give effects.compute and/or effects.figures")
    formats = effects.get("figures_format", ["png"])
    if not isinstance(formats, list) or not formats or not all(isinstance(f, str) for f in formats):
        raise SceneError(path, "effects.figures_format", f"{formats!r}: must be a non-empty list of format names")
    for f in formats:
        if f not in FIGURE_FORMATS:
            raise SceneError(path, "effects.figures_format",
                             f"unknown format {f!r}; known: {', '.join(FIGURE_FORMATS)}")
    if sweep:
        bad = [e for e in compute if e not in SWEEP_EFFECTS]
        if bad:
            raise SceneError(path, "effects.compute", f"{bad[0]!r} is not a scalar effect; a sweep computes "
                             f"{', '.join(SWEEP_EFFECTS)}")
        if figures and not compute:
            raise SceneError(path, "effects.figures", "a sweep figure draws a computed effect: list it in compute")
        return compute, figures, formats
    wanted = set(compute) | {FIGURES[f] for f in figures}
    if body["kind"] == "sleigh":
        bad = sorted(wanted - set(SLEIGH_EFFECTS))
        if bad:
            raise SceneError(path, "effects", f"{bad[0]!r} is not defined for a sleigh (allowed: "
                             f"{', '.join(SLEIGH_EFFECTS)})")
        drawn = [f for f in figures if f not in SLEIGH_FIGURES]
        if drawn:
            raise SceneError(path, "effects.figures", f"{drawn[0]!r} draws a Suslov body (the paper's omega or "
                             f"gamma); a sleigh scene draws: {', '.join(SLEIGH_FIGURES)}")
    elif "contact_point" in wanted:
        raise SceneError(path, "effects", "'contact_point' needs a sleigh body (body.kind = \"sleigh\")")
    return compute, figures, formats


def _numerics(path, numerics):
    rtol = _number(path, "numerics.rtol", numerics.get("rtol", 1e-10), positive=True, allow_zero=False)
    atol = _number(path, "numerics.atol", numerics.get("atol", 1e-12), positive=True, allow_zero=False)
    if not 1e-14 <= rtol <= 1e-2:
        raise SceneError(path, "numerics.rtol", f"{rtol!r}: must be in [1e-14, 1e-2]")
    method = numerics.get("method", "taylor")
    if method in SCIPY_METHODS:
        method = f"scipy:{method}"
    if method not in METHODS:
        raise SceneError(path, "numerics.method", f"{method!r}: must be one of {', '.join(METHODS)} (a bare SciPy "
                         f"name, {', '.join(SCIPY_METHODS)}, is read as scipy:NAME)")
    route = numerics.get("gamma_route", "gauss_2f1")
    if route not in GAMMA_ROUTES:
        raise SceneError(path, "numerics.gamma_route", f"{route!r}: must be one of {', '.join(GAMMA_ROUTES)}")
    return rtol, atol, method, route


def load_scene(path) -> Scene:
    """Parse and validate a scene file; raises :class:`SceneError`."""
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise SceneError(path, "file", "not found") from None
    except IsADirectoryError:
        raise SceneError(path, "file", "is a directory; give a scene file (TOML), e.g. scenes/fig1_omega.toml") from None
    except PermissionError:
        raise SceneError(path, "file", "cannot be read (permission denied)") from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise SceneError(path, "file", f"not valid TOML ({exc})") from None
    return parse_scene(data, path)


def parse_scene(data: dict, path=None) -> Scene:
    """Validate a scene given as a dict (the TOML file's tables as nested dicts); raises :class:`SceneError`.

    ``path`` names the scene in errors (default ``<dict>``) and gives its default name.

    >>> scene = parse_scene({"body": {"p": 2, "d": 0.5}, "motion": {"time": [-5, 5], "samples": 11},
    ...                      "effects": {"compute": ["scattering_angle"]}})
    >>> scene.effects, scene.name
    (['scattering_angle'], 'scene')
    """
    path = Path("<dict>") if path is None else Path(path)
    if not isinstance(data, dict):
        raise SceneError(path, "scene", f"{type(data).__name__}: must be a dict of tables (body, motion, ...)")
    top = sorted(set(data) - {"name", "title", "description", "body", "sweep", "motion", "effects", "numerics"})
    if top:
        raise SceneError(path, top[0], "unknown field; allowed: name, title, description, [body] or [sweep], "
                         "[motion], [effects], [numerics]")
    for key in ("name", "title", "description"):
        if key in data and not isinstance(data[key], str):
            raise SceneError(path, key, "must be a string")
    if ("body" in data) == ("sweep" in data):
        raise SceneError(path, "body", "give exactly one of [body] (one body) or [sweep] (many)")
    wanted = data.get("effects", {}).get("compute", []) if isinstance(data.get("effects"), dict) else []
    exact = isinstance(wanted, list) and any(e in ("galois_group", "scattering_angle_enclosure", "local_behaviour")
                                             for e in wanted)
    sweep = parse_sweep(path, data["sweep"], keep_written=exact) if "sweep" in data else None
    body = None if sweep else _body(path, _table(path, data, "body", ("kind", "inertia", "p", "d", "mass", "offset")))
    motion = _table(path, data, "motion", ("time", "samples", "energy", "initial", "gamma0", "speed"))
    window, samples, energy, initial, speed = _motion(path, motion, sweep)
    compute, figures, formats = _effects(path, _table(path, data, "effects", ("compute", "figures", "figures_format")),
                                         body, sweep)
    rtol, atol, method, route = _numerics(path, _table(path, data, "numerics", ("rtol", "atol", "method",
                                                                                "gamma_route")))
    if body and "p" in body and "integral_drift" in compute:
        _drift_in_float64(path, body, energy)
    default_name = "scene" if path.name == "<dict>" else path.stem
    return Scene(path, data.get("name", default_name), data.get("description", ""), body or {"kind": "sweep"}, window,
                 samples, energy, initial, speed, list(dict.fromkeys(compute)), list(dict.fromkeys(figures)), rtol,
                 atol, method, data.get("title", ""), tuple(dict.fromkeys(formats)), sweep, route)
