"""Round trip: certify the generated module as emitted, not the derivation beside it.

After rendering, the build imports ``suslov_formulas.py`` from the staging directory (or,
with ``--verify DIR``, from any generated tree) and certifies the module itself:

1. **Emitted formulas (exact).**  Every function printed from a certified expression
   (``_omega``, ``_omega_general``, ``_lambda_squared``, ``_p_squared_i13_zero``,
   ``_p_squared_i23_zero``, ``_special_parameters``, ``_scattering_angle``) is called with
   a SymPy context (``ctx.tanh = sympy.tanh``, ...) and symbolic arguments; the result
   minus the certified expression (bindings substituted) must have a zero numerator after
   expansion, with tanh t, sech t and the square roots as independent indeterminates: an
   exact zero test, stronger than needed.
2. **Shared recipes (exact, every p).**  ``_integral_core(p, ring)`` and
   ``_basis_core(p, ring)`` of the module are run on the build's python-flint rings
   (symbolic d) and must equal the objects the derivations certified, polynomial by
   polynomial (the first integrals for every p, the bases the meromorphic derivation keeps,
   p <= 15); ``first_integral_coefficients(p, 3/7)`` must equal the certified
   numerators evaluated at d = 3/7 and divided by their certified denominators (exact
   Fractions), which checks the module's own scaling.  Beyond p = 15 no basis is certified
   before the module is emitted: :func:`per_p_checks` certifies the numerators of the emitted
   ``_basis_core(p, BASIS_RING)`` themselves (``meromorphic.certify_numerators``: eq:gam3,
   F_23_pol, eq:ps, gam1-gam3, asymp; recorded as the meromorphic derivation's certificates, in
   the rows of its basis table), and asymp requires their sigma to be the one the module was
   emitted with (``meromorphic_sigma.sigma_certificate``, certified for every odd p before).
3. **Float paths (numeric evidence, labelled so).**  Each float64 function is compared
   with its mpmath twin at seeded points including the hard cases (large |t|, small and
   large d, p near odd integers, large omega), for every p in range, against the error
   bound stated in its docstring; ``gamma_basis_mp`` is compared with the certified numerators
   evaluated exactly at rational points (every p) and the rows are checked to
   form a rotation; ``special_case_parameters`` must chain into ``omega`` (the body's own
   general solution in the returned frame); ``meromorphy`` must agree with
   ``kovalevskaya_exponents`` in its special cases.
4. **Run-time routes (certificates at listed points).**  Every public route (float64, ``_mp`` twins, ball
   routes, the finite-value repair, the far phase of ``gamma_basis``, the ball-checked branches of
   ``general_scattering_angle``) at points that reach each branch, against the certified closed forms
   evaluated in python-flint balls from the exact inputs (:mod:`derivations.output.runtime_routes`): a
   fault in ``suslov/runtime`` or ``suslov/kernel`` that the models of part 3 share is seen there.

A failure stops the build like any certificate (nothing is moved into place) and names
the function, p and what differs; :func:`verify` returns the first discrepancy instead.
"""
from __future__ import annotations

import hashlib
import importlib.util
import itertools
import sys
from fractions import Fraction
from pathlib import Path

import mpmath
import sympy as sp
from sympy.codegen.cfunctions import expm1

from derivations.core.certificates import (
    Certificate,
    CertificateLog,
    CertificationFailure,
    Outcome,
    stopwatch,
)
from derivations.core.recipe_rings import BASIS_RING, INTEGRAL_RING
from derivations.output.ball_reference import integral_at

SECTION = "roundtrip"
EXACT_METHOD = ("exact zero test of the emitted code evaluated with a SymPy context (numerator expanded over the "
                "rationals in the arguments, with $tanh(t)$, $sech(t)$ and the roots as indeterminates)")
EVIDENCE = "numeric evidence (not a certificate): "
_counter = itertools.count()


class SymbolicContext:
    """The emitted functions' elementary functions as SymPy functions."""

    tanh = staticmethod(sp.tanh)
    sech = staticmethod(sp.sech)
    sqrt = staticmethod(sp.sqrt)
    atan2 = staticmethod(sp.atan2)
    exp = staticmethod(sp.exp)
    expm1 = staticmethod(expm1)

    @staticmethod
    def hypot(x, y):
        return sp.sqrt(x**2 + y**2)

    @staticmethod
    def tanh_sech(t):
        return sp.tanh(t), sp.sech(t)


def load_module(directory: Path):
    """Import ``directory/suslov_formulas.py`` under a fresh private name (not ``generated``)."""
    path = Path(directory) / "suslov_formulas.py"
    if not path.is_file():
        raise FileNotFoundError(f"{path}: no generated module there")
    name = f"_suslov_formulas_under_test_{next(_counter)}"
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    try:
        spec.loader.exec_module(module)
    finally:
        sys.modules.pop(name, None)
    return module


def _record(log, claim, label, method, ok, seconds, work=0, detail=""):
    return log.record(Certificate(claim, label, method, Outcome.PASS if ok else Outcome.FAIL, seconds, work, detail))


# ------------------------------------------------------------------ 1. emitted formulas


def _is_zero(expr) -> bool:
    numerator = sp.numer(sp.together(sp.sympify(expr)))
    return sp.expand(numerator) == 0


def certify_emitted(log: CertificateLog, module, emitted: dict) -> list:
    out = []
    for name, item in emitted.items():
        with stopwatch() as elapsed:
            function = getattr(module, f"_{name}", None)
            if function is None:
                ok, detail = False, f"`_{name}` is missing from the module"
            else:
                try:
                    values = function(SymbolicContext, *item.args)
                except Exception as error:  # a broken emitted function is a failed round trip, with the reason
                    values, detail = None, f"`_{name}` raised `{type(error).__name__}`: {error}"
                if values is not None:
                    values = values if isinstance(values, tuple) else (values,)
                    reference = item.substituted()
                    bad = [i for i, (v, r) in enumerate(zip(values, reference)) if not _is_zero(v - r)]
                    ok = len(values) == len(reference) and not bad
                    detail = ("emitted code equals the certified expression" if ok else
                              f"output {bad[0] if bad else 'count'} differs: emitted {values[bad[0]] if bad else values}"
                              f" vs certified {reference[bad[0]] if bad else reference}")
                else:
                    ok = False
        out.append(_record(log, f"function `_{name}`: the emitted code equals the certified expression",
                           "round trip", EXACT_METHOD, ok, elapsed[0], len(item.outputs), detail))
    return out


# ------------------------------------------------------------------ 2. shared recipes


def certify_integral_core(log: CertificateLog, module, objects: dict) -> list:
    out = []
    d_point = Fraction(3, 7)
    for p, ff in sorted(objects.items()):
        with stopwatch() as elapsed:
            core = module._integral_core(p, INTEGRAL_RING)
            differing = [f"${name}$" for name in ("P1t", "M2", "M3", "K", "Den") if getattr(core, name) != getattr(ff, name)]
            public = module.first_integral_coefficients(p, d_point)
            expected = integral_at(ff, d_point)
            differing += [f"`first_integral_coefficients(p, 3/7)[{name!r}]`" for name in ("P1", "P2", "P3")
                          if public[name] != expected[name]]
        out.append(_record(log, f"$p = {p}$: the exact core of `first_integral` reproduces the certified $P1t$, $M2$, $M3$, $K$, $Den$, "
                           "and `first_integral_coefficients(p, 3/7)` the certified $P1, P2, P3$", "round trip",
                           "exact equality in $Z[d,w1,w2]$ (`python-flint`) and in $Q(d, w1, w2)$", not differing, elapsed[0],
                           ff.terms(), "differs: " + ", ".join(differing) if differing else "identical"))
    return out


def _core_claim(p: int) -> str:
    return f"$p = {p}$: the exact core of `gamma_basis` reproduces the certified numerators of $gammaI$ and $V$"


def certify_basis_core(log: CertificateLog, module, objects: dict) -> list:
    """The emitted ``_basis_core`` against the certified numerators kept in this process: exact equality."""
    out = []
    for p, (real, cplx) in sorted(objects.items()):
        with stopwatch() as elapsed:
            mine = module._basis_core(p, BASIS_RING)
            differing = [f"{kind} component {j + 1}" for kind, got, want in (("$gammaI$", mine[0], real),
                                                                           ("$V$", mine[1], cplx))
                         for j in range(3) if got.M[j] != want[j]]
        out.append(_record(log, _core_claim(p), "round trip", "exact equality in $Q[x,d,i]/(i^2+1)$ (`python-flint`)",
                           not differing, elapsed[0], sum(len(m) for m in real + cplx),
                           "differs: " + ", ".join(differing) if differing else "identical"))
    return out


def basis_core_by_digest(module, p: int, digest: str) -> tuple:
    """The emitted core's numerators for p against :func:`derivations.sections.meromorphic.numerators_digest` of
    the basis certified in another process (a kept basis, p <= KEEP_BASES, certified in the main process, for a
    float-path check in a worker: :func:`float_check`): (certificate, numerators), the certificate returned,
    not recorded, the numerators as (real, complex) lists."""
    from derivations.sections.meromorphic import numerators_digest

    with stopwatch() as elapsed:
        real, cplx = module._basis_core(p, BASIS_RING)
        same = numerators_digest(real.M, cplx.M) == digest
    method = "equal `SHA-256` digests of the numerators as `python-flint` prints them (the certified basis's and the emitted core's)"
    certificate = Certificate(_core_claim(p), "round trip", method, Outcome.PASS if same else Outcome.FAIL, elapsed[0],
                              sum(len(m) for m in real.M + cplx.M), "identical" if same else "differs")
    return certificate, (real.M, cplx.M)


def _proved_numerators(module, p: int, digest: str) -> tuple:
    """(the core's certificate, its numerators when its digest is the certified one, else None)."""
    core, numerators = basis_core_by_digest(module, p, digest)
    return core, numerators if core.outcome is Outcome.PASS else None


EMITTED_CORE = "the numerators of the emitted module's `_basis_core` (round trip)"


def certify_emitted_basis(module, p: int, sigma: int) -> tuple:
    """The meromorphic derivation's certificates of one odd p > KEEP_BASES made on the emitted core's numerators
    (``module._basis_core(p, BASIS_RING)``, the build's exact ring): :func:`derivations.sections.meromorphic.
    certify_numerators` (eq:gam3, F_23_pol, eq:ps, orthonormality, asymp with the ``sigma`` the module was
    emitted with).  Returns (certificates, numerators, term counts): the certificates in a private log of the
    meromorphic derivation, handed over (keys and derivation left to the main log, which records them as the
    meromorphic derivation's); the numerators (real, complex lists) only when every certificate passed, else
    None (the failed certificate stops the round trip where it is recorded: :func:`per_p_checks` then runs no
    float-path check on numerators nobody certified)."""
    from derivations.sections import meromorphic

    private = CertificateLog(derivation=meromorphic.NAME)
    numerators, terms = None, []
    try:
        with stopwatch() as elapsed:
            real, cplx = module._basis_core(p, BASIS_RING)
        meromorphic.certify_numerators(private, p, real, cplx, sigma=sigma, seconds=elapsed[0], origin=EMITTED_CORE)
        numerators, terms = (real.M, cplx.M), [len(m) for m in real.M + cplx.M]
    except CertificationFailure:
        pass
    return private.handed_over(), numerators, terms


def _private_checks(module, checks) -> list:
    """The float-path checks ``(name, argument, numerators)`` (:func:`derivations.output.float_paths.run`) in a
    private log, at 15 digits, their certificates handed over (keys left to the main log); a failed one is
    returned with the others, and the main log raises when it records it, as in one process."""
    from derivations.output import float_paths

    private = CertificateLog(derivation=SECTION)
    try:
        with mpmath.workdps(15):
            for name, argument, numerators in checks:
                float_paths.run(private, module, name, argument, numerators)
    except CertificationFailure:
        pass
    return private.handed_over()


def per_p_checks(task) -> dict:
    """Per-p work (run in a worker) for an odd p > KEEP_BASES, whose basis no process has certified yet:
    ``task = (directory, p, sigma)``.  The emitted core's numerators certified directly
    (:func:`certify_emitted_basis`: the meromorphic certificates of p, on what the module computes), then the
    float-path checks of ``first_integral`` (proven: :mod:`derivations.proofs.integral_proof`) and ``gamma_basis``
    (:mod:`derivations.output.float_paths`), the latter's exact evaluation only on numerators that passed.  The
    module is imported from the directory once per process, so the emitted code is what is checked, and the
    directory must be visible to the worker (local processes; a Dask cluster on the same file system).

    Returns plain data: ``{"basis": certificates, "terms": term counts, "checks": certificates}``, keys left to
    the main log (the basis certificates recorded as the meromorphic derivation's, the checks as the round trip's)."""
    try:
        return _per_p(task)
    finally:
        release_freed_integers()   # the numerators of this p are freed by now


def _per_p(task) -> dict:
    directory, p, sigma = task
    module = load_module_once(directory)
    basis, numerators, terms = certify_emitted_basis(module, p, sigma)
    if numerators is None:   # a basis certificate failed: it stops the round trip where it is recorded, before these
        return {"basis": basis, "terms": terms, "checks": []}
    checks = ([("first_integral", p, None)] if p in module.INTEGRAL_PS else []) + [("gamma_basis", p, numerators)]
    return {"basis": basis, "terms": terms, "checks": _private_checks(module, checks)}


def release_freed_integers() -> None:
    """Empty FLINT's cache of freed multiprecision integers (``_fmpz_cleanup_mpz_content``, FLINT 3; a no-op when the
    symbol is not found).

    Why: FLINT keeps every freed big integer of up to 64 limbs, with its limbs, for reuse (800,000 of them after one
    p = 201, the numerators' coefficients have 3,400 bits), and hands them out last-freed first, scattered over the
    heap: a worker's later p computed on them slowly.  Measured in one process doing p = 201, 199, ..., 191, 201 (shared
    2-core AMD EPYC): without it the exact steps slowed with every p (at the second p = 201 the construction 2.5 s ->
    3.7 s, the third-order test 0.72 s -> 1.59 s, the Poisson tests 0.68 s -> 1.33 s; p = 191 took 9.1 s against 7.7 s);
    with it p = 191 took 7.7 s.  With the recipe's exact routes, one process doing p = 201, 199, ..., 187 in turn took
    96 s before, 67 s after (``bench/results/basis_roundtrip.md``), and ``build_formulas.py --pmax 201 --no-cache`` 203 s
    (about 275 s before, measured apart).  Live integers are untouched (FLINT's own thread-exit cleanup; blocks still
    in use are freed when their last integer is), so nothing computed changes; emptying 800,000 takes about 50 ms."""
    global _CLEANUP
    if _CLEANUP is None:
        import ctypes

        from flint.types import fmpz

        try:   # looked up through python-flint's own extension: the FLINT it is linked with
            _CLEANUP = ctypes.CDLL(fmpz.__file__)._fmpz_cleanup_mpz_content
            _CLEANUP.restype, _CLEANUP.argtypes = None, []
        except (OSError, AttributeError):
            _CLEANUP = False
    if _CLEANUP:
        _CLEANUP()


_CLEANUP = None


_modules: dict = {}


def load_module_once(directory) -> object:
    """:func:`load_module`, once per process and module content (per-p workers check one emitted module).

    Keyed by the file's SHA-256, not only its directory: workers outlive a build (the executor keeps
    its pool), and the next build may stage a different module in the same place.
    """
    path = Path(directory) / "suslov_formulas.py"
    key = (str(directory), hashlib.sha256(path.read_bytes()).hexdigest())
    if key not in _modules:
        _modules.clear()   # one emitted module at a time is all a worker needs
        _modules[key] = load_module(Path(directory))
    return _modules[key]


# ------------------------------------------------------------------ orchestration


FLOAT_CHECKS = "round trip: float paths"


def float_check(task) -> list:
    """One check of :func:`derivations.output.float_paths.tasks`, run in a worker: ``task = (directory, name,
    argument, digest)``.  The module is imported from the directory once per process (the emitted code is
    what is checked); a ``gamma_basis`` check gets the emitted core's numerators of that p, used only when
    their :func:`derivations.sections.meromorphic.numerators_digest` equals ``digest``, the certified
    numerators' (else none, and the proof that needs them fails).  Returns the certificates, keys left to the
    main log, which records them in the order of the tasks."""
    directory, name, argument, digest = task
    module = load_module_once(directory)
    numerators = _proved_numerators(module, argument, digest)[1] if name == "gamma_basis" else None
    return _private_checks(module, [(name, argument, numerators)])


def certify_module(log: CertificateLog, build, directory: Path, meanwhile=None, bases: dict | None = None,
                   routes_first: bool = False) -> list:
    """All round-trip certificates for the module in ``directory`` (raises CertificationFailure);
    ``meanwhile()``, the caller's own work, runs in this process once the float-path checks are started.

    The float-path checks of the functions and of the p whose bases this process keeps
    (:func:`derivations.output.float_paths.tasks`) start at once in the worker processes
    (``CertificateLog.prefetch``; in this process when there are none); meanwhile this process
    certifies the emitted formulas and the exact cores against the objects kept here, then records
    the float-path certificates in their order and certifies the run-time routes.  The p > KEEP_BASES,
    whose bases the meromorphic derivation left pending (``exports["pending"]``), get :func:`per_p_checks`
    through ``CertificateLog.map_per_p`` (largest p first, recorded in p order), after everything above: the
    emitted core's numerators certified directly (recorded as the meromorphic derivation's certificates),
    then the float-path checks of that p.  ``bases``, when given, receives for each such p the keys of its
    basis certificates and the numerators' term counts (the build completes its basis table with them:
    :func:`derivations.sections.meromorphic.complete_row`).  The log is the one a single process writes.
    ``routes_first`` (:func:`verify`, which writes no log) certifies the run-time routes before recording the
    float-path checks: a faulty route is named without waiting for every float proof first.
    """
    from derivations.core.emit import emitted_formulas
    from derivations.output import float_paths, runtime_routes
    from derivations.sections.meromorphic import NAME as MEROMORPHIC
    from derivations.sections.meromorphic import numerators_digest

    module = load_module(directory)
    exports = build.results["meromorphic"].exports
    pending = list(exports.get("pending", ()))
    kept = exports["objects"]
    checks = [(str(directory), name, argument,
               numerators_digest(*kept[argument]) if name == "gamma_basis" and argument in kept else "")
              for name, argument in float_paths.tasks(module, build, skip=set(pending))]
    log.prefetch(FLOAT_CHECKS, checks, float_check, cacheable=False)
    in_workers = FLOAT_CHECKS in log.prefetched
    if meanwhile is not None:
        meanwhile()
    # the same working precision whatever the caller set: the evidence details are part of the byte-identical outputs
    certs = []

    def in_this_process():
        # while the workers check the later p; recorded first, as when it ran before them
        certs.extend(certify_emitted(log, module, emitted_formulas(build)))
        certs.extend(certify_integral_core(log, module, build.results["first_integrals"].exports["objects"]))
        certs.extend(certify_basis_core(log, module, kept))
        if routes_first:
            certs.extend(runtime_routes.certify(log, module, build))
        if in_workers:
            for batch in log.map_per_p(FLOAT_CHECKS, checks, float_check, cacheable=False):
                certs.extend(log.record(c) for c in batch)
        else:
            certs.extend(float_paths.certify(log, module, build, skip=set(pending)))
        if not routes_first:
            certs.extend(runtime_routes.certify(log, module, build))   # every public route, independent references

    try:
        with log.section(SECTION), mpmath.workdps(15):
            tasks = [(str(directory), p, exports["sigma"][p]) for p in pending]
            outcomes = log.map_per_p("round trip: bases beyond the kept ones", tasks, per_p_checks, cacheable=False,
                                     meanwhile=in_this_process)
            for p, outcome in zip(pending, outcomes):
                recorded = []
                for certificate in outcome["basis"]:
                    certificate.derivation = MEROMORPHIC   # the derivation's claims, made on the emitted core
                    recorded.append(log.record(certificate))
                if bases is not None:
                    bases[p] = {"certificates": [c.key for c in recorded], "terms": outcome["terms"]}
                certs += recorded + [log.record(c) for c in outcome["checks"]]
    except BaseException:
        log.cancel_prefetched()   # a failure before the float checks were collected leaves none running
        raise
    return certs


def verify(build, directory: Path, jobs: int | None = None) -> str | None:
    """None when the module in ``directory`` passes every round-trip check, else the first discrepancy.

    ``jobs``: worker processes for the float-path and per-p checks (None: all cores; 1: all in this process,
    where a fault patched into this process's modules, as the mutation tests do, is what gets checked).

    The run-time routes are certified before the float-path checks are recorded (``routes_first``: the order of
    a build's log does not bind a check that writes none): a fault in a route is named after about 0.3 s of
    checks instead of 1.2 s (every float proof first; ``tests/test_verify_faults.py`` seeds 16 such faults in one
    batch: 26.6 s -> 12.1 s, measured back to back); a tree that passes runs every check either way."""
    log = CertificateLog(workers=jobs)
    try:
        certify_module(log, build, directory, routes_first=True)
    except CertificationFailure as failure:
        c = failure.certificate
        return f"{c.claim}: {c.detail}"
    except (ImportError, SyntaxError, AttributeError, FileNotFoundError, TypeError, ValueError) as error:
        return f"the module in {directory} cannot be checked: {type(error).__name__}: {error}"
    return None
