"""Turn a scene's effects into the smallest set of computations (DESIGN.md, "Scenes").

Rules (the planner's whole policy, in one place):

* omega is always a certified closed form (``omega`` / ``omega_general``);
  it is computed only when an effect shows it or needs it (``integral_drift``).
* A Poisson solution is needed by ``gamma``, ``integral_drift`` and their
  figures; ``orientation`` needs three.  Closed form (``gamma_basis``) when
  I13 = 0 and p is an odd integer with a certified basis; otherwise guarded
  numerical integration (``suslov.integrate``).
* The scattering angle is the closed form of Theorem 5.2 (corrected) whenever
  I13 = 0, for any real p: nothing is integrated.  Only a general body
  (I13 and I23 both non-zero) integrates the ss solution.
* ``scattering_angle_enclosure`` is always the validated integration (python-flint balls, any
  body); for I13 = 0 the ball contains the closed form.
* Figures add no computation of their own beyond the effect they draw.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from generated.suslov_formulas import INTEGRAL_PS

from .body import make_body
from .scene import FIGURES, Scene
from .sleigh import Sleigh


@dataclass(frozen=True)
class Step:
    name: str
    method: str
    reason: str


@dataclass
class Plan:
    scene: Scene
    body: object
    steps: list[Step] = field(default_factory=list)

    def names(self) -> list[str]:
        return [s.name for s in self.steps]

    def explain(self) -> str:
        lines = [f"scene {self.scene.name!r} ({self.scene.path})", f"body: {describe(self.body)}"]
        lines += [f"{i}. {s.name}: {s.method}  [{s.reason}]" for i, s in enumerate(self.steps, 1)]
        return "\n".join(lines)


def describe(body) -> str:
    if isinstance(body, Sleigh):
        return (f"Chaplygin sleigh: m = {body.mass:g}, J = {body.inertia:g}, offset = {body.offset:g}, "
                f"V = {body.speed:g}")
    return body.describe()


def build_body(scene: Scene):
    b = scene.body
    if b["kind"] == "sleigh":
        return Sleigh(b["mass"], b["inertia"], b["offset"], scene.speed)
    return make_body(b.get("inertia"), b.get("p"), b.get("d"), scene.energy)


def make_plan(scene: Scene) -> Plan:
    """The plan for ``scene`` (no computation beyond building the body)."""
    body = build_body(scene)
    plan = Plan(scene, body)
    wanted = set(scene.effects) | {FIGURES[f] for f in scene.figures}
    add = plan.steps.append
    if isinstance(body, Sleigh):
        if "omega" in wanted:
            add(Step("sleigh_velocities", "closed form (tanh, sech, Gudermannian)", "omega requested"))
        if "contact_point" in wanted:
            add(Step("sleigh_path", "closed-form velocities + DOP853 quadrature", "contact_point requested"))
    else:
        closed = body.odd_integer_p is not None
        if wanted & {"omega", "integral_drift"}:
            add(Step("omega", "closed form " + ("omega (p, d)" if body.special else "omega_general"),
                     ", ".join(sorted(wanted & {"omega", "integral_drift"})) + " requested"))
        if wanted & {"gamma", "integral_drift"}:
            start = "boundary condition ss" if isinstance(scene.initial, str) else "gamma0 at t0"
            if closed:
                add(Step("gamma_closed_form", f"gamma_basis (odd p = {body.odd_integer_p}), {start}",
                         "certified meromorphic basis exists"))
            else:
                add(Step("gamma_integrate", f"{scene.method} rtol={scene.rtol:g}, bounded step, {start}",
                         "no closed form: " + ("p not an odd integer" if body.special else "I13 != 0")))
        if "orientation" in wanted:
            if closed:
                add(Step("orientation_closed_form", f"gamma_basis rows (odd p = {body.odd_integer_p})",
                         "orientation requested"))
            else:
                add(Step("orientation_integrate", f"{scene.method}, three solutions from the identity at t0",
                         "orientation requested, no closed form"))
        if "integral_drift" in wanted:
            f3 = closed and body.odd_integer_p in INTEGRAL_PS
            add(Step("integrals", "F1 (energy), F2 = |gamma|^2" + (", F3 polynomial (Theorem 6.2)" if f3 else ""),
                     "integral_drift requested"))
        if "scattering_angle" in wanted:
            if body.special:
                add(Step("angle_closed_form", "scattering_angle(p, d) (Theorem 5.2, corrected)",
                         "I13 = 0: closed form for any real p"))
            else:
                add(Step("angle_integrate", "DOP853 rtol=1e-12 on ss from the series start to lam t = 40",
                         "general body: no closed form"))
        if "scattering_angle_enclosure" in wanted:
            add(Step("angle_enclosure", "validated integration in ball arithmetic (suslov.validated), 1e-20",
                     "scattering_angle_enclosure requested: a rigorous ball, any body"))
    for name in scene.figures:
        add(Step(f"figure:{name}", "matplotlib (Agg), " + ", ".join(f.upper() for f in scene.figures_format),
                 f"figure {name} requested"))
    return plan

