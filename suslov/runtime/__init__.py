"""The machinery behind the generated module's public functions (issue 25: Python in ``.py`` files).

The generated module (``generated/suslov_formulas.py``, ``suslov.formulas`` in a wheel) holds what the
build emits: the printed formulas (``_omega``, ``_scattering_angle``, ...), the build's data
(``PMAX``, ``INTEGRAL_PS``, ``BASIS_PS``, ``_BASIS_SIGMA``) and thin public functions with generated
docstrings.  Those functions call the modules here, passing the emitted functions and data as
arguments, so this code is linted, imported and unit-tested as itself, and the build's round trip
still certifies the module *as a user imports it* (a fault here changes what the public functions
return, and the round trip compares those values with the certified objects).

One module per concern:

* :mod:`.angular` -- omega (case I13 = 0) and the general omega of any tensor, float and mpmath;
* :mod:`.integrals` -- the polynomial first integral: exact coefficients, float64 path, mp twin;
* :mod:`.basis` -- the orthonormal basis: ball series, float path with phase reduction, mp twin;
* :mod:`.angle` -- the scattering angle of Theorem 5.4: float, mpmath and ball forms;
* :mod:`.bodies` -- numeric inertia tensors: special-case parameters, Kovalevskaya exponents, meromorphy.

May import: ``suslov.kernel``, ``suslov.recipes`` (and NumPy, mpmath, python-flint); never SymPy,
``generated`` or ``derivations``.
"""
