"""Figures for scenes (the paper's missing Figs. 1-5), drawn with matplotlib's Agg backend.

Each figure draws data the engine already computed; none computes anything itself, except the
reference curves a reader needs to read it (the energy ellipse, the equilibria line, the limit
value of gamma1), which are closed forms of the body.  Fig. 1: ``omega_plane`` (omega on the plane
(omega1, omega2) from the unstable to the stable equilibrium, section 2/eq:o12); Fig. 2:
``gamma_components`` or ``gamma_sphere`` (a solution with boundary condition ``ss``, section 5.1);
Fig. 3: ``sleigh_path`` (contact point of the Chaplygin sleigh, its blade and direction of motion,
section 4); Figs. 4, 5: ``basis_sphere`` (gamma^(1) and gamma^(2) on the unit sphere, body frame,
Theorem 6.1).

Conventions (why): titles come from the scene (``title``, else its name), never from the function,
so a figure is not mislabelled when reused; every line and marker is in a legend; labels are
mathtext; each figure is written in every format the scene asks for (``figures_format``, PNG and
PDF), with the metadata that would change between runs removed so outputs are byte-identical.
"""
from __future__ import annotations

from pathlib import Path

import matplotlib
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.legend_handler import HandlerBase
from matplotlib.patches import FancyArrow
from matplotlib.quiver import Quiver

matplotlib.use("Agg")   # no display needed; switching is allowed as long as no figure exists yet

FORMATS = ("png", "pdf", "svg")
METADATA = {  # no version or time stamps: byte-identical files across runs
    "png": {"Software": None},
    "pdf": {"Creator": None, "Producer": None, "CreationDate": None},
    "svg": {"Creator": None, "Date": None},
}


# SVG element ids are salted with a random uuid unless this is set: fixed, so SVG files are reproducible too
RC = {"svg.hashsalt": "suslov-figures"}


class _ArrowKey(HandlerBase):
    """Legend key of a quiver drawn as an arrow (matplotlib's default key for it is a filled box)."""

    def create_artists(self, legend, orig_handle, xdescent, ydescent, width, height, fontsize, trans):
        return [FancyArrow(-xdescent, height / 2 - ydescent, width, 0, width=0.12 * height, head_width=0.7 * height,
                           head_length=0.35 * width, length_includes_head=True,
                           color=orig_handle.get_facecolor()[0], transform=trans)]


def _title(run) -> str:
    scene = run.plan.scene
    return getattr(scene, "title", "") or scene.name


def _sphere(ax):
    u, v = np.mgrid[0:2 * np.pi:40j, 0:np.pi:20j]
    ax.plot_wireframe(np.cos(u) * np.sin(v), np.sin(u) * np.sin(v), np.cos(v), color="0.85", linewidth=0.4,
                      label=r"unit sphere $|\gamma|=1$")
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):   # three ticks: the default quarter ticks overlap at this size
        axis.set_ticks([-1, 0, 1])
    ax.set_xlabel(r"$e_1$")
    ax.set_ylabel(r"$e_2$")
    ax.set_zlabel(r"$e_3$")
    ax.set_box_aspect((1, 1, 1))


def _ends(ax, points, *args):
    """Start (open circle) and end (filled) markers of a path, with legend entries."""
    ax.plot(*points[0], *args, "o", mfc="white", mec="k", ms=7, label="start of the window")
    ax.plot(*points[-1], *args, "o", color="k", ms=6, label="end of the window")


def omega_plane(run):
    body, w = run.plan.body, run.data["omega_paper"]
    fig, ax = plt.subplots(figsize=(6, 5.5))
    s = np.linspace(-12, 12, 600)
    ell = body.rate * (np.outer(np.tanh(s), body.u) + np.outer(1 / np.cosh(s), body.v))
    ax.plot(ell[:, 0], ell[:, 1], color="0.6", lw=0.8, ls="--", label=r"energy level $F_1=$ const")
    ax.plot(-ell[:, 0], -ell[:, 1], color="0.6", lw=0.8, ls="--")
    ax.plot(w[:, 0], w[:, 1], color="C0", lw=2, label=r"$\omega(t)$ on the window")
    lim = body.rate * body.u
    span = 1.3 * np.linalg.norm(lim)
    direction = lim / np.linalg.norm(lim)
    ax.plot([-span * direction[0], span * direction[0]], [-span * direction[1], span * direction[1]], color="k",
            lw=0.8, label=r"equilibria $I_{13}\omega_1+I_{23}\omega_2=0$")
    ax.plot(*lim, "o", color="k", ms=9, label=r"stable equilibrium ($t\to+\infty$)")
    ax.plot(*(-lim), "o", mfc="white", mec="k", ms=9, label=r"unstable equilibrium ($t\to-\infty$)")
    ax.set_xlabel(r"$\omega_1$")
    ax.set_ylabel(r"$\omega_2$")
    ax.set_aspect("equal")
    ax.legend(fontsize=7, loc="best")
    ax.set_title(_title(run), fontsize=9)
    return fig


def gamma_components(run):
    t, g = run.data["t"], run.data["gamma"]
    body = run.plan.body
    fig, ax = plt.subplots(figsize=(7.5, 4.2))
    for i in range(3):
        ax.plot(t, g[:, i], label=rf"$\gamma_{i + 1}(t)$")
    ax.set_xlabel(r"$t$")
    angle = run.results.get("scattering_angle", {}).get("radians")
    title = _title(run)
    if angle is not None:
        if body.special:   # the limit axis is e1: gamma1 itself converges, to -cos(Delta psi)
            ax.axhline(-np.cos(angle), color="0.4", ls=":", lw=1.2,
                       label=r"$\gamma_1(+\infty)=-\cos\Delta\psi$ (Theorem 5.4)")
        else:              # the components keep turning about the limit axis n; <gamma, n> converges
            n = body.to_scene(body.limit_axis())
            ax.plot(t, g @ n, color="k", lw=1.6, ls="--", label=r"$\langle\gamma(t), n\rangle$, $n$ the limit axis")
            ax.axhline(-np.cos(angle), color="0.4", ls=":", lw=1.2, label=r"$-\cos\Delta\psi$ (its limit)")
        title += rf", $\Delta\psi={angle:.6f}$"
    ax.legend(fontsize=8, loc="best")
    ax.set_title(title, fontsize=9)
    return fig


def gamma_sphere(run):
    g = run.data["gamma"]
    fig = plt.figure(figsize=(5.5, 5.5))
    ax = fig.add_subplot(projection="3d")
    _sphere(ax)
    ax.plot(g[:, 0], g[:, 1], g[:, 2], color="C0", lw=1.2, label=r"$\gamma(t)$")
    _ends(ax, g)
    ax.legend(fontsize=7, loc="upper left")
    ax.set_title(_title(run) + " (body frame)", fontsize=9)
    return fig


def basis_sphere(run):
    B = run.data["orientation"]
    fig = plt.figure(figsize=(10, 5.2))
    for k in range(2):
        ax = fig.add_subplot(1, 2, k + 1, projection="3d")
        _sphere(ax)
        g = B[:, k, :]
        ax.plot(g[:, 0], g[:, 1], g[:, 2], color=f"C{k}", lw=1.2, label=rf"$\gamma^{{({k + 1})}}(t)$")
        _ends(ax, g)
        ax.legend(fontsize=7, loc="upper left")
        ax.set_title(rf"$\gamma^{{({k + 1})}}(t)$ in the body frame", fontsize=10)
    body = run.plan.body
    given = getattr(run.plan.scene, "title", "")
    suffix = f" ($p={body.p:g}$, $d={body.d:g}$)" if body.special and not given else ""
    fig.suptitle(_title(run) + suffix, fontsize=10)
    return fig


def sleigh_path(run):
    s = run.data["sleigh"]
    x, y, theta, v = s["x"], s["y"], s["theta"], s["v"]
    offset = run.plan.body.offset
    span = max(np.ptp(x), np.ptp(y))
    fig, ax = plt.subplots(figsize=(6.5, 6))
    ax.plot(x, y, color="C0", lw=1.2, label="path of the contact point")
    instants = np.linspace(0, len(x) - 1, 9).astype(int)
    blade = 0.025 * span
    for n, i in enumerate(instants):
        cos, sin = np.cos(theta[i]), np.sin(theta[i])
        ax.plot([x[i] - blade * cos, x[i] + blade * cos], [y[i] - blade * sin, y[i] + blade * sin], color="C3",
                lw=3, solid_capstyle="butt", label="blade (equal time steps)" if n == 0 else None)
        # one artist per instant (arm and its end marker), so the legend entry shows both
        ax.plot([x[i], x[i] + offset * cos], [y[i], y[i] + offset * sin], color="0.3", lw=0.8, marker="s", ms=4,
                markevery=[1], label="centre of mass (ahead of the blade)" if n == 0 else None)
    # direction of motion: arrows beside the path (the contact point moves along the blade, sign of v)
    arrows = [i for i in instants[1:-1] if abs(v[i]) > 0.05 * np.max(np.abs(v))]   # none where the sleigh stops
    heading = np.sign(v[arrows])
    normal = np.stack([-np.sin(theta[arrows]), np.cos(theta[arrows])], axis=-1) * 0.05 * span
    ax.quiver(x[arrows] + normal[:, 0], y[arrows] + normal[:, 1], heading * np.cos(theta[arrows]),
              heading * np.sin(theta[arrows]), color="k", angles="xy", scale_units="xy", scale=1 / (0.07 * span),
              width=0.005, label="direction of motion")
    ax.plot(x[0], y[0], "o", mfc="white", mec="k", ms=7, label="start of the window")
    ax.plot(x[-1], y[-1], "o", color="k", ms=6, label="end of the window")
    # equal aspect in a square frame, so the path is not squeezed into a narrow strip
    cx, cy = (x.max() + x.min()) / 2, (y.max() + y.min()) / 2
    half = 0.55 * span + offset
    ax.set_xlim(cx - half, cx + half)
    ax.set_ylim(cy - half, cy + half)
    ax.set_aspect("equal")
    ax.set_xlabel(r"$x$")
    ax.set_ylabel(r"$y$")
    turn = run.results["sleigh"]["turning_angle"]
    ax.set_title(_title(run) + rf": the blade turns by ${np.degrees(turn):.2f}^\circ$", fontsize=9)
    ax.legend(fontsize=8, loc="best", handler_map={Quiver: _ArrowKey()})
    return fig


DRAW = {"omega_plane": omega_plane, "gamma_components": gamma_components, "gamma_sphere": gamma_sphere,
        "basis_sphere": basis_sphere, "sleigh_path": sleigh_path}


def figure(name, run):
    """The matplotlib Figure of ``name`` for ``run`` (not saved; the caller closes it)."""
    return DRAW[name](run)


def save_formats(fig, stem, formats=("png",)) -> list[str]:
    """Save ``fig`` as ``stem.<fmt>`` for each format, reproducibly; returns the file names."""
    written = []
    with matplotlib.rc_context(RC):
        for fmt in formats:
            fig.savefig(f"{stem}.{fmt}", dpi=110, metadata=METADATA[fmt])
            written.append(f"{Path(stem).name}.{fmt}")
    return written


def draw(name, run, directory, formats=("png",)) -> list[str]:
    """Write figure ``name`` into ``directory`` in each format; returns the file names."""
    with matplotlib.rc_context(RC):
        fig = figure(name, run)
    try:
        return save_formats(fig, Path(directory) / name, formats)
    finally:
        plt.close(fig)
