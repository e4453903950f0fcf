"""The build's ring adapters for the shared recipes: those of :mod:`suslov.recipes.flint_rings` (one definition,
used by the build's certificates and by the formula catalog at run time)."""
from suslov.recipes.flint_rings import BASIS_CTX, BASIS_RING, INTEGRAL_CTX, INTEGRAL_RING  # noqa: F401
