"""Run a plan: compute exactly the planned steps, then write the results atomically.

Each step is a function of the plan and the data computed so far; the engine
records what ran (name, method, seconds) in ``Run.executed``, which the report
and the tests read.  Outputs (CSV, JSON, PNG, ``report.md``) are written atomically
(:func:`suslov.simulator.outputs.staged`), so a failed run leaves the output directory as it was.
"""
from __future__ import annotations

import cmath
import json
import logging
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from suslov.loader import gf
from suslov.simulator import integrate
from suslov.simulator.outputs import REPORT, staged
from suslov.simulator.planner import Plan

log = logging.getLogger(__name__)


@dataclass
class Run:
    plan: Plan
    data: dict = field(default_factory=dict)
    results: dict = field(default_factory=dict)
    executed: list = field(default_factory=list)


def _basis_paper(body, t):
    """Rows gamma^(1..3) of the certified basis at times t (paper frame), shape (n, 3, 3)."""
    return gf.gamma_basis(body.rate * np.asarray(t, dtype=float), body.odd_integer_p, body.d)


def _initial_paper(run: Run):
    scene, body = run.plan.scene, run.plan.body
    return None if isinstance(scene.initial, str) else body.to_paper(scene.initial)


def step_omega(run: Run):
    t = run.plan.scene.times()
    run.data["t"] = t
    run.data["omega"] = run.plan.body.omega_scene(t)
    run.data["omega_paper"] = run.plan.body.omega(t)


def step_gamma_closed_form(run: Run):
    body, t = run.plan.body, run.plan.scene.times()
    B = _basis_paper(body, t)
    g0 = _initial_paper(run)
    if g0 is None:
        coeff = np.array([1.0, 0.0, 0.0])  # gamma^(1): the ss solution
    else:
        coeff = _basis_paper(body, t[:1])[0] @ g0
    run.data["t"] = t
    run.data["gamma"] = body.to_scene(np.einsum("i,nij->nj", coeff, B))
    run.results["gamma"] = {"method": "closed form gamma_basis", "p": body.odd_integer_p,
                            "norm_drift": float(np.max(np.abs(np.linalg.norm(run.data["gamma"], axis=-1) - 1)))}


def step_gamma_integrate(run: Run):
    scene, body = run.plan.scene, run.plan.body
    t = scene.times()
    g0 = _initial_paper(run)
    t_start = None
    if g0 is None:
        t_start, g0 = integrate.ss_initial(body, t[0])
    sol = solve(scene, body, t, g0, t_start)
    run.data["t"] = t
    run.data["gamma"] = body.to_scene(sol.values[:, 0, :])
    run.results["gamma"] = sol.summary() | {"start": "ss series" if t_start is not None else "gamma0"}


GAUSS_TOLERANCE = 1e-10   # the checks every gauss_2f1 run must pass (absolute; measured ~1e-15, docs/simulator.md)
GAUSS_METHOD = ("gauss_2f1: gamma = the vector of Phi X0 Phi^-1, Phi from Gauss's 2F1 at infinity (z = (1 + i sinh "
                "lam t)/2, w = 1/z; the halves s < 0 and s > 0 joined by the Taylor series at z = 1/2), evaluated in "
                "float64 by its convergent series (suslov.kernel.gauss_gamma_float)")


def gauss_problems(summary: dict) -> list[str]:
    """What a gauss_2f1 run failed of its checks (:data:`GAUSS_TOLERANCE`); [] when it passed them all."""
    problems = []
    if not summary["norm_drift"] <= GAUSS_TOLERANCE:
        problems.append(f"| |gamma| - |gamma0| | = {summary['norm_drift']:.3g}")
    if not summary["mp_check"]["max_abs_difference"] <= GAUSS_TOLERANCE:
        problems.append(f"float64 vs the mpmath closed form: {summary['mp_check']['max_abs_difference']:.3g}")
    if not summary["ode_residual"] <= GAUSS_TOLERANCE:
        problems.append(f"ODE residual of the closed form: {summary['ode_residual']:.3g}")
    if not summary.get("initial_error", 0.0) <= GAUSS_TOLERANCE:
        problems.append(f"initial condition: {summary['initial_error']:.3g}")
    return problems


def gauss_solve(run: Run, initial, what: str):
    """(values (n, k, 3) in the paper frame, result metadata) by the Gauss route, checked; the scene's integrator
    instead, saying why, when the route fails or a check does not pass (never a silent wrong answer)."""
    from mpmath.libmp import NoConvergence

    from suslov.kernel.gauss_gamma_float import solve as solve_gauss
    scene, body = run.plan.scene, run.plan.body
    t = scene.times()
    try:
        sol = solve_gauss(body.u, body.v, body.rate * t, initial, body.rate * t[0])
        problems = gauss_problems(sol.summary())
    except (ArithmeticError, NoConvergence, ValueError) as error:
        sol, problems = None, [f"{type(error).__name__}: {error}"]
    if not problems:
        summary = sol.summary()
        error = max(summary["mp_check"]["max_abs_difference"], summary["norm_drift"], summary.get("initial_error", 0))
        return sol.values, {"method": GAUSS_METHOD, "route": "gauss_2f1", "error_estimate": error,
                            "checks_passed": True, "checks_tolerance": GAUSS_TOLERANCE, **summary}
    log.warning("gauss_2f1 %s refused (%s): integrating instead", what, "; ".join(problems))
    start = None
    if isinstance(initial, str):
        start, initial = integrate.ss_initial(body, t[0])
    try:
        numeric = solve(scene, body, t, initial, start)
    except ImportError as error:   # the plan needed no integrator: say both what failed and what is missing
        raise RuntimeError(f"gauss_2f1 {what} refused ({'; '.join(problems)}); its fallback, the scene's integrator, "
                           f"is not installed ({error}): pip install 'suslov-certified[sim]'") from error
    return numeric.values, numeric.summary() | {"route": "integrate (gauss_2f1 refused)",
                                                "gauss_2f1_refused": "; ".join(problems)}


def step_gamma_gauss(run: Run):
    g0 = _initial_paper(run)
    values, meta = gauss_solve(run, "ss" if g0 is None else g0, "gamma")
    run.data["t"] = run.plan.scene.times()
    run.data["gamma"] = run.plan.body.to_scene(values[:, 0, :])
    run.results["gamma"] = meta | {"start": "ss (exact: gamma(-oo) = -u/|u|)" if g0 is None else "gamma0"}


def step_orientation_gauss(run: Run):
    values, meta = gauss_solve(run, run.plan.body.to_paper(np.eye(3)), "orientation")
    run.data["t"] = run.plan.scene.times()
    run.data["orientation"] = run.plan.body.to_scene(values)
    run.results["orientation"] = meta | {"start": "identity at t0"}


def step_orientation_closed_form(run: Run):
    body, t = run.plan.body, run.plan.scene.times()
    run.data["t"] = t
    run.data["orientation"] = body.to_scene(_basis_paper(body, t))
    run.results["orientation"] = {"method": "closed form gamma_basis rows (gamma^(1) is the ss solution)"}


def step_orientation_integrate(run: Run):
    scene, body = run.plan.scene, run.plan.body
    t = scene.times()
    sol = solve(scene, body, t, body.to_paper(np.eye(3)))
    run.data["t"] = t    # orientation.csv and basis_sphere need it also when gamma is not asked for
    run.data["orientation"] = body.to_scene(sol.values)
    run.results["orientation"] = sol.summary() | {"start": "identity at t0"}


def step_integrals(run: Run):
    body = run.plan.body
    t, w = run.data["t"], run.data["omega"]
    energy = 0.5 * np.einsum("ni,ij,nj->n", w, body.tensor, w)
    g = run.data["gamma"]
    columns = {"F1": energy, "F2": np.einsum("ni,ni->n", g, g)}
    p = body.odd_integer_p
    if p is not None and p in gf.INTEGRAL_PS:
        wp, gp = run.data["omega_paper"], body.to_paper(g)
        columns["F3"] = gf.first_integral(p, body.d, wp[:, 0], wp[:, 1], gp[:, 0], gp[:, 1], gp[:, 2])
    run.data["integrals"] = (t, columns)
    run.results["integral_drift"] = {name: {"initial": float(v[0]), "max_abs_drift": float(np.max(np.abs(v - v[0])))}
                                     for name, v in columns.items()}


def step_angle_closed_form(run: Run):
    body = run.plan.body
    run.results["scattering_angle"] = {"radians": float(gf.scattering_angle(body.p, body.d)),
                                       "method": "closed form (Theorem 5.4, corrected: q = d)",
                                       "p": body.p, "d": body.d}


def general_angle(body) -> tuple[float, float]:
    """(angle, error bound) of any body by the closed form ``general_scattering_angle`` (paper-frame entries).

    The bound is the generated module's, absolute ``1e-13 (1 + |Y|)`` with ``Y = Im w_-``,
    ``w_-^2 = (u - i v).(u - i v)`` for omega = u tanh t + v sech t (numeric evidence against the mp twin).
    """
    u, v = body.u, body.v
    y = abs(cmath.sqrt(complex(u @ u - v @ v, -2.0 * (u @ v))).imag)
    return float(gf.general_scattering_angle(*body.entries)), 1e-13 * (1.0 + y)


GENERAL_ANGLE_METHOD = ("closed form of every body (Gauss's equation in s = sinh t, certified); error estimate: "
                        "the generated module's bound 1e-13 (1 + |Im w_-|), numeric evidence, not rigorous")


def step_angle_general_closed_form(run: Run):
    angle, bound = general_angle(run.plan.body)
    run.results["scattering_angle"] = {"radians": angle, "error_estimate": bound, "method": GENERAL_ANGLE_METHOD,
                                       "entries_paper_frame": [float(x) for x in run.plan.body.entries]}


def step_angle_enclosure(run: Run):
    from suslov.kernel.display import ball_fields
    from suslov.simulator import exact  # python-flint balls only when asked for

    body = run.plan.body.exact
    enclosure = exact.enclosure(body, dps=20)
    run.results["scattering_angle_enclosure"] = {
        **ball_fields(enclosure.angle),   # the printed ball and the radius agree
        "method": "closed form of every body (Gauss's equation in s = sinh t, certified) in ball arithmetic, rigorous, "
                  + body.whose(),
        "entries_paper_frame": body.entries_text(), "body": body.as_json()}


def step_galois_monodromy(run: Run):
    """The group decided exactly for the body as written (:func:`suslov.simulator.exact.galois_group`), beside
    the monodromy balls of that body (:func:`suslov.validated.monodromy`); when the monodromy would cost more
    than its time limit (``MonodromyTooCostly``) the exact decision stands alone and the result says why."""
    from suslov.simulator import exact  # python-flint balls only when asked for
    from suslov.validated import MonodromyTooCostly, monodromy

    body = run.plan.body.exact
    decided = exact.galois_group(body)
    entries = exact.ball_entries(body, 1200)
    try:
        result = monodromy(*entries, dps=GALOIS_DIGITS)
    except MonodromyTooCostly as error:
        certificates = [("the monodromy balls", "unknown", f"not computed: {error}")]
        verdict, liouvillian, radius = "unknown", None, None
    else:
        certificates = list(result.certificates)
        verdict, liouvillian, radius = result.verdict, result.liouvillian, result.radius
    contradiction = verdict in ("SO(3,C)", "reducible") and verdict != decided.group
    if not any("decided exactly" in c or "agrees with the exact decision" in c for c, _, _ in certificates):
        # monodromy() adds the exact decision itself for rational entries; here: ball entries, or no balls at all
        if contradiction:
            certificates.append(("the ball verdict agrees with the exact decision (Kimura)", "fail",
                                 f"balls: {verdict}, exact: {decided.group}"))
        else:
            claim = "the differential Galois group, decided exactly (Kimura's theorem on the body's Gauss equation)"
            certificates.append((claim, "pass", decided.reason))
    if not contradiction:   # a contradiction is kept as monodromy() keeps it: the balls' verdict, a failed certificate
        verdict, liouvillian = decided.group, decided.liouvillian
    run.results["galois_group"] = {"verdict": verdict, "liouvillian": liouvillian,
                                   "certificates": [{"claim": c, "outcome": o, "detail": d} for c, o, d in certificates],
                                   "largest_radius": radius, "decided_exactly": decided.group,
                                   "body": body.as_json()}


GALOIS_DIGITS = 20


def step_local_behaviour(run: Run):
    """Meromorphic, logarithmic or branching at the poles of omega, decided exactly for the body as written (the
    certified theorem for every p: :func:`suslov.simulator.exact.local_behaviour`)."""
    from suslov.simulator import exact

    body = run.plan.body.exact
    decided = exact.local_behaviour(body)
    run.results["local_behaviour"] = {"kind": decided.kind, "meromorphic": decided.meromorphic,
                                      "logarithmic": decided.logarithmic, "Lambda": decided.Lambda,
                                      "exponents_at_poles": decided.exponents, "reason": decided.reason,
                                      "method": decided.method, "body": body.as_json()}


def step_angle_integrate(run: Run):
    angle, error, sol = numeric_angle(run.plan.scene, run.plan.body)
    run.results["scattering_angle_integrated"] = {"radians": angle, "error_estimate": error,
                                                  "method": "numerical: ss integrated to lam t = 40"} | sol.summary()


def solve(scene, body, t, initial, t_start=None):
    """The scene's integrator: heyoka's Taylor method (``taylor``) or SciPy (``scipy:NAME``)."""
    if scene.method == "taylor":
        from suslov.simulator import taylor  # LLVM compilation only when a Taylor integration is planned
        return taylor.solve_poisson_taylor(body, t, initial, tol=scene.rtol, t_start=t_start)
    return integrate.solve_poisson(body, t, initial, scene.rtol, scene.atol, scene.method.split(":", 1)[1],
                                   t_start=t_start)


def numeric_angle(scene, body):
    """(angle, error estimate, Integration) of any body with the scene's integrator family (the cross-check)."""
    if scene.method == "taylor":
        from suslov.simulator import taylor
        return taylor.taylor_angle(body, tol=1e-12)
    return integrate.numeric_angle(body)


def step_sleigh_velocities(run: Run):
    t = run.plan.scene.times()
    v, w, theta = run.plan.body.velocities(t)
    run.data["t"] = t
    run.data["sleigh"] = {"v": v, "omega": w, "theta": theta}
    run.results["sleigh"] = {"turning_angle": run.plan.body.turning_angle(), "rate": run.plan.body.rate}


def step_sleigh_path(run: Run):
    x, y, nfev = run.plan.body.contact_point(run.data["t"])
    run.data["sleigh"].update(x=x, y=y)
    run.results["sleigh"] = {"turning_angle": run.plan.body.turning_angle(), "rate": run.plan.body.rate,
                             "quadrature_evaluations": nfev}


STEPS = {
    "omega": step_omega,
    "gamma_closed_form": step_gamma_closed_form,
    "gamma_integrate": step_gamma_integrate,
    "gamma_gauss": step_gamma_gauss,
    "orientation_closed_form": step_orientation_closed_form,
    "orientation_integrate": step_orientation_integrate,
    "orientation_gauss": step_orientation_gauss,
    "integrals": step_integrals,
    "angle_closed_form": step_angle_closed_form,
    "angle_general_closed_form": step_angle_general_closed_form,
    "angle_integrate": step_angle_integrate,
    "angle_enclosure": step_angle_enclosure,
    "galois_monodromy": step_galois_monodromy,
    "local_behaviour": step_local_behaviour,
    "sleigh_velocities": step_sleigh_velocities,
    "sleigh_path": step_sleigh_path,
}


def execute(plan: Plan, progress=None) -> Run:
    """Run the computation steps of ``plan`` (figures are drawn by :func:`write_outputs`)."""
    run = Run(plan)
    compute = [s for s in plan.steps if not s.name.startswith("figure:")]
    for i, step in enumerate(compute, 1):
        if progress:
            progress(f"[{i}/{len(compute)}] {step.name}: {step.method}")
        start = time.perf_counter()
        STEPS[step.name](run)
        run.executed.append({"step": step.name, "method": step.method, "seconds": time.perf_counter() - start})
    return run


def _csv(path: Path, header: list[str], columns: list[np.ndarray]):
    np.savetxt(path, np.column_stack(columns), delimiter=",", header=",".join(header), comments="", fmt="%.17g")


def _data_files(run: Run, out: Path) -> list[str]:
    written, d = [], run.data
    if "omega" in d and "omega" in run.plan.scene.effects:
        _csv(out / "omega.csv", ["t", "omega1", "omega2", "omega3"], [d["t"], *d["omega"].T])
        written.append("omega.csv")
    if "gamma" in d:
        _csv(out / "gamma.csv", ["t", "gamma1", "gamma2", "gamma3"], [d["t"], *d["gamma"].T])
        written.append("gamma.csv")
    if "orientation" in d:
        rows = d["orientation"].reshape(len(d["t"]), 9)
        names = [f"gamma{i}_{j}" for i in (1, 2, 3) for j in (1, 2, 3)]
        _csv(out / "orientation.csv", ["t", *names], [d["t"], *rows.T])
        written.append("orientation.csv")
    if "integrals" in d:
        t, cols = d["integrals"]
        _csv(out / "integrals.csv", ["t", *cols], [t, *cols.values()])
        written.append("integrals.csv")
    if "sleigh" in d:
        s = d["sleigh"]
        keys = [k for k in ("v", "omega", "theta", "x", "y") if k in s]
        _csv(out / "sleigh.csv", ["t", *keys], [d["t"], *(s[k] for k in keys)])
        written.append("sleigh.csv")
    return written


def _cell(text) -> str:
    """A Markdown table cell: a ``|`` inside it (as in "|omega|") must not end the cell."""
    return str(text).replace("|", "\\|").replace("\n", " ")


def _report(run: Run, files: list[str]) -> str:
    plan = run.plan
    lines = [f"# Scene {plan.scene.name}", "", plan.scene.description or "", "",
             f"Scene file: `{plan.scene.path.name}`", "", "## Plan and what ran", "", "```", plan.explain(), "```", "",
             "| step | method | seconds |", "|---|---|---|"]
    lines += [f"| {_cell(e['step'])} | {_cell(e['method'])} | {e['seconds']:.3f} |" for e in run.executed]
    lines += ["", "## Results", "", "```json", json.dumps(run.results, indent=1, sort_keys=True), "```", "",
              "## Files", ""] + [f"- `{f}`" for f in files]
    return "\n".join(lines) + "\n"


def write_outputs(run: Run, out, progress=None) -> list[str]:
    """Write data, figures, results.json and report.md into ``out`` atomically."""
    with staged(out) as staging:
        files = _data_files(run, staging)
        for step in run.plan.steps:
            if step.name.startswith("figure:"):
                from suslov.simulator import figures  # matplotlib only when a figure is drawn (none: core suffices)
                name = step.name.split(":", 1)[1]
                if progress:
                    progress(f"figure {name}")
                start = time.perf_counter()
                written = figures.draw(name, run, staging, run.plan.scene.figures_format)
                run.executed.append({"step": step.name, "method": step.method,
                                     "seconds": time.perf_counter() - start})
                files.extend(written)
        (staging / "results.json").write_text(json.dumps(
            {"scene": run.plan.scene.name, "results": run.results,
             "steps": [e["step"] for e in run.executed]}, indent=1, sort_keys=True) + "\n", encoding="utf-8")
        files.append("results.json")
        (staging / REPORT).write_text(_report(run, files), encoding="utf-8")
    return files
