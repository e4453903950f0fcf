"""Certificate records: what was claimed, where the paper states it, how it was checked.

Every formula the build emits is backed by one or more :class:`Certificate`
records (docs/design.md, "Certification").  A certificate names

* the claim in words and mathematics (a :class:`~derivations.core.statement.Statement`: written
  ``"words $formula$"``, each formula a SymPy object; the JSON and the terminal print its plain
  text, the documents its LaTeX -- method and detail the same),
* the paper's equation label (``ep3.26``, ``gen12``, ... of the paper's LaTeX
  source, arXiv:0902.0079), or ``derived`` for a claim the
  paper does not state,
* the method (exact zero test in a named canonical domain, or numeric
  corroboration with mpmath at a stated precision),
* the outcome: ``pass``, ``fail`` or ``unknown``,
* the cost in seconds (wall clock; volatile, so it is kept out of the
  byte-identical outputs, see ``derivations.output.pipeline``),
* a deterministic work measure (terms tested, points sampled) and a detail,
* for floating-point evidence, the measured value (``measured``: worst error over bound, say),
  volatile like the cost: NumPy's float64 kernels differ in the last bits between CPUs (AVX2
  and AVX-512 dispatch), so the value goes to ``certificate_measurements.json`` only.

Claims about the *paper's printed* forms that turn out false are not build
failures: they are recorded with ``expect=False`` and reported as errata.  A
certificate fails the build only when its outcome differs from what the
derivation expects.
"""
from __future__ import annotations

import time
from contextlib import contextmanager
from dataclasses import dataclass, field
from enum import Enum

from derivations.core.statement import Statement, say, text


class Outcome(str, Enum):
    """Three-valued outcome of a certification attempt."""

    PASS = "pass"
    FAIL = "fail"
    UNKNOWN = "unknown"


@dataclass
class Certificate:
    """One certified (or refuted) claim."""

    claim: Statement
    label: str
    method: Statement
    outcome: Outcome
    seconds: float
    work: int = 0
    detail: Statement = ""
    derivation: str = ""
    expected: Outcome = Outcome.PASS
    key: str = ""
    measured: str = ""

    def __post_init__(self):
        # text with $formulas$ (or prose only) becomes words and SymPy objects here, once
        self.claim, self.method, self.detail = say(self.claim), say(self.method), say(self.detail)

    @property
    def as_expected(self) -> bool:
        """True when the outcome is the one the derivation predicted."""
        return self.outcome == self.expected

    def deterministic_record(self) -> dict:
        """The fields that are identical across builds and machines (no timing, no float measurement)."""
        record = {name: getattr(self, name) for name in self.__dataclass_fields__}
        record.pop("seconds")
        record.pop("measured")
        record.update(claim=text(self.claim), method=text(self.method), detail=text(self.detail),
                      outcome=self.outcome.value, expected=self.expected.value)
        return record

    def typeset_record(self) -> dict:
        """:meth:`deterministic_record` with claim, method and detail as statements (for the templates)."""
        return {**self.deterministic_record(), "claim": self.claim, "method": self.method, "detail": self.detail}


class CertificationFailure(RuntimeError):
    """Raised when a certificate's outcome is not the expected one."""

    def __init__(self, certificate: Certificate):
        self.certificate = certificate
        super().__init__(
            f"certificate failed: [{certificate.label}] {certificate.claim} "
            f"(outcome {certificate.outcome.value}, expected "
            f"{certificate.expected.value}; method: {certificate.method}; "
            f"{certificate.detail})"
        )


@dataclass
class CertificateLog:
    """Collects certificates for one build, in the order they were made."""

    certificates: list[Certificate] = field(default_factory=list)
    derivation: str = ""
    on_record: object = None  # optional callback(Certificate) for progress display
    on_phase: object = None   # optional callback(label, done, total, p) for per-p phases (progress display)
    workers: int | None = None   # map_per_p: local processes (None: all cores; 1: in this process)
    scheduler: str | None = None  # map_per_p: a dask.distributed scheduler address instead
    cache: bool = False           # map_per_p: results from/to the content-keyed cache (derivations.core.cache)
    cache_report: list = field(default_factory=list)   # what came from the cache (volatile, cache_report.json)
    prefetched: dict = field(default_factory=dict)     # label -> (values, work, suslov.executor.Ahead)

    def record(self, certificate: Certificate) -> Certificate:
        certificate.derivation = certificate.derivation or self.derivation
        if not certificate.key:
            certificate.key = f"{certificate.derivation}:{len(self.certificates) + 1:03d}"
        self.certificates.append(certificate)
        if callable(self.on_record):
            self.on_record(certificate)
        if not certificate.as_expected:
            raise CertificationFailure(certificate)
        return certificate

    @contextmanager
    def section(self, derivation: str):
        """Tag the certificates recorded inside the block with a derivation name."""
        previous, self.derivation = self.derivation, derivation
        try:
            yield self
        finally:
            self.derivation = previous

    def total_seconds(self) -> float:
        return sum(c.seconds for c in self.certificates)

    def per_p(self, label: str, values):
        """Iterate over ``values`` (the p of a per-p phase), telling the progress display about each one.

        The display (``on_phase(label, done, total, value)``) estimates the time left; the
        certificates and every output are unaffected.
        """
        values = list(values)
        report = getattr(self, "on_phase", None)
        for done, value in enumerate(values):
            if callable(report):
                report(label, done, len(values), value)
            yield value
        if callable(report) and values:
            report(label, len(values), len(values), values[-1])

    def handed_over(self) -> list[Certificate]:
        """This (worker's private) log's certificates with keys and derivation cleared, for a main log
        to record in its own order (:meth:`map_per_p`'s work functions return them)."""
        for certificate in self.certificates:
            certificate.key = certificate.derivation = ""
        return self.certificates

    def map_per_p(self, label: str, values, work, cacheable: bool = True, meanwhile=None) -> list:
        """``[work(p) for p in values]``, independent per-p computations run in parallel.

        ``work`` is a top-level function (it is sent to worker processes or a Dask cluster) that
        returns plain data (no python-flint objects: they do not pickle).  The results come back
        in the order of ``values`` and the caller records the certificates from them, so the
        certificate log and every output are identical whatever executed the work (one process,
        local processes, Dask).  Phases shorter than ``PARALLEL_MIN`` values stay in this process.
        ``cacheable=False`` for work whose result depends on more than its module and the value (the
        round trip's checks of an emitted module, say): never taken from the cache.  ``meanwhile()``
        runs once in this process while the workers compute (:func:`suslov.executor.run_chunks`): the
        caller's serial work overlaps the parallel phase, and records its certificates before the
        phase's, exactly as when it ran first.
        """
        from suslov.executor import (
            run_chunks,  # the simulator's executor: one mechanism for both
        )

        values = list(values)
        report = self.on_phase if callable(self.on_phase) else None
        done = [0]
        if report and values:
            report(label, 0, len(values), values[0])

        def finished(i):
            done[0] += 1
            if report:
                report(label, done[0], len(values), values[i])

        ahead = self.prefetched.pop(label, None)
        if ahead is not None and (ahead[0], ahead[1]) == (values, work):
            if meanwhile is not None:
                meanwhile()
            results, computed = ahead[2].collect(on_finish=finished)
            if ahead[2].store is not None:
                self.cache_report.append({"phase": label, "values": len(values), "from_cache": len(values) - computed,
                                          "work": f"{work.__module__}.{work.__qualname__}", "prefetched": True})
            return results
        if ahead is not None:    # prefetched with other arguments: not this phase's results
            ahead[2].cancel()
        store, keys = None, [str(v) for v in values]
        if self.cache and cacheable:
            from derivations.core.cache import per_p_key, per_p_store
            store, keys = per_p_store(), [per_p_key(work, v) for v in values]
        small = all(isinstance(v, int) for v in values) and max(values, default=0) <= INLINE_PMAX
        parallel = len(values) >= PARALLEL_MIN and not small
        workers = self.workers if parallel else 1
        # the cost of a p grows with p: hand out the largest first, so no worker is left with a big
        # one at the end while the others idle; results are put back in the order of ``values``
        n = len(values)
        backwards, computed = run_chunks(work, values[::-1], keys[::-1], store=store, workers=workers,
                                         scheduler=self.scheduler if parallel else None,
                                         on_finish=lambda i: finished(n - 1 - i), meanwhile=meanwhile)
        results = backwards[::-1]
        if store is not None:
            self.cache_report.append({"phase": label, "values": len(values), "from_cache": len(values) - computed,
                                      "work": f"{work.__module__}.{work.__qualname__}"})
        return results


    def prefetch(self, label: str, values, work, cacheable: bool = True) -> None:
        """Start ``map_per_p(label, values, work)`` now, in the local worker processes, and return at once;
        the later ``map_per_p`` call with the same arguments collects the results (the certificates are
        recorded there, in the usual order: the log and every output are as without the prefetch).

        The build prefetches what derivations declare in ``PREFETCH`` (numeric certificates that need no
        other result) before running any derivation, so that the numeric work of a cold build overlaps
        the symbolic one.  Nothing is prefetched in one process (``workers`` 1) or on a Dask scheduler.
        """
        from suslov.executor import default_workers, submit_ahead

        workers = default_workers() if self.workers is None else self.workers
        if workers <= 1 or self.scheduler:
            return
        values = list(values)
        store, keys = None, [str(v) for v in values]
        if self.cache and cacheable:
            from derivations.core.cache import per_p_key, per_p_store
            store, keys = per_p_store(), [per_p_key(work, v) for v in values]
        self.prefetched[label] = (values, work, submit_ahead(work, values, keys, store=store, workers=workers))

    def cancel_prefetched(self) -> None:
        """Drop the prefetched work nobody collected (a build that failed before reaching it)."""
        while self.prefetched:
            self.prefetched.popitem()[1][2].cancel()


PARALLEL_MIN = 16   # per-p phases with fewer values are not worth starting processes for
# nor per-p phases whose p are all this small: galois's p = 1..40 of a default build take 0.26 s in this process
# and took 1.1 s through the workers, queued behind the ball checks prefetched there
INLINE_PMAX = 40


@contextmanager
def stopwatch():
    """Yield a one-element list that receives the elapsed wall time in seconds."""
    elapsed = [0.0]
    start = time.perf_counter()
    try:
        yield elapsed
    finally:
        elapsed[0] = time.perf_counter() - start
