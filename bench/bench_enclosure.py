"""What rigour costs: validated enclosures of the scattering angle against the non-rigorous routes (issue 16).

Measured side by side in one run, on one general body (I13 != 0) and one body with I13 = 0:

* ``suslov.validated.scattering_angle_enclosure`` at widths 1e-12 and 1e-30 (targets: 0.5 s and 10 s);
* the simulator's DOP853 float route (``suslov.simulator.integrate.numeric_angle``, error *estimate* only);
* the 36-digit mpmath route of the build's old evidence grid (``derivations.sections.poisson_taylor.ss_through``);
* the build's grid certificate: 24 points at 36 digits of evidence (old) against 18 enclosed points at
  1e-18 plus 6 fast-rotation points of evidence (new).

Run: ``python bench/bench_enclosure.py`` (about 2 minutes); writes ``bench/results/enclosure.md`` and
``.json``.  Medians of 5 runs (2 for the grid) on a shared 2-core machine.
"""
from __future__ import annotations

import json
import platform
import sys
from pathlib import Path

import mpmath
import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))

from machine_info import cpu_name  # noqa: E402
from timing import median_seconds  # noqa: E402

from derivations.sections import scattering_balls, scattering_evidence  # noqa: E402
from derivations.core.certificates import CertificateLog  # noqa: E402
from derivations.sections.poisson_taylor import ss_through  # noqa: E402
from suslov.simulator.body import make_body  # noqa: E402
from suslov.simulator.integrate import numeric_angle  # noqa: E402
from suslov.validated import omega_coefficients, scattering_angle_enclosure  # noqa: E402

GENERAL = ("5/4", "1", "3/10", "-1/2")
SPECIAL = ("5/4", "1", "0", "-1/4")          # I13 = 0: p = 2, d = 1/2


def floats(body):
    return [float(eval(x)) if "/" in x else float(x) for x in body]  # noqa: S307 (fixed literals above)


def row(name, body):
    rows = []
    for digits in (12, 30):
        seconds = median_seconds(lambda digits=digits: scattering_angle_enclosure(*body, dps=digits, method="integration"), 5)
        width = scattering_angle_enclosure(*body, dps=digits, method="integration").width
        rows.append({"body": name, "route": f"enclosure, digits={digits}", "seconds": seconds, "width": width,
                     "rigorous": True})
    I11, I22, I13, I23 = floats(body)
    tensor = np.array([[I11, 0, I13], [0, I22, I23], [I13, I23, (1 + I11 * I23**2 + I22 * I13**2) / (I11 * I22)]])
    sim = make_body(tensor=tensor)
    seconds = median_seconds(lambda: numeric_angle(sim), 5)
    _, error, _ = numeric_angle(sim)
    rows.append({"body": name, "route": "DOP853 float (simulator)", "seconds": seconds, "width": 2 * error,
                 "rigorous": False})
    uu, vv = omega_coefficients(*body)
    with mpmath.workdps(50):
        u_mp = [mpmath.mpf(x.mid().str(40, radius=False)) for x in uu]
        v_mp = [mpmath.mpf(x.mid().str(40, radius=False)) for x in vv]
        seconds = median_seconds(lambda: ss_through(u_mp, v_mp, 36), 5)
    rows.append({"body": name, "route": "mpmath 36 digits (old evidence route)", "seconds": seconds, "width": None,
                 "rigorous": False})
    return rows


def grid_rows():
    old_d = ("0.05", "0.5", "2", "50")

    def old():
        saved = scattering_evidence.GRID_D
        scattering_evidence.GRID_D = old_d
        try:
            scattering_evidence.fast_rotation_certificate(CertificateLog(derivation="bench"))
        finally:
            scattering_evidence.GRID_D = saved

    def new():
        log = CertificateLog(derivation="bench")
        scattering_balls.grid(log)
        scattering_evidence.fast_rotation_certificate(log)

    return [{"body": "build grid", "route": "old: 24 points, 36-digit evidence", "seconds": median_seconds(old, 2),
             "width": None, "rigorous": False},
            {"body": "build grid", "route": "new: 18 points enclosed to 1e-18 + 6 points evidence",
             "seconds": median_seconds(new, 2), "width": 1e-18, "rigorous": True}]


def main():
    rows = row("general (I13 = 3/10, I23 = -1/2)", GENERAL) + row("I13 = 0 (p = 2, d = 1/2)", SPECIAL) + grid_rows()
    machine = f"{cpu_name()}, {platform.python_version()}, 2 cores (shared)"
    lines = ["# Enclosures of the scattering angle: what rigour costs", "",
             f"Machine: {machine}. Command: `python bench/bench_enclosure.py`. Medians (5 runs; 2 for the grid).", "",
             "| body | route | seconds | width | rigorous |", "| --- | --- | ---: | ---: | --- |"]
    for r in rows:
        width = "-" if r["width"] is None else f"{r['width']:.1e}"
        lines.append(f"| {r['body']} | {r['route']} | {r['seconds']:.3f} | {width} | {'yes' if r['rigorous'] else 'no'} |")
    lines += ["", "Targets (issue 16): width 1e-12 in at most 0.5 s, width 1e-30 in at most 10 s (general body); the "
              "build's scattering certificates by enclosure add at most 10 s to the default build.", ""]
    out = ROOT / "bench" / "results"
    (out / "enclosure.md").write_text("\n".join(lines), encoding="utf-8")
    (out / "enclosure.json").write_text(json.dumps({"machine": machine, "rows": rows}, indent=1) + "\n",
                                        encoding="utf-8")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
