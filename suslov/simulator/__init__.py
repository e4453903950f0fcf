"""The simulator: declarative scenes, the planner, integrators, sweeps, figures and the command line.

``scene`` / ``sweep_spec`` parse scene files (``scene_errors`` holds their one error), ``planner``
turns the requested effects into the fewest computations, ``engine`` runs one body, ``sweep`` (with
``sweep_outputs`` and ``executor``) runs many, ``integrate`` / ``taylor`` integrate where no closed
form exists, ``figures`` draws, ``sleigh`` is Fig. 3's model, ``outputs`` writes output directories
(``suslov.outdir``), ``cli`` is ``suslov simulate``.

May import: the generated module (through ``suslov.loader``), ``suslov.runtime``, ``suslov.kernel``,
``suslov.validated`` -- never ``derivations``.
"""
