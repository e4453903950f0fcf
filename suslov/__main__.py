"""``python -m suslov``: the ``suslov`` command (:mod:`suslov.cli`)."""
import sys

if __name__ == "__main__":   # not when a spawned worker process imports this module
    # Ctrl-C first (issue 44): a background job starts with SIGINT ignored, and a kill -INT sent before a handler
    # exists is lost; suslov.interrupts is standard library only and already loaded with the package
    from suslov.interrupts import listen_for_interrupts

    listen_for_interrupts()
    try:
        from suslov.cli import main
    except KeyboardInterrupt:
        print("suslov: interrupted; nothing was written", file=sys.stderr)
        sys.exit(130)
    sys.exit(main())
