"""A simulation result in a notebook (issue 47): ``Result._repr_html_`` of :mod:`suslov.simulator.api`.

What a cell showing ``suslov.simulate(scene)`` displays: the scene, one line per computed result (the
value first, then the method), the arrays and a sweep's table by shape, the steps that ran with their
seconds, and the scene's figures inline as PNG (base64 data URIs, drawn by :meth:`Result.plot` and closed
again, so nothing is left open for the inline backend).  Without matplotlib (a core install) the figures
are replaced by the one line naming the [sim] extra; everything else needs NumPy only.  The whole record
is folded underneath as JSON, as ``results.json`` holds it.
"""
from __future__ import annotations

import base64
import html
import io
import json

import numpy as np

from suslov.extras import FIGURES as FIGURE_LIBRARIES
from suslov.extras import install_hint, missing

__all__ = ["figure_png", "result_html", "summary"]

escape = html.escape
FIGURE_DPI = 80   # inline figures: about 450 x 350 pixels for the scenes' default sizes


def _number(x) -> str:
    """A float as Python prints it (the shortest text that reads back as the same float)."""
    return repr(float(x))


def summary(name: str, value) -> str:
    """One line of text for a computed result: its value first (escaped HTML)."""
    if not isinstance(value, dict):
        return escape(str(value))
    if "ball" in value:                                   # scattering_angle_enclosure
        return f"Δψ ∈ {escape(value['ball'].replace('+/-', '±'))} rad (rigorous)"
    if "radians" in value:                                # scattering_angle, scattering_angle_integrated
        error = value.get("error_estimate")
        bound = "" if error is None else f" (error estimate {float(error):.2g})"
        return f"Δψ = {_number(value['radians'])} rad{bound}"
    if "verdict" in value:                                # galois_group
        liouvillian = {True: "Liouvillian", False: "not Liouvillian"}.get(value.get("liouvillian"), "undecided")
        radius = value.get("largest_radius")
        balls = "" if radius is None else f"; monodromy balls up to {float(radius):.2g}"
        return (f"<b>{escape(str(value['verdict']))}</b>, {liouvillian} (decided exactly: "
                f"{escape(str(value.get('decided_exactly')))}{balls})")
    if "kind" in value:                                   # local_behaviour
        lam = "" if value.get("Lambda") is None else f", Λ = {value['Lambda']}"
        return f"<b>{escape(value['kind'])}</b> at every pole of ω{lam}"
    if "turning_angle" in value:                          # sleigh
        return f"turning angle {_number(value['turning_angle'])} rad"
    if name == "integral_drift":
        return "; ".join(f"{escape(k)}: largest drift {float(v['max_abs_drift']):.2g}" for k, v in value.items())
    if "error_estimate" in value or "norm_drift" in value:   # gamma, orientation by integration or closed form
        drift = value.get("norm_drift")
        error = value.get("error_estimate")
        extra = "".join([f", error estimate {float(error):.2g}" if error is not None else "",
                         f", |γ| drift {float(drift):.2g}" if drift is not None else ""])
        return extra.lstrip(", ") or "computed"
    rest = {k: v for k, v in value.items() if k != "method"}
    return escape(json.dumps(rest, default=str)[:300]) if rest else "computed"


def _method(value) -> str:
    return escape(str(value.get("method", ""))) if isinstance(value, dict) else ""


def figure_png(result, name: str) -> bytes:
    """Figure ``name`` of ``result`` as PNG bytes (drawn, saved into memory, closed)."""
    import matplotlib.pyplot as plt

    fig = result.plot(name)
    try:
        buffer = io.BytesIO()
        fig.savefig(buffer, format="png", dpi=FIGURE_DPI, metadata={"Software": None})
        return buffer.getvalue()
    finally:
        plt.close(fig)


def _figures(result) -> str:
    names = list(result.scene.figures)
    if not names:
        return ""
    absent = missing("sim", FIGURE_LIBRARIES)
    if absent:
        return (f"<p>figures {escape(', '.join(names))}: need the [sim] extra ({escape(', '.join(absent))} not "
                f"installed): <code>{escape(install_hint('sim'))}</code></p>")
    images = []
    for name in names:
        try:
            data = base64.b64encode(figure_png(result, name)).decode("ascii")
        except Exception as error:   # noqa: BLE001 (a display shows what failed instead of failing itself)
            images.append(f"<p>figure {escape(name)} could not be drawn: {escape(repr(error))}</p>")
            continue
        images.append(f"<figure style='display:inline-block;margin:0 8px'><img alt='{escape(name)}' "
                      f"src='data:image/png;base64,{data}'/><figcaption>{escape(name)}</figcaption></figure>")
    return "<div>" + "".join(images) + "</div>"


def _row(cells) -> str:
    return "<tr>" + "".join(f"<td style='text-align:left'>{c}</td>" for c in cells) + "</tr>"


def _table(header, rows) -> str:
    head = "<tr>" + "".join(f"<th style='text-align:left'>{h}</th>" for h in header) + "</tr>"
    return f"<table>{head}{''.join(_row(r) for r in rows)}</table>"


def result_html(result) -> str:
    scene = result.scene
    title = f": {escape(scene.title)}" if scene.title else ""
    parts = [f"<p><b>suslov Result of scene {escape(scene.name)}</b>{title}</p>"]
    if result.results:
        parts.append(_table(["effect", "value", "method"],
                            [[f"<code>{escape(k)}</code>", summary(k, v), _method(v)] for k, v in result.results.items()]))
    arrays = [[f"<code>{escape(k)}</code>", escape(str(np.shape(v)))] for k, v in result.data.items()
              if isinstance(v, np.ndarray)]
    if arrays:
        parts.append("<p>arrays (<code>result[name]</code>): " + ", ".join(f"{a} {s}" for a, s in arrays) + "</p>")
    if result.table:
        rows = len(next(iter(result.table.values())))
        parts.append(f"<p>table: {rows} rows, columns {escape(', '.join(result.table))}</p>")
    if result.steps:
        parts.append("<details><summary>steps that ran</summary>"
                     + _table(["step", "method", "seconds"],
                              [[escape(s["step"]), escape(s["method"]), f"{s['seconds']:.3f}"] for s in result.steps])
                     + "</details>")
    parts.append(_figures(result))
    if result.results:
        record = json.dumps(result.results, indent=1, sort_keys=True, default=str)
        parts.append(f"<details><summary>results (JSON)</summary><pre>{escape(record)}</pre></details>")
    return "".join(parts)
