"""The paper's sections, one derivation module each (registered in ``derivations.registry``).

Each module has ``NAME``, ``TITLE``, optional ``REQUIRES`` and ``run(log, options, *results)``, and a
docstring naming the paper's section and equation labels and the method.  Helpers that two
derivations share live in their own module (``meromorphic_ring``, ``local_obstruction``,
``poisson_taylor``, ``scattering_balls``, ``physical_bodies``).

May import: ``derivations.core``, ``suslov.kernel``, ``suslov.recipes`` -- never
``derivations.output`` or ``derivations.registry``.
"""
