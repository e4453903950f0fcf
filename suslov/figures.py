"""Figures for scenes (the paper's missing Figs. 1-5), drawn with matplotlib's Agg backend.

Each figure draws data the engine already computed; none computes anything
itself.  Fig. 1: ``omega_plane`` (omega on the plane (omega1, omega2), the
equilibria line, stable and unstable equilibria); Fig. 2: ``gamma_components``
or ``gamma_sphere`` (a solution with boundary condition ``ss``); Fig. 3:
``sleigh_path`` (contact point of the Chaplygin sleigh); Figs. 4, 5:
``basis_sphere`` (gamma^(1) and gamma^(2) on the unit sphere, body frame).
"""
from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

METADATA = {"Software": None}  # no version/time stamps in the PNG


def _save(fig, path):
    fig.savefig(path, dpi=110, metadata=METADATA)
    plt.close(fig)


def _sphere(ax):
    u, v = np.mgrid[0:2 * np.pi:40j, 0:np.pi:20j]
    ax.plot_wireframe(np.cos(u) * np.sin(v), np.sin(u) * np.sin(v), np.cos(v), color="0.85", linewidth=0.4)
    ax.set_xlabel(r"$e_1$")
    ax.set_ylabel(r"$e_2$")
    ax.set_zlabel(r"$e_3$")
    ax.set_box_aspect((1, 1, 1))


def omega_plane(run, path):
    body, w = run.plan.body, run.data["omega_paper"]
    fig, ax = plt.subplots(figsize=(5.5, 5))
    s = np.linspace(-12, 12, 600)
    ell = body.rate * (np.outer(np.tanh(s), body.u) + np.outer(1 / np.cosh(s), body.v))
    ax.plot(ell[:, 0], ell[:, 1], color="0.7", lw=0.8, ls="--", label="energy level (other half: branch -1)")
    ax.plot(-ell[:, 0], -ell[:, 1], color="0.7", lw=0.8, ls="--")
    ax.plot(w[:, 0], w[:, 1], color="C0", lw=2, label=r"$\omega(t)$")
    lim = body.rate * body.u
    span = 1.3 * np.linalg.norm(lim)
    direction = lim / np.linalg.norm(lim)
    ax.plot([-span * direction[0], span * direction[0]], [-span * direction[1], span * direction[1]], color="k",
            lw=0.8, label=r"equilibria $I_{13}\omega_1+I_{23}\omega_2=0$")
    ax.plot(*lim, "o", color="k", ms=8, label="stable (t -> +oo)")
    ax.plot(*(-lim), "o", mfc="white", mec="k", ms=8, label="unstable (t -> -oo)")
    ax.set_xlabel(r"$\omega_1$")
    ax.set_ylabel(r"$\omega_2$")
    ax.set_aspect("equal")
    ax.legend(fontsize=7, loc="best")
    ax.set_title(f"Fig. 1: omega(t), {run.plan.scene.name}", fontsize=9)
    _save(fig, path)


def gamma_components(run, path):
    t, g = run.data["t"], run.data["gamma"]
    fig, ax = plt.subplots(figsize=(7, 4))
    for i in range(3):
        ax.plot(t, g[:, i], label=rf"$\gamma_{i + 1}$")
    ax.set_xlabel("t")
    ax.legend()
    angle = run.results.get("scattering_angle", {}).get("radians")
    title = "Fig. 2: gamma(t), boundary condition ss" if isinstance(run.plan.scene.initial, str) else "gamma(t)"
    if angle is not None:
        ax.axhline(-np.cos(angle), color="0.5", ls=":", lw=1)
        title += rf", $\Delta\psi$ = {angle:.6f}"
    ax.set_title(title, fontsize=9)
    _save(fig, path)


def gamma_sphere(run, path):
    g = run.data["gamma"]
    fig = plt.figure(figsize=(5.5, 5.5))
    ax = fig.add_subplot(projection="3d")
    _sphere(ax)
    ax.plot(g[:, 0], g[:, 1], g[:, 2], color="C0", lw=1)
    ax.plot(*g[0], "o", mfc="white", mec="k")
    ax.plot(*g[-1], "o", color="k")
    ax.set_title("gamma(t) on the sphere (body frame)", fontsize=9)
    _save(fig, path)


def basis_sphere(run, path):
    B = run.data["orientation"]
    fig = plt.figure(figsize=(10, 5))
    for k in range(2):
        ax = fig.add_subplot(1, 2, k + 1, projection="3d")
        _sphere(ax)
        g = B[:, k, :]
        ax.plot(g[:, 0], g[:, 1], g[:, 2], color=f"C{k}", lw=1)
        ax.plot(*g[0], "o", mfc="white", mec="k")
        ax.plot(*g[-1], "o", color="k")
        ax.set_title(rf"$\gamma^{{({k + 1})}}(t)$", fontsize=10)
    body = run.plan.body
    fig.suptitle(f"gamma^(1), gamma^(2) in the body frame, p = {body.p:g}, d = {body.d:g}" if body.special
                 else "two solutions in the body frame", fontsize=10)
    _save(fig, path)


def sleigh_path(run, path):
    s = run.data["sleigh"]
    fig, ax = plt.subplots(figsize=(6, 5))
    ax.plot(s["x"], s["y"], color="C0", lw=1.5)
    idx = np.linspace(0, len(s["x"]) - 1, 41).astype(int)
    ax.plot(s["x"][idx], s["y"][idx], ".", color="C3", ms=4, label="equal time steps")
    ax.set_aspect("equal")
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    turn = run.results["sleigh"]["turning_angle"]
    ax.set_title(f"Fig. 3: contact point of the Chaplygin sleigh; blade turns by {np.degrees(turn):.2f} deg",
                 fontsize=9)
    ax.legend(fontsize=8)
    _save(fig, path)


DRAW = {"omega_plane": omega_plane, "gamma_components": gamma_components, "gamma_sphere": gamma_sphere,
        "basis_sphere": basis_sphere, "sleigh_path": sleigh_path}


def draw(name, run, path):
    DRAW[name](run, path)
