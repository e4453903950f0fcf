"""Sweep scenes: many bodies instead of one (the ``[sweep]`` table, which takes the place of ``[body]``).

The paper's open problem (Conclusion: the general case I13 != 0, where the paper has no closed form;
``general_scattering_angle`` is one) asks for maps of the scattering angle (section 5.1, Theorem 5.4)
over inertia tensors and energies.  A sweep names
the points; the planner chooses a method per point; the executor runs them in chunks.

Schema (every field optional unless stated; values are a number, a list of numbers, or a range)::

    [sweep]
    # exactly one of: bodies = "FILE.csv" | p and d | I11, I22 and I33 (I12, I13, I23 default 0)
    bodies = "bodies.csv"          # path relative to the scene file; columns I11, I22, I33, I12, I13, I23,
                                   # optional energy; one point per row
    I11 = 2.0
    I13 = {linear = [-0.4, 0.4], count = 41}       # count equally spaced values, ends included
    I23 = {log = [0.01, 1.0], count = 20}          # logarithmically spaced, both ends > 0
    d = {random = [0.05, 2.0], count = 100, seed = 7}   # seeded uniform values (numpy default_rng)
    energy = [0.5, 1.0, 2.0]       # kinetic energies; default: rate lam = 1
    chunk = 256                    # points per chunk (default: about 8 chunks per worker)

A value may also be a decimal or ``"a/b"`` string (``I23 = ["-0.2", "-1/3"]``): the exact effects
(``galois_group``, ``scattering_angle_enclosure``) read it as written (-1/5, -1/3), as they read a CSV cell
("-0.2" in the file is -1/5); float values, and every value of a range, are the binary numbers they hold
(:mod:`suslov.simulator.exact`).  The rest of the sweep computes with float64.

Points are the Cartesian product of the fields in the order p, d or I11, I22, I33, I12, I13, I23,
then energy (the energies of one body are consecutive rows).  Errors in the scene or the CSV
(missing column, non-numeric cell, NaN, a negative count, 0 points, more than ``MAX_POINTS``) are
:class:`~suslov.simulator.scene.SceneError` naming the file, the row or the field; a point that is
physically impossible (a tensor that is not positive definite, say) is refused on its own row
by the sweep, not here.
"""
from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path

import numpy as np

from suslov.kernel.validate import rational, shown
from suslov.simulator.scene_errors import SceneError

MAX_POINTS = 10_000_000
TENSOR_FIELDS = ("I11", "I22", "I33", "I12", "I13", "I23")
PD_FIELDS = ("p", "d")
RANGE_KINDS = ("linear", "log", "random")
ALLOWED = ("bodies", *PD_FIELDS, *TENSOR_FIELDS, "energy", "chunk")


@dataclass(frozen=True)
class Sweep:
    """The points of a sweep: ``columns`` names the inputs, ``values`` has one row per point."""

    columns: tuple
    values: np.ndarray             # shape (points, len(columns)), float64
    kind: str                      # "tensor" or "pd"
    varying: tuple                 # the fields with more than one value (grid axes), in column order
    energies: int                  # number of energies per body (consecutive rows), 1 without a list
    chunk: int | None
    source: str                    # "grid" or the CSV path
    written: np.ndarray | None = None   # object array like values: the string a cell was written as, where the
                                        # exact effects need it (its decimal is not its float's binary value)

    def __len__(self) -> int:
        return len(self.values)

    def point(self, i: int) -> dict:
        return dict(zip(self.columns, (float(x) for x in self.values[i])))

    def written_point(self, i: int) -> dict | None:
        """column -> the string the scene or the CSV gave for point ``i`` (None where the float is the number)."""
        return None if self.written is None else dict(zip(self.columns, self.written[i]))


def _error(path, field_name, reason):
    return SceneError(path, field_name, reason)


def _finite(path, name, value):
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise _error(path, name, f"{shown(value)} is not a number")
    try:
        number = float(value)
    except OverflowError:   # a Python int beyond float64 (10**400)
        raise _error(path, name, f"{shown(value)} is beyond float64's range (|x| <= 1.8e308)") from None
    if not math.isfinite(number):
        raise _error(path, name, f"{value!r} is not finite")
    return number


def _count(path, name, table) -> int:
    count = table.get("count")
    if isinstance(count, bool) or not isinstance(count, int):
        raise _error(path, f"{name}.count", f"{count!r}: must be an integer (the number of values)")
    if count < 0:
        raise _error(path, f"{name}.count", f"{count}: a count cannot be negative")
    if count > MAX_POINTS:
        raise _error(path, f"{name}.count", f"{count}: more than {MAX_POINTS} values")
    return count


def _range(path, name, table) -> np.ndarray:
    kinds = [k for k in RANGE_KINDS if k in table]
    unknown = sorted(set(table) - {*RANGE_KINDS, "count", "seed"})
    if unknown:
        raise _error(path, f"{name}.{unknown[0]}", f"unknown key; a range has one of {', '.join(RANGE_KINDS)}, "
                     "count and (random only) seed")
    if len(kinds) != 1:
        raise _error(path, name, f"a range needs exactly one of {', '.join(RANGE_KINDS)} (= [start, stop])")
    kind = kinds[0]
    ends = table[kind]
    if not isinstance(ends, list) or len(ends) != 2:
        raise _error(path, f"{name}.{kind}", f"{ends!r}: must be [start, stop]")
    a, b = (_finite(path, f"{name}.{kind}[{i}]", ends[i]) for i in range(2))
    count = _count(path, name, table)
    if "seed" in table and kind != "random":
        raise _error(path, f"{name}.seed", "only a random range takes a seed")
    if kind == "linear":
        if not math.isfinite(b - a):   # [-1e308, 1e308]: b - a overflows, linspace gave NaN and inf
            weights = np.linspace(0.0, 1.0, count)
            return (1.0 - weights) * a + weights * b
        return np.linspace(a, b, count)
    if kind == "log":
        if not (a > 0 and b > 0):
            raise _error(path, f"{name}.log", f"[{a}, {b}]: a logarithmic range needs both ends > 0")
        return np.geomspace(a, b, count)
    seed = table.get("seed", 0)
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise _error(path, f"{name}.seed", f"{seed!r}: must be a non-negative integer")
    if not a < b:
        raise _error(path, f"{name}.random", f"[{a}, {b}]: need start < stop")
    if not math.isfinite(b - a):   # numpy's uniform refuses a range wider than float64 (OverflowError)
        weights = np.random.default_rng(seed).uniform(0.0, 1.0, count)
        return (1.0 - weights) * a + weights * b
    return np.random.default_rng(seed).uniform(a, b, count)


def _written(path, name, value):
    """(float, the string as written or None) of one listed value: a number, or a decimal / "a/b" string."""
    if not isinstance(value, str):
        return _finite(path, name, value), None
    try:   # read exactly, its size checked before conversion (MAX_ENTRY_BITS of suslov.kernel.validate)
        exact = rational(name, value)
    except ValueError as error:
        reason = str(error).split(": ", 1)[-1]
        raise _error(path, name, f"{shown(value)} is not a number (a decimal or \"a/b\" string is)"
                     if "not a decimal" in reason else f"{shown(value)}: {reason}") from None
    try:
        number = float(exact)
    except OverflowError:
        raise _error(path, name, f"{shown(value)} is beyond float64's range") from None
    return number, (value.strip() if Fraction(number) != exact else None)


def _values(path, name, value) -> tuple[np.ndarray, list | None]:
    """(float64 values, the strings they were written as or None) of one field."""
    field_name = f"sweep.{name}"
    if isinstance(value, dict):
        return _range(path, field_name, value), None
    if not isinstance(value, list):
        value = [value]
        names = [field_name]
    else:
        if len(value) > MAX_POINTS:
            raise _error(path, field_name, f"more than {MAX_POINTS} values")
        names = [f"{field_name}[{i}]" for i in range(len(value))]
    pairs = [_written(path, n, v) for n, v in zip(names, value)]
    texts = [t for _, t in pairs]
    return np.array([x for x, _ in pairs], dtype=float), (texts if any(t is not None for t in texts) else None)


def _energy_positive(path, energies):
    for i, e in enumerate(energies):
        if not e > 0:
            raise _error(path, "sweep.energy", f"value {i}: {e!r}: an energy must be > 0")


def read_bodies_csv(path: Path, scene_path, keep_written: bool = False) -> tuple[tuple, np.ndarray, np.ndarray | None]:
    """Columns, rows and (``keep_written``) the cells as written of a bodies file; errors name the file, the row
    (1 = first data row) and the column.  A cell is kept as written only where its decimal is not its float's
    binary value ("0.3", not "0.5"); None when no cell is, or when not asked."""
    if not path.is_file():
        raise _error(scene_path, "sweep.bodies", f"{path}: file not found")
    # utf-8-sig: a byte-order mark (Excel's "CSV UTF-8", Notepad) is dropped instead of becoming part of the first
    # column's name ("\ufeffI11", refused as "missing column 'I11'"); a file without one reads as plain UTF-8
    with path.open(newline="", encoding="utf-8-sig") as handle:
        reader = csv.reader(handle)
        try:
            header = [h.strip() for h in next(reader)]
        except StopIteration:
            raise _error(path, "header", "the file is empty (need columns I11, I22, I33, I12, I13, I23)") from None
        duplicated = sorted({c for c in header if header.count(c) > 1})
        if duplicated:
            raise _error(path, "header", f"column {duplicated[0]!r} appears {header.count(duplicated[0])} times; "
                         "each column must appear once")
        missing = [c for c in TENSOR_FIELDS if c not in header]
        if missing:
            raise _error(path, "header", f"missing column {missing[0]!r} (need {', '.join(TENSOR_FIELDS)}; "
                         "optional energy)")
        columns = tuple(c for c in (*TENSOR_FIELDS, "energy") if c in header)
        index = [header.index(c) for c in columns]
        unknown = sorted(set(header) - set(columns))
        if unknown:
            raise _error(path, "header", f"unknown column {unknown[0]!r}")
        rows, written, inexact = [], [], False
        for number, row in enumerate(reader, 1):
            if not row or all(not cell.strip() for cell in row):
                continue
            if len(row) != len(header):
                raise _error(path, f"row {number}", f"{len(row)} cells, the header has {len(header)}")
            values, texts = [], []
            for column, k in zip(columns, index):
                cell = row[k].strip()
                try:
                    x = float(cell)
                except ValueError:
                    raise _error(path, f"row {number}, column {column}", f"{shown(cell)} is not a number") from None
                if not math.isfinite(x):
                    raise _error(path, f"row {number}, column {column}", f"{shown(cell)} is not finite")
                values.append(x)
                if keep_written:
                    text = None if column == "energy" or _exact_cell(path, number, column, cell) == Fraction(x) else cell
                    inexact = inexact or text is not None
                    texts.append(text)
            rows.append(values)
            if keep_written:
                written.append(texts)
            if len(rows) > MAX_POINTS:
                raise _error(path, "rows", f"more than {MAX_POINTS} points")
    if not rows:
        raise _error(path, "rows", "no data rows: a sweep needs at least one point")
    return columns, np.array(rows, dtype=float), (_object_array(written) if inexact else None)


def _exact_cell(path, number: int, column: str, cell: str) -> Fraction:
    """A cell read exactly, its size checked before conversion (``MAX_ENTRY_BITS`` of :mod:`suslov.kernel.validate`:
    a cell "1e-100000000" is a float 0.0 but would be a 100-million-digit denominator)."""
    where = f"row {number}, column {column}"
    try:
        return rational(where, cell)
    except ValueError as error:
        raise _error(path, where, str(error).split(": ", 1)[-1]) from None


def _object_array(rows: list) -> np.ndarray:
    out = np.empty((len(rows), len(rows[0]) if rows else 0), dtype=object)
    for i, row in enumerate(rows):
        out[i, :] = row
    return out


def parse_sweep(path, table, keep_written: bool = False) -> Sweep:
    """Validate a ``[sweep]`` table and expand its points (see the module docstring).

    ``keep_written``: keep the CSV cells as written (``Sweep.written``) where their decimal is not their float's
    binary value; the scene asks for it when it computes an exact effect (the strings cost memory per point).
    Strings written in the scene itself are always kept."""
    if not isinstance(table, dict):
        raise _error(path, "sweep", "must be a table ([sweep])")
    unknown = sorted(set(table) - set(ALLOWED))
    if unknown:
        raise _error(path, f"sweep.{unknown[0]}", f"unknown field; allowed: {', '.join(ALLOWED)}")
    chunk = table.get("chunk")
    if chunk is not None and (isinstance(chunk, bool) or not isinstance(chunk, int) or chunk < 1):
        raise _error(path, "sweep.chunk", f"{chunk!r}: must be a positive integer")
    has_csv = "bodies" in table
    has_pd = any(k in table for k in PD_FIELDS)
    has_tensor = any(k in table for k in TENSOR_FIELDS)
    if has_csv + has_pd + has_tensor != 1:
        raise _error(path, "sweep", "give exactly one of: bodies = \"FILE.csv\", p and d, or I11, I22, I33 "
                     "(with optional I12, I13, I23)")
    if has_csv:
        if not isinstance(table["bodies"], str):
            raise _error(path, "sweep.bodies", "must be a path (string) relative to the scene file")
        csv_path = Path(path).parent / table["bodies"]
        columns, values, written = read_bodies_csv(csv_path, path, keep_written)
        if "energy" in columns:
            if "energy" in table:
                raise _error(path, "sweep.energy", f"{csv_path} has an energy column: give energies in one place")
            _energy_positive(csv_path, values[:, columns.index("energy")])
            return Sweep(columns, values, "tensor", (), 1, chunk, str(csv_path), written)
        energies = _values(path, "energy", table["energy"])[0] if "energy" in table else None
        if energies is None:
            return Sweep(columns, values, "tensor", (), 1, chunk, str(csv_path), written)
        _energy_positive(path, energies)
        grid = np.repeat(values, len(energies), axis=0)
        grid = np.column_stack([grid, np.tile(energies, len(values))])
        if written is not None:
            written = np.column_stack([np.repeat(written, len(energies), axis=0),
                                       np.full(len(grid), None, dtype=object)])
        return Sweep((*columns, "energy"), grid, "tensor", (), len(energies), chunk, str(csv_path), written)
    names = PD_FIELDS if has_pd else TENSOR_FIELDS
    required = PD_FIELDS if has_pd else TENSOR_FIELDS[:3]
    for key in required:
        if key not in table:
            raise _error(path, f"sweep.{key}", "missing (" + ("p and d go together" if has_pd else
                         "a tensor sweep needs I11, I22 and I33; I12, I13, I23 default to 0") + ")")
    fields = {name: _values(path, name, table.get(name, 0.0)) for name in names}
    axes = [(name, fields[name][0]) for name in names]
    if "energy" in table:
        energies = _values(path, "energy", table["energy"])[0]
        _energy_positive(path, energies)
        axes.append(("energy", energies))
    total = math.prod(len(v) for _, v in axes)
    if total == 0:
        empty = next(n for n, v in axes if len(v) == 0)
        raise _error(path, f"sweep.{empty}", "has no values: the sweep has 0 points")
    if total > MAX_POINTS:
        raise _error(path, "sweep", f"{total} points: more than {MAX_POINTS} (split the sweep)")
    mesh = np.meshgrid(*[v for _, v in axes], indexing="ij")
    values = np.column_stack([m.ravel() for m in mesh])
    varying = tuple(n for n, v in axes if len(v) > 1 and n != "energy")
    energies = len(axes[-1][1]) if axes[-1][0] == "energy" else 1
    written = None
    if any(texts is not None for _, texts in fields.values()):   # the strings, point by point (object array)
        index = np.meshgrid(*[np.arange(len(v)) for _, v in axes], indexing="ij")
        written = np.full(values.shape, None, dtype=object)
        for k, name in enumerate(names):
            texts = fields[name][1]
            if texts is not None:
                written[:, k] = np.array(texts, dtype=object)[index[k].ravel()]
    return Sweep(tuple(n for n, _ in axes), values, "pd" if has_pd else "tensor", varying, energies, chunk, "grid",
                 written)


def tensor_of(point: dict, exact: bool = False):
    """The symmetric 3x3 tensor of a tensor-sweep point: float64, or (``exact``) the point's numbers as they
    are (nested lists, for :func:`suslov.simulator.exact.from_tensor`)."""
    g = point.get
    rows = [[g("I11"), g("I12", 0), g("I13", 0)],
            [g("I12", 0), g("I22"), g("I23", 0)],
            [g("I13", 0), g("I23", 0), g("I33")]]
    return rows if exact else np.array(rows, dtype=float)
