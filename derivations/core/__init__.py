"""The certification machinery every derivation uses (docs/design.md, "Certification").

Certificates and their log (``certificates``), exact zero tests in canonical domains (``exact``,
``rational_field``, ``recipe_rings``), numeric evidence (``numeric``) and ball certificates
(``balls``), the content-keyed cache (``cache``), build options (``options``), the shared symbols and
the differential ring of tanh/sech (``symbols``, ``differential``), LaTeX typesetting (``typeset``),
emitted code (``emit``), errata rows (``errata``) and the paper's printed forms, transcribed once
(``paper``).

May import: SymPy, python-flint, mpmath, ``suslov.kernel``, ``suslov.recipes``, ``suslov.executor``
(the process pool) -- never ``derivations.sections`` or ``derivations.output``.
"""
