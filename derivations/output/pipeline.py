"""derive -> certify -> render, with an all-or-nothing write of ``generated/``.

The pipeline runs the derivations of ``derivations.registry`` in dependency
order, collecting certificates in one :class:`CertificateLog`.  A certificate
whose outcome differs from the expected one raises
:class:`CertificationFailure` at once, naming the claim; nothing is rendered.

Rendering writes every output into a fresh temporary directory beside the
target and only then swaps it into place, so the target is either the old
tree or the complete new one, never a mixture.

Determinism: the committed outputs carry no timing, no timestamp and no
absolute path.  The cost of each certificate (seconds) is volatile and goes
into ``certificate_costs.json`` / ``certificate_costs.tex`` only, and the measured values
of floating-point evidence (CPU-dependent in their last digits) into
``certificate_measurements.json``; those files are ignored by git, by ``--check`` and by the
reproducibility test, and the LaTeX document includes the cost table when it is present.
"""
from __future__ import annotations

import json
import math
import shutil
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

from derivations.core.certificates import CertificateLog, Outcome
from derivations.core.emit import emitted_formulas
from derivations.core.notation import index_rows
from derivations.core.options import BuildOptions
from derivations.core.statement import say, text
from derivations.output import catalog_data, figures, public_api
from derivations.output.render import render
from derivations.output.tree import (  # noqa: F401 - ROOT, GENERATED, MODULE_NEEDS, BUILD_SIGNATURE: the pipeline's names too
    BUILD_SIGNATURE,
    BUILD_TOOL,
    GENERATED,
    MODULE_NEEDS,
    OUTPUTS,
    ROOT,
    VOLATILE,
    claim_output,
    compare_trees,
    install_tree,
    swap_in,
    write_manifest,
)
from derivations.registry import DERIVATIONS, resolve
from suslov import outdir


@dataclass
class Build:
    options: BuildOptions
    names: list[str]
    log: CertificateLog
    results: dict = field(default_factory=dict)
    seconds: dict = field(default_factory=dict)
    round_trip_done: bool = False
    catalog_json: str | None = None   # generated/catalog.json, made (and its srepr checked) once per build
    catalog_chunks: list = field(default_factory=list)   # its srepr check while it runs (start_catalog)


def time_left(elapsed: float, done: int, total: int, elapsed_at_half: float | None = None) -> float | None:
    """Seconds left in a per-p phase, extrapolated with the growth of the cumulative time.

    Per-p work grows like a power of p, so the cumulative time after i of n steps grows like
    i^k; k is estimated from the time at i and at i/2 (k >= 1: never faster than linear),
    and the remaining time is elapsed ((n/i)^k - 1).  None until there is enough to go on.
    """
    if done < 2 or elapsed <= 0:
        return None
    k = 1.0
    if elapsed_at_half:
        k = max(1.0, min(6.0, math.log(elapsed / elapsed_at_half) / math.log(done / (done // 2))))
    return elapsed * ((total / done) ** k - 1.0)


class Progress:
    """One line per derivation; on a terminal also a live counter and, in per-p phases, the p reached
    and an estimate of the time left (when stderr is not a terminal: only the line per derivation)."""

    def __init__(self, stream=sys.stderr, quiet: bool = False, calibration=None):
        self.stream, self.quiet = stream, quiet
        # derivations.output.estimate.Calibration: after each derivation, the build's time left on this machine
        self.calibration, self.started = calibration, time.perf_counter()
        self.live = hasattr(stream, "isatty") and stream.isatty()
        self.count = 0
        self.phase_text = ""

    def start(self, index: int, total: int, name: str):
        self.prefix, self.count, self.t0 = f"[{index}/{total}] {name}", 0, time.perf_counter()
        self.phase_text, self.phase_start, self.phase_times = "", None, {}
        if not self.quiet and self.live:
            self.stream.write(f"{self.prefix} ...")
            self.stream.flush()

    def _show(self):
        if not self.quiet and self.live:
            line = f"{self.prefix}: {self.count} certificates, {time.perf_counter() - self.t0:.1f} s{self.phase_text}"
            self.stream.write("\r" + line.ljust(100)[:160])
            self.stream.flush()

    def certificate(self, cert):
        self.count += 1
        self._show()

    def phase(self, label: str, done: int, total: int, value):
        now = time.perf_counter()
        if done == 0 or self.phase_start is None:
            self.phase_start, self.phase_times = now, {}
        elapsed = now - self.phase_start
        self.phase_times[done] = elapsed
        left = time_left(elapsed, done, total, self.phase_times.get(done // 2))
        estimate = f", about {left:.0f} s left" if left is not None and done < total else ""
        # a per-p phase names the p reached; other phases (the round trip's checks, the catalog's) only count
        reached = f"p = {value} " if isinstance(value, int) else ""
        self.phase_text = f"; {label}: {reached}({done}/{total}){estimate}"
        self._show()

    def done(self, name: str | None = None):
        now = time.perf_counter()
        if not self.quiet:
            line = f"{self.prefix}: {self.count} certificates, {now - self.t0:.2f} s"
            if self.calibration is not None and name is not None:
                self.calibration.finished(name, now - self.t0)
                left = self.calibration.left()
                if left is not None:
                    line += (f"; build: {now - self.started:.0f} s so far, about {left:.0f} s left "
                             f"(this machine: {self.calibration.factor():.2f}x the benchmark's)")
            self.stream.write(("\r" + line.ljust(100).rstrip() if self.live else line) + "\n")
            self.stream.flush()


def derive(options: BuildOptions, only: list[str] | None = None, progress: Progress | None = None) -> Build:
    """Run and certify the derivations (raises CertificationFailure)."""
    names = resolve(only)
    progress = progress or Progress(quiet=True)
    log = CertificateLog(on_record=progress.certificate, on_phase=progress.phase, workers=options.jobs,
                         scheduler=options.scheduler, cache=options.cache)
    build = Build(options, names, log)
    # numeric certificates that need no other result start at once in the worker processes; the
    # derivations collect them where they record them (CertificateLog.prefetch)
    for name in names:
        prefetch = getattr(DERIVATIONS[name], "PREFETCH", ())
        for label, values, work in (prefetch(options) if callable(prefetch) else prefetch):
            log.prefetch(label, values, work)
    try:
        for index, name in enumerate(names, 1):
            module = DERIVATIONS[name]
            progress.start(index, len(names), name)
            start = time.perf_counter()
            with log.section(name):
                required = [build.results[req] for req in getattr(module, "REQUIRES", ())]
                build.results[name] = module.run(log, options, *required)
            build.seconds[name] = time.perf_counter() - start
            progress.done(name)
    finally:
        log.cancel_prefetched()
    return build


EMITTED_ORDER = ("omega", "omega_general", "lambda_squared", "p_squared_i13_zero", "p_squared_i23_zero",
                 "special_parameters", "scattering_angle", "gauss_invariants", "general_angle")


def _scattering_keys(build: Build) -> str:
    if "scattering" not in build.results:
        return "-"
    return ", ".join(f"{k} {v}" for k, v in sorted(build.results["scattering"].exports["certificates"].items()))


def titles(build: Build) -> dict:
    """Every derivation's title, and the round trip's."""
    return {**{name: DERIVATIONS[name].TITLE for name in build.names},
            "roundtrip": "The emitted module, as written (round trip)"}


def context(build: Build) -> dict:
    """Everything the templates see (deterministic apart from ``costs``)."""
    certificates = [c.typeset_record() for c in build.log.certificates]
    results = [build.results[name] for name in build.names]
    errata = [e for r in results for e in r.errata]
    by_key = {c["key"]: c for c in certificates}
    numbers = {f.key: n for n, f in enumerate((f for r in results for f in r.formulas), 1)}
    return {
        "pmax": build.options.pmax,
        "odd_ps": build.options.odd_p_values(),
        "even_ps": build.options.even_p_values(),
        "names": build.names,
        "titles": titles(build),
        # the certificates document lists every derivation's certificates and the round trip's
        "certificate_sections": build.names + ["roundtrip"],
        "results": results,
        "certificates": certificates,
        "certificate_by_key": by_key,
        "errata": errata,
        "per_p": build.results["special_case"].exports["per_p"] if "special_case" in build.results else [],
        "emitted": {name: item.source() for name, item in emitted_formulas(build).items()},
        "emitted_order": [name for name in EMITTED_ORDER if name in emitted_formulas(build)],
        "basis_sigma": dict(sorted(build.results["meromorphic"].exports["sigma"].items()))
        if "meromorphic" in build.results else {},
        "scattering_certificates": _scattering_keys(build),
        "public_api": public_api.sections(_scattering_keys(build)),
        "integral_ps": [r["p"] for r in build.results["first_integrals"].exports["rows"]]
        if "first_integrals" in build.results else [],
        "basis_ps": [r["p"] for r in build.results["meromorphic"].exports["rows"]]
        if "meromorphic" in build.results else [],
        "scattering": build.results["scattering"].exports if "scattering" in build.results else None,
        "galois_rows": build.results["galois"].exports["log_rows"] if "galois" in build.results else [],
        "prop_rows": build.results["galois"].exports["prop_rows"] if "galois" in build.results else [],
        "fuchsian_rows": build.results["fuchsian"].exports["rows"] if "fuchsian" in build.results else [],
        "log_rows": build.results["residue"].exports["log_rows"] if "residue" in build.results else [],
        "body_rows": build.results["residue"].exports["body_rows"] if "residue" in build.results else [],
        "basis_rows": build.results["meromorphic"].exports["rows"] if "meromorphic" in build.results else [],
        "basis_tables": build.results["meromorphic"].exports["tables"] if "meromorphic" in build.results else {},
        "integral_rows": build.results["first_integrals"].exports["rows"] if "first_integrals" in build.results else [],
        "counts": {o.value: sum(1 for c in build.log.certificates if c.outcome is o) for o in Outcome},
        "refuted": sum(1 for c in build.log.certificates if c.expected is Outcome.FAIL),
        "costs": [(c.key, c.claim, c.seconds) for c in build.log.certificates],
        "total_seconds": build.log.total_seconds(),
        # the number (N) of each formula's display in the formulas document (its equation counter: every
        # formula one number, in the document's order), and for every certificate the formulas citing it
        "formula_numbers": {f.key: n for n, f in enumerate((f for r in results for f in r.formulas), 1)},
        "cited_by": {c["key"]: [(f.key, n) for n, f in enumerate((f for r in results for f in r.formulas), 1)
                                if c["key"] in f.certificates] for c in certificates},
        # the notation index (derivations.core.notation) and the figures (derivations.output.figures; None when
        # the build lacks what they draw)
        "notation": index_rows([f for r in results for f in r.formulas], numbers),
        "figures": figures.figures(emitted_formulas(build), {f.key: f for r in results for f in r.formulas})
        if all(n in build.results for n in figures.NEEDS) else None,
    }


def certificate_document(build: Build, ctx: dict | None = None) -> dict:
    ctx = ctx or context(build)
    return {
        "pmax": ctx["pmax"],
        "ball_checks": build.options.ball_checks,
        "derivations": ctx["names"],
        "certificates": [c.deterministic_record() for c in build.log.certificates],
        "errata": [{**vars(e), "note": text(say(e.note))} for e in ctx["errata"]],
        "notes": {r.name: [text(say(note)) for note in r.notes] for r in ctx["results"]},
    }


CATALOG_CHECK = "catalog: every formula reads back from srepr"


def start_catalog(build: Build) -> None:
    """``build.catalog_json``, made once per build (not per render), and its check that every formula reads back
    from ``srepr`` (:mod:`derivations.output.catalog_data`): half of the formulas checked here, half started in the
    worker processes (in this process when there are none, at :func:`finish_catalog`): 0.8 s of evaluating SymPy
    constructors, shared with the workers while they run the round trip's float-path checks."""
    if build.catalog_json is None:
        document = catalog_data.catalog_document(build, titles(build), check=False)
        build.catalog_json = catalog_data.text_of(document)
        chunks = catalog_data.read_back_chunks(document)
        # half to the workers, behind the round trip's float-path checks; the other half here meanwhile
        build.catalog_chunks = chunks[1::2]
        build.log.prefetch(CATALOG_CHECK, build.catalog_chunks, catalog_data.read_back, cacheable=False)
        failures = [f for chunk in chunks[::2] for f in catalog_data.read_back(chunk)]
        if failures:
            build.catalog_json, build.catalog_chunks = None, []
            build.log.cancel_prefetched()
            raise catalog_data.CatalogError(failures[0])


def finish_catalog(build: Build) -> None:
    """The result of the check :func:`start_catalog` started (raises ``catalog_data.CatalogError`` at the first
    formula that does not read back); nothing to do once done."""
    if build.catalog_chunks:
        chunks, build.catalog_chunks = build.catalog_chunks, []
        failures = [f for found in build.log.map_per_p(CATALOG_CHECK, chunks, catalog_data.read_back, cacheable=False)
                    for f in found]
        if failures:
            build.catalog_json = None
            raise catalog_data.CatalogError(failures[0])


def make_catalog(build: Build) -> None:
    """``build.catalog_json``, checked."""
    start_catalog(build)
    finish_catalog(build)


def render_into(build: Build, directory: Path, only: tuple[str, ...] | None = None) -> list[str]:
    """Write every output whose derivations ran into ``directory`` (of the templated ones and the catalog, those
    named in ``only`` where given; the other JSON files always)."""
    ctx = context(build)
    written = []
    for template, filename, needs in OUTPUTS:
        if all(n in build.results for n in needs) and (only is None or filename in only):
            (directory / filename).write_text(render(template, ctx), encoding="utf-8")
            written.append(filename)
    (directory / "certificates.json").write_text(
        json.dumps(certificate_document(build, ctx), indent=1, sort_keys=True) + "\n", encoding="utf-8")
    if only is None or catalog_data.FILENAME in only:
        make_catalog(build)
        (directory / catalog_data.FILENAME).write_text(build.catalog_json, encoding="utf-8")
        written.append(catalog_data.FILENAME)
    (directory / "certificate_costs.json").write_text(
        json.dumps({k: round(s, 6) for k, _, s in ctx["costs"]}, indent=1, sort_keys=True) + "\n",
        encoding="utf-8")
    (directory / "certificate_measurements.json").write_text(
        json.dumps({c.key: c.measured for c in build.log.certificates if c.measured}, indent=1, sort_keys=True)
        + "\n", encoding="utf-8")
    (directory / "cache_report.json").write_text(
        json.dumps(build.log.cache_report, indent=1, sort_keys=True) + "\n", encoding="utf-8")
    return written + ["certificates.json", "certificate_costs.json", "certificate_measurements.json",
                      "cache_report.json"]


def certify_pending_bases(build: Build) -> None:
    """The meromorphic bases the derivation left to the round trip (p > KEEP_BASES), certified from the recipe
    instead (:func:`derivations.sections.meromorphic.certify_pending`), for a build that runs no round trip:
    one that emits no module (``--only`` without the module's derivations) or writes nothing.  Nothing to do
    when none are pending (the round trip certified them, or pmax <= KEEP_BASES)."""
    result = build.results.get("meromorphic")
    if result is not None and result.exports.get("pending"):
        from derivations.sections.meromorphic import certify_pending

        certify_pending(build.log, result)


def write_atomically(build: Build, target: Path) -> None:
    """Render into a staging sibling, then swap it into ``target`` (crash-safe: :mod:`suslov.outdir`)."""
    target = claim_output(target)
    outdir.make_dir(target.parent)
    staging = outdir.new_staging(target, BUILD_TOOL)
    try:
        module_first = ("__init__.py", "suslov_formulas.py")
        if build.round_trip_done or "suslov_formulas.py" not in render_into(build, staging, only=module_first):
            certify_pending_bases(build)   # no module, no round trip: the bases beyond the kept ones from the recipe
            render_into(build, staging)
        else:
            # certify the module as emitted (it and certificates.json are all the round trip reads; the module's
            # text does not depend on the round trip's certificates), then render everything, so the round-trip
            # certificates are in every output
            from derivations.output.roundtrip import certify_module
            from derivations.sections.meromorphic import complete_row

            emitted = (staging / "suslov_formulas.py").read_bytes()
            # the catalog's srepr check queued behind the float-path checks in the workers; the bases beyond the
            # kept ones certified on the emitted core's numerators, their rows completed before the documents
            bases = {}
            certify_module(build.log, build, staging, meanwhile=lambda: start_catalog(build), bases=bases)
            for p, done in sorted(bases.items()):
                complete_row(build.results["meromorphic"], p, done["certificates"], done["terms"])
            build.round_trip_done = True
            render_into(build, staging)
            if (staging / "suslov_formulas.py").read_bytes() != emitted:
                raise RuntimeError("the emitted module changed after its round trip: the certified text is not the "
                                   "one written")
        finish_catalog(build)   # render_into checked it already unless it started above
        write_manifest(staging)
        claim_output(target)   # again: a file a user put into the previous output meanwhile is not lost
    except BaseException:
        build.log.cancel_prefetched()   # the catalog's check, if it was started: nothing runs on for a failed write
        shutil.rmtree(staging, ignore_errors=True)
        raise
    swap_in(staging, target)


def summary(build: Build, top: int = 5) -> str:
    """Certificate summary with costs, for the console."""
    certs = build.log.certificates
    refuted = [c for c in certs if c.expected is Outcome.FAIL and c.outcome is Outcome.FAIL]
    passed = sum(1 for c in certs if c.outcome is Outcome.PASS)
    unknown = sum(1 for c in certs if c.outcome is Outcome.UNKNOWN)
    lines = [f"{len(certs)} certificates, all as expected: {passed} claims proved (or corroborated, where the method "
             f"says evidence), {len(refuted)} printed forms of the paper refuted as the derivation predicts (see the "
             f"errata table), {unknown} unknown"]
    for name in build.names:
        n = sum(1 for c in certs if c.derivation == name)
        lines.append(f"  {name:<16} {n:4d} certificates  {build.seconds[name]:8.3f} s")
    trip = [c for c in certs if c.derivation == "roundtrip"]
    if trip:
        lines.append(f"  {'roundtrip':<16} {len(trip):4d} certificates  {sum(c.seconds for c in trip):8.3f} s"
                     "  (the emitted module, as written)")
    lines.append(f"costliest {min(top, len(certs))}:")
    for c in sorted(certs, key=lambda c: -c.seconds)[:top]:
        verdict = c.outcome.value + (" as predicted: the printed form is refuted" if c.expected is Outcome.FAIL else "")
        lines.append(f"  {c.seconds:8.4f} s  [{c.label}] {c.claim} ({verdict})")
    return "\n".join(lines)
