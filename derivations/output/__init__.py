"""The build's command line and its stages after the derivations: pipeline, rendering, round trip, documents, diff.

``cli`` is ``python build_formulas.py`` (that file only imports it when the build runs); ``pipeline`` runs the registry's derivations and writes the outputs (crash-safely, through
``suslov.outdir``); ``render`` and ``public_api`` feed the templates; ``roundtrip`` and ``float_paths``
certify the emitted module as a user imports it (the proofs of its float bounds: ``derivations.proofs``); ``pdf`` compiles, ``diff`` compares two trees;
``estimate`` predicts the build's time.

May import: ``derivations.registry``, ``derivations.proofs``, ``derivations.sections``, ``derivations.core`` and the runtime
package (``suslov``) -- nothing imports this layer except ``build_formulas.py``, the tests and benches.
"""
