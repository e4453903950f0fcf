"""Ctrl-C that stops any run, and children that end with their parent (issue 36).

Two kernel-level facts the command lines and the process pools rely on:

* a non-interactive shell starts a background job (``cmd &``) with SIGINT *ignored*, and Python then
  installs no handler, so ``kill -INT`` of such a build did nothing: :func:`listen_for_interrupts`
  restores Python's handler in the process that owns the run;
* a watching thread cannot end a child that is inside a long C call holding the GIL, but the kernel
  can: :func:`die_with_parent` asks for a signal when the parent goes (``PR_SET_PDEATHSIG``, Linux;
  elsewhere a no-op, and the pools' watching threads remain the fallback).

Standard library only; every layer may import it.
"""
from __future__ import annotations

import signal
import threading

__all__ = ["listen_for_interrupts", "die_with_parent"]

_PR_SET_PDEATHSIG = 1


def listen_for_interrupts() -> None:
    """Make SIGINT raise ``KeyboardInterrupt`` in this process even if it was started with SIGINT ignored."""
    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGINT, signal.default_int_handler)


def die_with_parent(sig: int = signal.SIGKILL) -> None:
    """Ask the kernel to send ``sig`` to this process when its parent ends (Linux; elsewhere nothing)."""
    try:
        import ctypes

        ctypes.CDLL(None, use_errno=True).prctl(_PR_SET_PDEATHSIG, int(sig), 0, 0, 0)
    except (OSError, AttributeError):
        pass
