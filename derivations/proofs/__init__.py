"""Proven float64 error bounds of the emitted module's functions (issue 34; a package of its own since issue 43).

``float_bounds`` is the rounding-error arithmetic (FE values: Higham's gamma_n, libm rules, ball walks);
``float_proofs`` proves ``omega``, ``omega_general`` and ``scattering_angle``; ``integral_proof``
``first_integral``; ``basis_proof`` ``gamma_basis``; ``general_angle_proof`` ``general_scattering_angle``;
``derivations.output.float_paths`` runs them on the emitted module as a user imports it (the round trip and
``build_formulas.py --verify``).  Each proof also checks, bit for bit, that the run-time code computes the
operation sequence it analyses.

May import: ``derivations.core`` and the runtime package (``suslov``); imported by ``derivations.output``.
"""
