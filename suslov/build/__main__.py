"""``python -m suslov.build ARGS``: the build's command line from an installed package (see ``suslov.build``)."""
import sys

if __name__ == "__main__":   # not when a spawned worker process imports this module
    from suslov.interrupts import listen_for_interrupts

    listen_for_interrupts()   # before the heavy imports: a background job starts with SIGINT ignored

    from suslov.build import main

    sys.exit(main())
