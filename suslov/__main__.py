"""``python -m suslov``: the simulator's command line (:mod:`suslov.simulator.cli`)."""
import sys

from suslov.simulator.cli import main

if __name__ == "__main__":   # not when a spawned worker process imports this module
    sys.exit(main())
