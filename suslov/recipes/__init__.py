"""Recipes written once and run twice: by the build (exactly, with symbolic d) and by the module.

A recipe is the construction of a certified object, written with ring operations only
(``+``, ``-``, ``*``, ``**`` and the few operations a *ring adapter* provides).  The build
(``derivations/``) runs it on python-flint polynomials with d as a variable and certifies
the result exactly for every p; the generated module runs the very same function on
:class:`suslov.kernel.sparse.Sparse` polynomials whose coefficients are ``Fraction`` or
``mpmath`` numbers for a numeric d.  So the formula is not implemented twice, and the
build's round trip (``derivations/output/roundtrip.py``) re-runs the module's entry points in
exact arithmetic and compares them with the certified objects.

* :mod:`.integrals`  P1, P2, P3 of the first integral for odd p (section 6.2, Theorem 6.2);
* :mod:`.basis`      the numerators of the orthonormal basis of Poisson solutions for odd p
  (sections 5.1, 6.1, Theorem 6.1 corrected);
* :mod:`.rings`      the run-time ring adapters (Fractions, mpmath).

Pure Python: no NumPy, SymPy or python-flint import here.
"""
