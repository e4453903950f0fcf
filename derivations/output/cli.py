"""The build's command line (``python build_formulas.py``): derive -> certify -> render into generated/.

``build_formulas.py`` at the repository's top is only the entry point: it imports this module when
the build runs, not at import time, so the worker processes the build spawns (``suslov.executor``,
start method ``spawn``, which re-imports the main script as ``__mp_main__``) start without SymPy and
the derivations unless their work needs them: the numeric certificates prefetched by a cold build
(monodromy, enclosures) import python-flint and mpmath only (about 0.8 s less per worker).

Options, outputs and exit status: ``build_formulas.py``'s docstring and ``docs/build.md``.
"""
from __future__ import annotations

import argparse
import json
import os
import re
import sys
import tempfile
from pathlib import Path

import suslov.manifest as manifest
from derivations.core.cache import TreeCache, build_key, cache_root, per_p_store
from derivations.core.options import (
    BALL_CHECKS,
    CROSS_CHECK_PMAX,
    CROSS_CHECK_STEP,
    PMAX_LIMIT,
    BuildOptions,
)
from derivations.output.pdf import PdfError, compile_pdfs, document_report, is_byproduct
from derivations.output.tree import (
    GENERATED,
    MODULE_NEEDS,
    ROOT,
    claim_output,
    compare_trees,
    install_tree,
)
from derivations.registry import NAMES
from suslov.executor import (
    TMP_PREFIX,
    SchedulerError,
    check_reachable,
    scheduler_address,
    worker_limit,
)
from suslov.interrupts import listen_for_interrupts
from suslov.outdir import (
    OutputRefused,
    discard_own,
    discard_own_staging,
    writable_directory,
    write_failure,
)

# SymPy, the derivations and the certificate machinery (derivations.core.certificates, derivations.output.pipeline,
# derivations.output.estimate) are imported by the functions that run a build, after the command line and the
# output paths were checked: a bad option or path is refused in about 0.1 s instead of 0.8 s.


def _pmax(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"--pmax {text!r}: not an integer") from None
    if not 1 <= value <= PMAX_LIMIT:
        raise argparse.ArgumentTypeError(f"--pmax {value}: must be between 1 and {PMAX_LIMIT}")
    return value


def plain_title(title: str) -> str:
    """A derivation's TeX title as terminal text: "$I_{13}=0$" -> "I13=0", "$\\omega(t)$" -> "omega(t)"."""
    return re.sub(r"[${}_]", "", title).replace("\\", "")


class _OneLineErrors(argparse.ArgumentParser):
    """Bad input gets one clear line (which option, which value, why), exit status 2.  The list of derivations
    (with their titles, which takes importing them) is added to the help when the help is shown."""

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message} (see --help)\n")

    def format_help(self):
        if self.epilog is None:
            from derivations.registry import DERIVATIONS

            self.epilog = "Derivations: " + ", ".join(f"{n} ({plain_title(m.TITLE)})" for n, m in DERIVATIONS.items())
        return super().format_help()


ESTIMATE_FROM = 31   # print the time estimate before building beyond this pmax
NO_CACHE_ENV = "SUSLOV_NO_CACHE"


def parser() -> argparse.ArgumentParser:
    ap = _OneLineErrors(
        prog="build_formulas.py",
        description="Derive, certify and render the formulas of the Suslov problem.",
    )
    ap.add_argument("--pmax", type=_pmax, default=BuildOptions().pmax,
                    help=f"largest p for the per-p tables, 1..{PMAX_LIMIT} (default %(default)s); tables "
                         "of odd-p objects stop at the largest odd p <= pmax, even-p tables at the largest even one")
    ap.add_argument("--only", nargs="+", metavar="NAME",
                    help="run only these derivations (and what they require); writes nothing unless --out is given")
    ap.add_argument("--out", type=Path, default=None,
                    help="output directory (default: generated/ for a full build)")
    ap.add_argument("--install", action="store_true",
                    help="write into the per-user store (suslov.loader.store_dir()/pmax-N, where "
                         "suslov.load_formulas(pmax=N) finds it) instead of generated/: any p range without touching "
                         "the checkout")
    ap.add_argument("--check", action="store_true",
                    help="compare the output directory with the build these sources and options give (from the "
                         "certificate cache when an entry matches, else rebuilt in a temporary directory; with "
                         "--no-cache always rebuilt) and exit 3 if it differs")
    ap.add_argument("--verify", type=Path, metavar="DIR", default=None,
                    help="check DIR against its manifest (SHA256SUMS: every file's SHA-256, and nobody else may "
                         "write the tree; see docs/trust.md), then certify its module against the derivations "
                         "without rewriting anything: exit 0, or 1 naming the first discrepancy; pmax is read from "
                         "DIR/certificates.json")
    ap.add_argument("--pdf", nargs="?", type=Path, const=ROOT / "build" / "pdf", default=None, metavar="OUTDIR",
                    help="after writing, compile the LaTeX documents (formulas, certificates) with pdflatex (two passes) into OUTDIR "
                         "(default build/pdf/, outside the tracked tree); generated/ gets no by-products")
    ap.add_argument("--diff", metavar="OLD", default=None,
                    help="compare OLD (a git revision or a generated directory) with generated/ (or --out DIR), "
                         "without rebuilding: list changed formulas, tables, certificates, errata (in Unicode) and "
                         "write a latexdiff PDF of the formulas document into build/diff/ (needs latexdiff)")
    ap.add_argument("--ball-checks", choices=BALL_CHECKS, default=BuildOptions().ball_checks,
                    help="how many bodies and points the numeric corroborations run on: the general angle's seeded "
                         "bodies (complex-path monodromy, ss enclosures in balls), the ball monodromy of the "
                         "representative bodies and the scattering enclosure points; 'default' a few of each (seconds), "
                         "'full' all of them (20 seeded bodies at 100 digits, 7 bodies, 18 points: about 30 s more on "
                         "one core); the certificates say which")
    ap.add_argument("--cross-check-pmax", type=_cross_check_pmax, default=CROSS_CHECK_PMAX, metavar="N",
                    help="the per-p logarithm recursions (Frobenius at t0, obstructions at s1..s4) cross-check a "
                         f"theorem proved for every p: they run for every p <= N (default %(default)s) and above it "
                         f"only for p = 0 or 1 mod {CROSS_CHECK_STEP} and the largest even and odd p of the range; "
                         "N >= pmax runs every p")
    ap.add_argument("--jobs", type=_jobs, default=None, metavar="N",
                    help="worker processes for the per-p certificates (default: the cores this process may run on; 1: none); the outputs "
                         "are identical whatever N")
    ap.add_argument("--scheduler", default=None, metavar="ADDRESS",
                    help="send the per-p certificates to a dask.distributed scheduler (tcp://host:port; default "
                         "$SUSLOV_SCHEDULER) instead of local processes")
    ap.add_argument("--no-cache", action="store_true",
                    help="recompute every certificate (default: reuse results whose sources, library versions and "
                         "options are unchanged, from $SUSLOV_CACHE_DIR or ~/.cache/suslov-certified; also "
                         f"${NO_CACHE_ENV}=1)")
    ap.add_argument("--quiet", action="store_true", help="no progress display and no certificate summary")
    return ap


def _cross_check_pmax(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"--cross-check-pmax {text!r}: not an integer") from None
    if not 1 <= value <= PMAX_LIMIT:
        raise argparse.ArgumentTypeError(f"--cross-check-pmax {value}: must be between 1 and {PMAX_LIMIT}")
    return value


def _jobs(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not an integer") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"{value}: must be at least 1")
    return value


def verify_tree(directory: Path, pmax: int | None, quiet: bool) -> int:
    """--verify DIR: derive what the module needs, then run the round trip on DIR's module."""
    if not (directory / "suslov_formulas.py").is_file():
        print(f"build_formulas.py: --verify {directory}: no suslov_formulas.py there", file=sys.stderr)
        return 2
    try:   # a tree whose certificates cannot be read is refused, whatever the flags
        # a regular file only: a FIFO planted as certificates.json must not block --verify
        document = json.loads(manifest.read_regular(directory / "certificates.json").decode("utf-8"))
        stated = document["pmax"]
        if not isinstance(stated, int) or not isinstance(document["certificates"], list):
            raise ValueError("pmax or certificates of the wrong type")
    except (OSError, ValueError, KeyError, TypeError) as error:
        print(f"build_formulas.py: --verify {directory}: certificates.json cannot be read ({error}); a tree without "
              "its certificates is not verified", file=sys.stderr)
        return 1
    try:   # the manifest first (what the loader checks before executing the module): cheap, and nothing runs
        manifest.verify(directory)
    except manifest.ManifestError as error:
        print(f"build_formulas.py: --verify {directory}: {error}", file=sys.stderr)
        return 1
    if not quiet:
        print(f"--verify: {directory}: every file matches {manifest.MANIFEST} and nobody else can write the tree; "
              "now certifying the module against the derivations", file=sys.stderr)
    if pmax is None:
        pmax = stated
    from derivations.core.certificates import CertificationFailure
    from derivations.output.pipeline import Progress, derive
    from derivations.output.roundtrip import verify

    try:
        build = derive(BuildOptions(pmax=pmax), list(MODULE_NEEDS), Progress(quiet=quiet))
    except CertificationFailure as failure:
        print(f"build_formulas.py: {failure}", file=sys.stderr)
        return 1
    problem = verify(build, directory)
    if problem:
        print(f"build_formulas.py: --verify {directory}: {problem}", file=sys.stderr)
        return 1
    print(f"--verify: {directory / 'suslov_formulas.py'} reproduces the certified objects (pmax = {pmax}): "
          "every emitted formula, every exact core for every p, every float path within its stated bound")
    return 0


def diff_command(old: str, new: Path) -> int:
    """--diff OLD: the change list, then the latexdiff PDF (exit 1 with the reason if it cannot be made)."""
    from derivations.output.diff import DiffError, diff_trees

    if not (new / "suslov_formulas.tex").is_file():
        print(f"build_formulas.py: --diff: {new} has no suslov_formulas.tex (build first)", file=sys.stderr)
        return 2
    try:
        pdf = diff_trees(old, new, ROOT, ROOT / "build" / "diff")
    except DiffError as error:
        print(f"build_formulas.py: --diff: {error}", file=sys.stderr)
        return 2 if "neither a directory" in str(error) or "directory without" in str(error) else 1
    print(f"wrote {pdf} and {pdf.with_name('certificates-diff.pdf').name} (latexdiff of the formulas and the "
          "certificates documents: deletions struck out, additions underlined)")
    return 0


def allow_rebuilding_generated(quiet: bool) -> None:
    """Let this build (and its worker processes) load the checkout's generated module when it does not match
    its manifest: after a merge or a hand edit, the build is how the tree is made consistent again.

    The validated certificates evaluate the active module (:mod:`suslov.validated`); the module this build
    emits is certified as written by the round trip, whatever the old one was.  A tree that other users can
    write is still refused (:class:`suslov.manifest.UntrustedTree`).
    """
    try:
        manifest.verify(GENERATED)
    except manifest.UntrustedTree:
        return
    except manifest.ManifestError as error:
        os.environ[manifest.REBUILD_ENV] = os.path.realpath(GENERATED)
        if not quiet:
            print(f"build_formulas.py: note: {error}", file=sys.stderr)


def main(argv: list[str] | None = None) -> int:
    ap = parser()
    args = ap.parse_args(argv)
    if (GENERATED / "suslov_formulas.py").is_file():
        allow_rebuilding_generated(args.quiet)
    unknown = [n for n in (args.only or []) if n not in NAMES]
    if unknown:
        ap.error(f"--only {unknown[0]!r}: unknown derivation (known: {', '.join(NAMES)})")
    if args.check and args.only:
        ap.error("--check compares a full build; it cannot be combined with --only")
    if args.pdf is not None and (args.check or (args.only and args.out is None)):
        ap.error("--pdf compiles the tree a build writes; it cannot be combined with --check or --only without --out")
    if args.diff is not None:
        if args.only or args.check or args.verify or args.pdf:
            ap.error("--diff OLD compares two existing trees; it cannot be combined with --only, --check, --verify "
                     "or --pdf")
        return diff_command(args.diff, args.out if args.out is not None else GENERATED)
    if args.verify is not None:
        if args.only or args.check or args.out or args.pdf:
            ap.error("--verify DIR checks an existing tree; it cannot be combined with --only, --check or --out")
        explicit = any(a == "--pmax" or a.startswith("--pmax=") for a in (argv if argv is not None else sys.argv[1:]))
        return verify_tree(args.verify, args.pmax if explicit else None, args.quiet)
    use_cache = not args.no_cache and not os.environ.get(NO_CACHE_ENV)
    if args.jobs is not None:
        args.jobs, capped = worker_limit(args.jobs, "--jobs")
        if capped:
            print(f"build_formulas.py: note: {capped}", file=sys.stderr)
    options = BuildOptions(pmax=args.pmax, ball_checks=args.ball_checks, cross_check_pmax=args.cross_check_pmax,
                           jobs=args.jobs, scheduler=scheduler_address(args.scheduler), cache=use_cache)
    if options.scheduler:
        try:
            check_reachable(options.scheduler)
        except SchedulerError as exc:
            print(f"build_formulas.py: {exc}; nothing was written", file=sys.stderr)
            return 2
    if args.install:
        if args.out is not None or args.only or args.check:
            ap.error("--install writes the per-user store; it cannot be combined with --out, --only or --check")
        from suslov.loader import store_dir
        args.out = store_dir() / f"pmax-{args.pmax}"
    target = args.out if args.out is not None else (None if args.only else GENERATED)
    if target is not None:
        try:   # before any work: a file, someone else's directory or an unwritable place is refused
            target = claim_output(target)
        except OutputRefused as exc:
            print(f"build_formulas.py: --out {exc}; nothing was done", file=sys.stderr)
            return 2
    if args.pdf is not None:
        try:   # also before any work: --pdf naming a file (or an unwritable place) would fail only after the build
            args.pdf = writable_directory(args.pdf)
        except OutputRefused as exc:
            print(f"build_formulas.py: --pdf {exc}; nothing was done", file=sys.stderr)
            return 2
    key = build_key(options, None) if use_cache and not args.only else None
    if key is not None:
        status = _from_cache(key, target, args)
        if status is not None:
            return status
    from derivations.core.certificates import CertificationFailure
    from derivations.output.estimate import (
        Calibration,
        estimate_seconds,
        predicted_seconds,
    )
    from derivations.output.pipeline import Progress, certify_pending_bases, derive

    if not args.quiet and not args.only and options.pmax > ESTIMATE_FROM:
        seconds = estimate_seconds(options.pmax, options.jobs, cross_check_pmax=options.cross_check_pmax)
        if seconds is not None:
            print(f"build_formulas.py: --pmax {options.pmax}: estimated {seconds / 60:.1f} min on the benchmark's "
                  "machine (power-law fit in bench/results/build.md), recalibrated on this machine as the "
                  "build runs; proceeding", file=sys.stderr)

    calibration = None if args.only else Calibration(predicted_seconds(options.pmax, options.jobs, cross_check_pmax=options.cross_check_pmax))
    try:
        build = derive(options, args.only, Progress(quiet=args.quiet, calibration=calibration))
    except CertificationFailure as failure:
        print(f"build_formulas.py: {failure}", file=sys.stderr)
        print("build_formulas.py: nothing was written", file=sys.stderr)
        return 1
    except SchedulerError as exc:
        print(f"build_formulas.py: {exc}; nothing was written", file=sys.stderr)
        return 2
    except OSError as error:   # the build itself writes only the per-p certificate cache (a full disk, a read-only home)
        unchanged = "" if target is None else f" ({target} is unchanged)"
        if use_cache:
            discard_own(per_p_store().directory, TMP_PREFIX)   # this run's half-written entry, if any
            print(f"build_formulas.py: cannot write the certificate cache: {write_failure(error, cache_root())}; "
                  f"nothing was written{unchanged}; --no-cache builds without it", file=sys.stderr)
        else:
            print(f"build_formulas.py: {write_failure(error, 'a file of the build')}; nothing was written{unchanged}",
                  file=sys.stderr)
        return 2
    if args.check:
        reference = target
        with tempfile.TemporaryDirectory(prefix="suslov-check-") as tmp:
            fresh = Path(tmp) / "generated"
            status = _write_and_cache(build, fresh, key, args.quiet)
            if status:
                return status
            differing = compare_trees(fresh, reference)
        return _check_verdict(reference, differing, "a fresh build")
    if target is None:
        try:   # no module is emitted, so no round trip: the bases beyond the kept ones are certified from the recipe
            certify_pending_bases(build)
        except CertificationFailure as failure:
            print(f"build_formulas.py: {failure}", file=sys.stderr)
            return 1
        _summary(build, args.quiet)
        print("(--only without --out: certified, nothing written)")
        return 0
    status = _write_and_cache(build, target, key, args.quiet)
    if status:
        return status
    print(f"wrote {target}")
    return _pdf(args, target)


def _pdf(args, target) -> int:
    if args.pdf is not None:
        try:
            for pdf in compile_pdfs(target, args.pdf):
                pages, problems = document_report(pdf)
                print(f"wrote {pdf} ({pages} pages; " + (f"{len(problems)} layout problems: " + "; ".join(problems[:5])
                                                          if problems else "no layout problems") + ")")
        except PdfError as error:
            print(f"build_formulas.py: --pdf: {error}", file=sys.stderr)
            return 1
    return 0


def _check_verdict(reference, differing: list, against: str) -> int:
    """--check's report: 0 when ``reference`` is identical to ``against``, else 3 naming the files."""
    if differing:
        print(f"build_formulas.py: --check: {reference} differs from {against} in: " + ", ".join(differing),
              file=sys.stderr)
        return 3
    print(f"--check: {reference} is identical to {against}")
    return 0


def _from_cache(key: str, target, args) -> int | None:
    """A whole build from the content-keyed cache (derivations.core.cache), or None when there is none."""
    entry = TreeCache().lookup(key)
    if entry is None:
        return None
    note = f"from the certificate cache (key {key[:12]}; --no-cache recomputes)"
    if args.check:
        with tempfile.TemporaryDirectory(prefix="suslov-check-") as tmp:
            install_tree(entry, Path(tmp) / "generated")
            differing = compare_trees(Path(tmp) / "generated", target)
        return _check_verdict(target, differing, f"the build {note}")
    try:
        install_tree(entry, target)
    except OSError as error:   # a full disk: the staging is removed, the previous output stays
        discard_own_staging(target)
        print(f"build_formulas.py: cannot write the output: {write_failure(error, target)}; {target} is unchanged",
              file=sys.stderr)
        return 2
    report = Path(target) / "cache_report.json"   # volatile (not in SHA256SUMS): written after the swap, whole or not
    partial = report.with_name(f".cache_report.json.{os.getpid()}")
    try:
        partial.write_text(json.dumps({"whole build": "from the cache", "key": key}, indent=1) + "\n", encoding="utf-8")
        os.replace(partial, report)
    except OSError as error:
        partial.unlink(missing_ok=True)
        print(f"build_formulas.py: note: {target} is complete; its cache_report.json was not written: "
              f"{write_failure(error, report)}", file=sys.stderr)
    print(f"wrote {target} {note}")
    return _pdf(args, target)


def _summary(build, quiet: bool) -> None:
    if not quiet:
        from derivations.output.pipeline import summary

        print(summary(build))


def _write(build, target: Path) -> int:
    """Render, certify the emitted module (round trip) and swap into place.

    0 written; 1 a certificate failed; 2 the output cannot be written (nothing was replaced).
    """
    from derivations.core.certificates import CertificationFailure
    from derivations.output.pipeline import write_atomically

    try:
        write_atomically(build, target)
    except OutputRefused as error:
        print(f"build_formulas.py: cannot write {target}: {error}; {target} is unchanged", file=sys.stderr)
        return 2
    except OSError as error:   # a full disk (ENOSPC), a quota, a read-only remount: nothing half-written is left
        discard_own_staging(target)
        print(f"build_formulas.py: cannot write the output: {write_failure(error, target)}; {target} is unchanged",
              file=sys.stderr)
        return 2
    except CertificationFailure as failure:
        print(f"build_formulas.py: {failure}", file=sys.stderr)
        print(f"build_formulas.py: nothing was written ({target} is unchanged)", file=sys.stderr)
        return 1
    return 0


def _write_and_cache(build, target: Path, key, quiet: bool) -> int:
    """Write the build into ``target`` (:func:`_write`), keep it in the tree cache under ``key`` (if any) and
    print the summary; the exit status of the write."""
    status = _write(build, target)
    if status:
        return status
    if key is not None:
        try:
            TreeCache().store(key, target, keep=lambda name: not is_byproduct(name))
        except OSError as error:   # the output is complete: a cache that cannot take a copy only costs time later
            print(f"build_formulas.py: note: the build was not kept in the certificate cache: "
                  f"{write_failure(error, TreeCache().root)}", file=sys.stderr)
    _summary(build, quiet)
    return 0


def run(argv: list[str] | None = None) -> int:
    """:func:`main`, with Ctrl-C reported in one line (the output is swapped in whole or not at all)."""
    from suslov.executor import release_pools

    listen_for_interrupts()
    try:
        return main(argv)
    except KeyboardInterrupt:
        print("build_formulas.py: interrupted; nothing was replaced (an output is swapped in whole or not at all)",
              file=sys.stderr)
        return 130
    except manifest.UntrustedCache as error:   # a cache other users can write: refused before it is read
        print(f"build_formulas.py: {error}; nothing was written", file=sys.stderr)
        return 2
    except OSError as error:   # any other place a full disk or a vanished directory is met: one line, no traceback
        print(f"build_formulas.py: {write_failure(error, 'a file of the build')}; nothing was replaced (an output is "
              "swapped in whole or not at all)", file=sys.stderr)
        return 2
    finally:
        release_pools()   # the build is over, written or not: its workers are idle or their work abandoned

