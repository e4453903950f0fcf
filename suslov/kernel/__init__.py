"""Numerical machinery of the generated module that is not a formula.

The formulas themselves are emitted by the build into ``generated/suslov_formulas.py``;
what lives here is the code every formula shares (docs/design.md, "Generated outputs"):

* :mod:`.validate`   argument checks with messages that name the field, the value and why;
* :mod:`.contexts`   one formula, several number contexts (float64, mpmath, and any object
  with ``tanh``/``sech``/``sqrt``), as in mpmath's ``ctx_fp``/``ctx_mp``;
* :mod:`.sparse`     a small sparse polynomial type with generic coefficients (the shared
  recipes of :mod:`suslov.recipes` run on it with Fractions or mpmath numbers);
* :mod:`.horner`     stable evaluation of homogeneous polynomials (first integrals);
* :mod:`.phase`      exact argument reduction: the phase (p/d) t in double-double, pi p/2;
* :mod:`.fourier`    x^m/(1+x^2)^p as trigonometric polynomials in th = 2 arctan(e^-t);
* :mod:`.scalars`    scalar in, scalar out: the float routes return NumPy scalars as ufuncs do.

Importing this package needs NumPy and mpmath only: no SymPy, no python-flint, and no
import of ``generated`` (so ``generated`` can import it without a cycle).
"""
