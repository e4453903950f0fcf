"""``python -m suslov.build ARGS``: the build's command line from an installed package (see ``suslov.build``)."""
import sys

from suslov.build import main

sys.exit(main())
