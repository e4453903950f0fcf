"""Turn a scene's effects into the smallest set of computations: a declarative effect graph (docs/design.md, "Scenes").

Each effect has *providers*, in order of preference; a provider is an engine step with the
effects it needs and the condition under which it applies.  The plan is the minimal subgraph
that yields the requested effects: for each one the first provider whose condition holds,
then, recursively, what that provider needs; steps run in the order of ``ORDER`` (a
topological order: a need always comes earlier).  The whole policy is the table
``PROVIDERS`` below:

* omega is always a certified closed form (``omega`` / ``omega_general``, paper eq:o12, omegas).
* A Poisson solution (``gamma``, ``orientation``) is the certified basis ``gamma_basis``
  (Theorem 6.1) when I13 = 0 and p is an odd integer with a certified basis; otherwise the closed form of
  every body from Gauss's 2F1 (``gauss_2f1``, :mod:`suslov.kernel.gauss_gamma`, evaluated in float64 by
  :mod:`suslov.kernel.gauss_gamma_float` and checked on every run: ``|gamma|``, the mpmath closed form at a few
  samples, the ODE residual there) while ``|u| + |v| <= GAUSS_MAX_OMEGA`` (its precomputation grows like
  ``|omega|``); numerical integration (heyoka's Taylor integrator by default, SciPy on request;
  ``suslov.simulator.taylor``, ``suslov.simulator.integrate``) beyond that, or as the cross-check when the
  scene says ``[numerics] gamma_route = "integrate"``.
* The scattering angle is always a certified closed form, never an integration: Theorem 5.4
  (corrected) whenever I13 = 0, for any real p; for every other body the closed form of every
  body (``general_scattering_angle``: Gauss's equation in s = sinh t).
* ``scattering_angle_integrated`` is the explicit cross-check: the ss solution integrated to
  lam t = 40 with the scene's integrator family, for any Suslov body, asked for beside the closed form.
* ``scattering_angle_enclosure`` is a ball of the closed form of every body
  (``suslov.validated.scattering_angle_enclosure``, default ``method="closed_form"``), rigorous;
  the validated integration stays available there as ``method="integration"``.
* ``integral_drift`` needs omega and gamma; a figure needs the effect it draws, nothing more.

What each step needs of the ``[sim]`` extra (:func:`step_libraries`): the closed forms, the balls and the exact
decisions need NumPy, mpmath and python-flint only (the core install); a numerical integration needs its
integrator (heyoka for ``method = "taylor"``, SciPy for ``scipy:NAME``), the sleigh's path SciPy's quadrature, a
figure matplotlib.  ``suslov simulate`` and ``suslov.simulate`` ask for the extra only when a planned step
needs it (:func:`suslov.simulator.api.check_extras`).

A sweep scene uses the same providers per point (:func:`point_steps`); its plan counts the
points of each class (:mod:`suslov.simulator.sweep`).
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from suslov.extras import FIGURES as FIGURE_LIBRARIES
from suslov.loader import gf
from suslov.simulator.body import make_body
from suslov.simulator.exact import of_scene_body
from suslov.simulator.scene import FIGURES, Scene
from suslov.simulator.sleigh import Sleigh


@dataclass(frozen=True)
class Step:
    name: str
    method: str
    reason: str
    needs: tuple = ()


@dataclass(frozen=True)
class Provider:
    """Engine step ``step`` provides ``effect`` when ``applies(scene, body)``; it needs ``needs`` first."""

    effect: str
    step: str
    needs: tuple
    condition: str                          # what ``applies`` tests, in words (for --explain)
    applies: Callable[[Scene, object], bool]
    method: Callable[[Scene, object], str]


def _sleigh(scene, body):
    return isinstance(body, Sleigh)


def _suslov(scene, body):
    return not isinstance(body, Sleigh)


def _closed_basis(scene, body):
    return _suslov(scene, body) and body.odd_integer_p is not None


GAUSS_MAX_OMEGA = 500.0   # |u| + |v| (omega at rate 1) up to which gamma is Gauss's closed form (docs/simulator.md)


def gauss_applies(body) -> bool:
    """The Gauss route's size condition: ``|u| + |v| <= GAUSS_MAX_OMEGA`` (its Taylor centres and mpmath's hyp2f1
    grow with |omega|: 0.13 s at |u| + |v| = 8, 1.3-1.7 s at about 120, 12-18 s at about 420 on the Fig. 2 grid, on the
    bench machine; beyond, integration)."""
    return float(np.hypot(*body.u) + np.hypot(*body.v)) <= GAUSS_MAX_OMEGA


def _gauss(scene, body):
    return _suslov(scene, body) and scene.gamma_route == "gauss_2f1" and gauss_applies(body)


GAUSS_CONDITION = f'any Suslov body with |u| + |v| <= {GAUSS_MAX_OMEGA:g} (numerics.gamma_route = "gauss_2f1", default)'
INTEGRATE_CONDITION = f'otherwise (gamma_route = "integrate", or |u| + |v| > {GAUSS_MAX_OMEGA:g})'


def _special(scene, body):
    return _suslov(scene, body) and body.special


def integrator_name(scene) -> str:
    if scene.method == "taylor":
        return f"heyoka Taylor tol={scene.rtol:g}, step cap"
    return f"SciPy {scene.method.split(':', 1)[1]} rtol={scene.rtol:g}, bounded step"


def _start(scene):
    return "boundary condition ss" if isinstance(scene.initial, str) else "gamma0 at t0"


PROVIDERS = (
    Provider("omega", "sleigh_velocities", (), "a Chaplygin sleigh", _sleigh,
             lambda s, b: "closed form (tanh, sech, Gudermannian)"),
    Provider("omega", "omega", (), "a Suslov body", _suslov,
             lambda s, b: "closed form " + ("omega (p, d)" if b.special else "omega_general")),
    Provider("contact_point", "sleigh_path", ("omega",), "a Chaplygin sleigh", _sleigh,
             lambda s, b: "closed-form velocities + DOP853 quadrature"),
    Provider("gamma", "gamma_closed_form", (), "I13 = 0 and p an odd integer with a certified basis",
             _closed_basis, lambda s, b: f"gamma_basis (odd p = {b.odd_integer_p}), {_start(s)}"),
    Provider("gamma", "gamma_gauss", (), GAUSS_CONDITION, _gauss,
             lambda s, b: f"gauss_2f1: Gauss's 2F1 closed form (float64 series, checked), {_start(s)}"),
    Provider("gamma", "gamma_integrate", (), INTEGRATE_CONDITION, _suslov,
             lambda s, b: f"{integrator_name(s)}, {_start(s)}"),
    Provider("orientation", "orientation_closed_form", (), "I13 = 0 and p an odd integer with a certified basis",
             _closed_basis, lambda s, b: f"gamma_basis rows (odd p = {b.odd_integer_p})"),
    Provider("orientation", "orientation_gauss", (), GAUSS_CONDITION, _gauss,
             lambda s, b: "gauss_2f1: Gauss's 2F1 closed form (float64 series, checked), three solutions from the "
                          "identity at t0"),
    Provider("orientation", "orientation_integrate", (), INTEGRATE_CONDITION, _suslov,
             lambda s, b: f"{integrator_name(s)}, three solutions from the identity at t0"),
    Provider("integral_drift", "integrals", ("omega", "gamma"), "a Suslov body", _suslov,
             lambda s, b: "F1 (energy), F2 = |gamma|^2" + (", F3 polynomial (Theorem 6.2)"
                                                           if _closed_basis(s, b) and b.odd_integer_p in gf.INTEGRAL_PS
                                                           else "")),
    Provider("scattering_angle", "angle_closed_form", (), "I13 = 0 (any real p)", _special,
             lambda s, b: "scattering_angle(p, d) (Theorem 5.4, corrected)"),
    Provider("scattering_angle", "angle_general_closed_form", (), "any Suslov body (I13 != 0 included)", _suslov,
             lambda s, b: "the closed form of every body: Gauss's equation in s = sinh t (certified)"),
    Provider("scattering_angle_integrated", "angle_integrate", (), "any Suslov body (a cross-check)", _suslov,
             lambda s, b: ("heyoka Taylor tol=1e-12" if s.method == "taylor" else "SciPy DOP853 rtol=1e-12")
             + " on ss from the series start to lam t = 40"),
    Provider("scattering_angle_enclosure", "angle_enclosure", (), "any Suslov body", _suslov,
             lambda s, b: "the closed form of every body in ball arithmetic (suslov.validated), 1e-20, for the "
                          "body as written (exact; suslov.simulator.exact)"),
    Provider("galois_group", "galois_monodromy", (), "any Suslov body", _suslov,
             lambda s, b: "the group decided exactly (Kimura on the body's Gauss equation) for the body as written "
                          "(exact; suslov.simulator.exact); one body: also the monodromy balls (suslov.validated.monodromy)"),
    Provider("local_behaviour", "local_behaviour", (), "any Suslov body", _suslov,
             lambda s, b: "meromorphic / logarithmic / branching at the poles of omega: the certified theorem for every "
                          "p, decided exactly for the body as written (suslov.simulator.exact)"),
)
ORDER = ("omega", "contact_point", "gamma", "orientation", "integral_drift", "scattering_angle",
         "scattering_angle_integrated", "scattering_angle_enclosure", "galois_group", "local_behaviour")


@dataclass
class Plan:
    scene: Scene
    body: object
    steps: list[Step] = field(default_factory=list)
    graph: list = field(default_factory=list)     # (effect, chosen Provider, providers not chosen)

    def names(self) -> list[str]:
        return [s.name for s in self.steps]

    def libraries(self, figures: bool = True) -> dict:
        """Step name -> the libraries of the [sim] extra it needs, for the steps that need any (figure steps only
        when ``figures``: drawn by ``Result.plot``, ``save`` or ``out=``, not by computing)."""
        needs = {s.name: step_libraries(s.name, self.scene) for s in self.steps
                 if figures or not s.name.startswith("figure:")}
        return {name: libraries for name, libraries in needs.items() if libraries}

    def explain(self) -> str:
        lines = [f"scene {self.scene.name!r} ({self.scene.path})", f"body: {describe(self.body)}"]
        exact = getattr(self.body, "exact", None)
        if exact is not None and {"angle_enclosure", "galois_monodromy", "local_behaviour"} & set(self.names()):
            lines.append(f"exact effects for {exact.for_whom()}; paper-frame entries "
                         f"({', '.join(exact.entries_text())})")
        lines.append("effect graph (effect <- step [condition]; needs):")
        for effect, chosen, others in self.graph:
            needs = ", ".join(chosen.needs) or "-"
            lines.append(f"  {effect} <- {chosen.step} [{chosen.condition}]; needs: {needs}")
            lines += [f"      not {p.step} [{p.condition}]: does not apply" for p in others]
        lines.append("steps:")
        lines += [f"{i}. {s.name}: {s.method}  [{s.reason}]" for i, s in enumerate(self.steps, 1)]
        return "\n".join(lines)


INTEGRATING_STEPS = ("gamma_integrate", "orientation_integrate", "angle_integrate")


def integrator_library(scene) -> str:
    """The library of the scene's integrator: heyoka (``method = "taylor"``) or SciPy (``scipy:NAME``)."""
    return "heyoka" if scene.method == "taylor" else "scipy"


def step_libraries(name: str, scene) -> tuple:
    """The libraries of the [sim] extra step ``name`` needs; () for a closed form, a ball or an exact decision
    (NumPy, mpmath and python-flint: the core install)."""
    if name in INTEGRATING_STEPS:
        return (integrator_library(scene),)
    if name == "sleigh_path":
        return ("scipy",)       # the contact point: closed-form velocities + SciPy's DOP853 quadrature
    if name.startswith("figure:"):
        return FIGURE_LIBRARIES
    return ()


def sweep_libraries(scene, figures: bool = True) -> dict:
    """What a sweep scene needs of the [sim] extra, per effect or figure (the same steps per point as
    :func:`point_steps`: only ``scattering_angle_integrated`` integrates)."""
    needs = {}
    if "scattering_angle_integrated" in scene.effects:
        needs["scattering_angle_integrated"] = (integrator_library(scene),)
    if figures:
        needs.update({f"figure:{name}": FIGURE_LIBRARIES for name in scene.figures})
    return needs


def describe(body) -> str:
    if isinstance(body, Sleigh):
        return (f"Chaplygin sleigh: m = {body.mass:g}, J = {body.inertia:g}, offset = {body.offset:g}, "
                f"V = {body.speed:g}")
    return body.describe()


def build_body(scene: Scene):
    b = scene.body
    if b["kind"] == "sleigh":
        return Sleigh(b["mass"], b["inertia"], b["offset"], scene.speed)
    # the numbers as written, exactly (the exact effects' body); ValueError when they are not a body exactly
    return make_body(b.get("inertia"), b.get("p"), b.get("d"), scene.energy, exact=of_scene_body(b))


def choose(effect: str, scene: Scene, body) -> tuple[Provider, list[Provider]]:
    """The first provider of ``effect`` whose condition holds, and the preferred ones that did not."""
    candidates = [p for p in PROVIDERS if p.effect == effect]
    for i, provider in enumerate(candidates):
        if provider.applies(scene, body):
            return provider, candidates[:i]
    raise ValueError(f"effect {effect!r} has no provider for {describe(body)}")


def resolve(wanted, scene: Scene, body) -> dict:
    """effect -> (Provider, providers not chosen) for ``wanted`` and everything they need."""
    chosen: dict = {}
    stack = list(wanted)
    while stack:
        effect = stack.pop()
        if effect in chosen:
            continue
        chosen[effect] = choose(effect, scene, body)
        stack.extend(chosen[effect][0].needs)
    return chosen


def point_steps(effects, scene: Scene, body) -> list[str]:
    """The step names for ``effects`` of one body (a sweep point), in execution order."""
    chosen = resolve(effects, scene, body)
    return [chosen[e][0].step for e in ORDER if e in chosen]


def make_plan(scene: Scene) -> Plan:
    """The plan for a one-body ``scene`` (no computation beyond building the body)."""
    body = build_body(scene)
    plan = Plan(scene, body)
    wanted = list(scene.effects) + [FIGURES[f] for f in scene.figures]
    chosen = resolve(wanted, scene, body)
    for effect in ORDER:
        if effect not in chosen:
            continue
        provider, others = chosen[effect]
        plan.graph.append((effect, provider, others))
        requested = [w for w in dict.fromkeys(wanted) if w == effect or effect in chosen[w][0].needs]
        reason = (f"{effect} requested" if effect in wanted else f"needed by {', '.join(requested)}")
        plan.steps.append(Step(provider.step, provider.method(scene, body), reason, provider.needs))
    for name in scene.figures:
        plan.steps.append(Step(f"figure:{name}", "matplotlib (Agg), " + ", ".join(f.upper() for f in
                                                                                  scene.figures_format),
                               f"figure {name} requested", (FIGURES[name],)))
    return plan
