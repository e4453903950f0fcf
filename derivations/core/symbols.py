"""The symbols shared by every derivation, with their assumptions.

Inertia tensor entries (paper section 2): ``I12 = 0`` by the choice of frame,
``det I = 1`` by normalisation; the constraint vector is ``a = (0, 0, 1)`` so
``omega3 = 0``.  Special case (section 4): ``I13 = 0`` and the parameters
``p`` (``eq:necc1``) and ``d`` with ``c = sqrt(d^2 + 1)`` (``eq:cpr``).
"""
import sympy as sp

I11, I22, I33 = sp.symbols("I11 I22 I33", positive=True)
I13, I23 = sp.symbols("I13 I23", real=True, nonzero=True)

w1, w2, w3 = sp.symbols("omega1 omega2 omega3", real=True)
g1, g2, g3 = sp.symbols("gamma1 gamma2 gamma3", real=True)
lam = sp.Symbol("lambda", real=True)

p = sp.Symbol("p", real=True, nonzero=True)
d = sp.Symbol("d", positive=True)
# Extension symbols: plain symbols, their relation lives in the Domain.
c = sp.Symbol("c")          # c**2 = d**2 + 1
r = sp.Symbol("r")          # r**2 = I11*I22, i.e. r = +-sqrt(I11*I22)
x = sp.Symbol("x")          # x = exp(t), used for residues at t = i*pi/2

omega = sp.Matrix([w1, w2, 0])
gamma = sp.Matrix([g1, g2, g3])


def from_symengine(expr, *symbols: sp.Symbol) -> sp.Expr:
    """A symengine result as SymPy with ``symbols`` (SymPy symbols with their assumptions) put back by name:
    symengine keeps a symbol's name, not its assumptions, so a plain ``Symbol("d")`` would otherwise stand
    beside the positive ``d`` as a second generator.  Other names stay plain symbols.

    >>> import symengine as se
    >>> from_symengine(se.Symbol("d") ** 2 + se.Symbol("t"), d).free_symbols == {d, sp.Symbol("t")}
    True
    """
    value = sp.sympify(expr)
    own = {s.name: s for s in symbols}
    return value.xreplace({s: own[s.name] for s in value.free_symbols if s.name in own and s != own[s.name]})
