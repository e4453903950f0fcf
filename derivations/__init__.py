"""Symbolic layer: derive the paper's formulas, certify them, hand them to the renderer.

Never imported by the runtime package or by ``generated/`` (docs/design.md, data flow).  Three layers,
each importing only the ones below it (``tests/test_architecture.py`` checks it):

* :mod:`derivations.output` -- the build's stages after the derivations: pipeline (derive ->
  certify -> render -> round trip), rendering, the round trip of the emitted module, PDF, diff;
* :mod:`derivations.registry` -- the derivations the build knows, in dependency order;
* :mod:`derivations.sections` -- one module per section of the paper (model, special case,
  Kovalevskaya exponents, residues and logarithms, hypergeometric form, meromorphic solutions,
  first integrals, scattering angle, Galois analysis);
* :mod:`derivations.core` -- the certification machinery (certificates, exact zero tests, numeric
  evidence, balls, cache, options, symbols, typesetting, the paper's printed forms).

A new derivation goes into ``sections/`` and into ``registry.py``; a new kind of certificate into
``core/``; a new output file into ``output/pipeline.py``'s ``OUTPUTS`` with its template.
"""
