"""
From a body to its Galois group, its scattering angle and the formula catalog
=============================================================================

A tour of what the package says about one rigid body, each answer an object that displays itself in a
notebook (HTML and LaTeX, as SymPy's and pandas' objects do): the differential Galois group of its
Poisson equations, decided exactly; the behaviour of their solutions at the poles of omega; the
scattering angle in closed form and as a rigorous ball; the parameters A, B, C of the body's Gauss
hypergeometric equation; the certified formulas behind them in the catalog; and a figure of the angle
over a range of one inertia entry, with the Liouvillian bodies marked.

The body: an inertia tensor in the paper's frame (I12 = 0, constraint axis a = e3) with I13 != 0, a
case the paper leaves open (its Conclusion).  Entries given as strings are read as the exact
decimals they are, so every exact decision below is about this body, not about its float64 neighbour.
This page is also a Jupyter notebook: ``docs/examples/catalog_tour.ipynb`` (the same cells).
"""
from fractions import Fraction

import matplotlib.pyplot as plt
import numpy as np

import suslov
from suslov import validated

inertia = [["5/4", 0, "3/10"],
           [0, 1, "-1/2"],
           ["3/10", "-1/2", "3/2"]]
I11, I22, I13, I23 = inertia[0][0], inertia[1][1], inertia[0][2], inertia[1][2]
print(f"I11 = {I11}, I22 = {I22}, I13 = {I13}, I23 = {I23} (I33 does not enter: omega and the angle depend on "
      "these four)")

# %%
# The differential Galois group
# -----------------------------
# Decided exactly by Kimura's theorem on the body's Gauss equation: ``u.v != 0`` here, so the group is
# SO(3, C) and the Poisson equations have no Liouvillian solution basis.  In a notebook the result shows
# itself (``_repr_html_``, ``_repr_latex_``); printed, it is the dataclass.
group = validated.galois_group(I11, I22, I13, I23)
print(group.group, "| Liouvillian:", group.liouvillian)
group

# %%
# The same question by the monodromy balls (the independent route: four loops about the singular points
# of the Poisson equations in x = e^t, validated integration at 15 digits) agrees.
monodromy = validated.monodromy(I11, I22, I13, I23, dps=15)
print(monodromy.verdict, "| largest radius", f"{monodromy.radius:.1e}")

# %%
# Local behaviour at the poles of omega
# -------------------------------------
# At every pole of omega = u tanh t + v sech t the solutions are meromorphic, logarithmic or branching,
# decided by the Kovalevskaya exponent Lambda (a theorem for every p, certified by the build).  Beside
# the general body, the special case p = 3, d = 1 (I13 = 0: I11 = c^2 = 1 + d^2 = 2, I22 = 1,
# I23 = -I22 d / p = -1/3), where Lambda = p = 3 is odd.
behaviour = validated.local_behaviour(I11, I22, I13, I23)
special = (2, 1, 0, Fraction(-1, 3))
print("general body:", behaviour.kind, "| p = 3, d = 1:", validated.local_behaviour(*special).kind,
      "| its group:", validated.galois_group(*special).group)
behaviour

# %%
# The scattering angle
# --------------------
# ``suslov.general_scattering_angle`` is the certified closed form of every body in float64 (Gauss's
# equation in s = sinh t); ``scattering_angle_enclosure`` evaluates the same closed form in ball arithmetic,
# a rigorous enclosure at the digits asked for.
angle = suslov.general_scattering_angle(*(float(Fraction(x)) for x in (I11, I22, I13, I23)))
enclosure = validated.scattering_angle_enclosure(I11, I22, I13, I23, dps=30)
print(f"float64 closed form: {float(angle)!r} rad")
print(f"ball:                {enclosure.angle} (width {enclosure.width:.1e})")
print(f"difference: {abs(float(angle) - float(enclosure.angle.mid())):.1e} (the float64 bound: 1e-13 (1 + |Im w_-|))")
enclosure

# %%
# Gauss's hypergeometric equation of the body
# -------------------------------------------
# z(1 - z)F'' + (C - (A + B + 1)z)F' - AB F = 0 with z = (1 + i sinh t)/2: A, B, C are complex balls, and
# the invariants they come from (``U^2``, ``Re w_-^2``, ``Im w_-^2``) are exact.
form = validated.hypergeometric_form(I11, I22, I13, I23, dps=20)
print("A =", form.A)
print("B =", form.B)
print("C =", form.C)
print("exact:", form.exact)
form

# %%
# The formulas behind these answers: the catalog
# ----------------------------------------------
# Every certified formula of the documents is an entry of ``suslov.catalog``: the paper's label, the
# hypotheses, the certificates the build recorded, and the formula (LaTeX here; SymPy, Mathematica,
# Maple and JSON from ``entry.expr``, ``entry.mathematica``, ...; those need SymPy, the ``[catalog]`` extra).
from suslov import catalog

entry = catalog["general_angle"]
print(entry)
print("paper:", ", ".join(entry.numbers) or entry.labels)
print("hypotheses:", "; ".join(entry.hypotheses))
print([(c["key"], c["kind"], c["outcome"]) for c in entry.certificates][:4])
entry   # in a notebook: the formula, typeset, with its certificates

# %%
# A family takes its parameter: the first integral of Theorem 6.2 (corrected) for p = 5, as SymPy and as
# Mathematica input.
P = catalog["first_integrals"](p=5)
print(P.expr[0])
print(P.mathematica[:200], "...")

# %%
# The angle over one inertia entry, and the Liouvillian bodies
# ------------------------------------------------------------
# Along I13 = 0 (I11 = 2, I22 = 1, d = 1) the entry I23 = -1/p sets p; the Galois group is reducible
# (Liouvillian) exactly for odd p, where the angle is pi (Theorem 5.4:
# ``cos(angle/2) = |cos(pi p/2)| / cosh(pi p/(2d))``).  Those bodies are decided exactly and marked; off that
# line (I13 = 0.1) no body of this range is Liouvillian.
i23 = np.linspace(-1.25, -0.13, 600)
fig, ax = plt.subplots(figsize=(6.4, 4.0))
ax.plot(i23, suslov.general_scattering_angle(2.0, 1.0, 0.0, i23), label=r"$I_{13}=0$")
ax.plot(i23, suslov.general_scattering_angle(2.0, 1.0, 0.1, i23), "--", label=r"$I_{13}=0.1$")
odd = [p for p in range(1, 8) if validated.galois_group(2, 1, 0, Fraction(-1, p)).liouvillian]
marks = [-1.0 / p for p in odd]
ax.plot(marks, [float(validated.scattering_angle_enclosure(2, 1, 0, Fraction(-1, p), dps=15).angle.mid()) for p in odd],
        "o", color="C3", label="Liouvillian (reducible group): odd $p$")
for k, (p, x) in enumerate(zip(odd, marks)):
    ax.annotate(f"p = {p}", (x, np.pi), textcoords="offset points", xytext=(0, 7 + 10 * (k % 2)), ha="center",
                fontsize=8)
ax.set_xlabel(r"$I_{23}$  ($I_{11}=2$, $I_{22}=1$)")
ax.set_ylabel(r"scattering angle $\Delta\psi$ (rad)")
ax.set_ylim(2.6, 3.3)
ax.legend(loc="lower right")
ax.set_title("The closed form of every body; Liouvillian bodies decided exactly")
print("Liouvillian for p =", odd)
