"""The catalog's srepr check, run in the worker processes during a build (``catalog_data.read_back``).

The build writes every formula's ``srepr`` into ``catalog.json`` and checks that it reads back: in a worker, the
text is evaluated with SymPy's constructors and must print back to itself (``pipeline.start_catalog`` /
``finish_catalog``).  A text that evaluates to another object, or not at all, is named; the balanced chunks carry
every formula once.
"""
import sympy as sp

from derivations.output import catalog_data


def test_a_faithful_text_reads_back():
    x = sp.Symbol("x", positive=True)
    expr = sp.Eq(sp.Symbol("F"), sp.sqrt(x**2 + 1) / (x - sp.Rational(3, 7)), evaluate=False)
    assert catalog_data.read_back([("formula 'f'", sp.srepr(expr))]) == []


def test_a_text_that_evaluates_to_another_object_is_named():
    # Add(1, 1) is what an unevaluated formula would print; read back it is Integer(2), another object
    found = catalog_data.read_back([("formula 'two'", "Add(Integer(1), Integer(1))")])
    assert found == ["formula 'two': its SymPy form reads back from srepr as a different object"]


def test_a_text_that_does_not_evaluate_is_named():
    (found,) = catalog_data.read_back([("formula 'bad'", "NoSuchConstructor(Integer(1))")])
    assert found.startswith("formula 'bad': its SymPy form does not read back from srepr")


def test_the_check_in_workers_is_the_check_in_line(default_build):
    """Every formula of the default build is in exactly one chunk, and the chunks read back clean, as the
    in-line check (``serialised``) says."""
    document = catalog_data.catalog_document(default_build, {n: n for n in default_build.names}, check=False)
    chunks = catalog_data.read_back_chunks(document)
    carried = sorted(text for chunk in chunks for _, text in chunk)
    assert carried == sorted(e["srepr"] for e in document["entries"] if e["srepr"])
    assert all(catalog_data.read_back(chunk) == [] for chunk in chunks)
    checked = catalog_data.catalog_document(default_build, {n: n for n in default_build.names}, check=True)
    assert checked == document


def test_a_failed_read_back_stops_the_write(default_build):
    """``finish_catalog`` raises ``CatalogError`` naming the first formula that failed, and drops the text."""
    import copy

    import pytest

    from derivations.output import pipeline

    build = copy.copy(default_build)
    build.catalog_json = "{}"
    build.catalog_chunks = [[("formula 'two' of model", "Add(Integer(1), Integer(1))")]]
    with pytest.raises(catalog_data.CatalogError, match="formula 'two' of model"):
        pipeline.finish_catalog(build)
    assert build.catalog_json is None and build.catalog_chunks == []
