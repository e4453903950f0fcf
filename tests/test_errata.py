"""The errata table: every comparison with the paper is backed by certificates."""
from generated import suslov_formulas as sf

REQUIRED_LABELS = {"ep3.26", "gen12", "eq:whole", "c's", "eq:enlev", "omegas", "eq:sysfin", "eq:necc1",
                   "eq:am2", "omegas (text)", "eq:ccalki (text)"}


def test_errata_cover_the_foundation_labels():
    labels = {e["label"] for e in sf.load_certificates()["errata"]}
    assert REQUIRED_LABELS <= labels


def test_every_erratum_is_backed_by_existing_certificates():
    doc = sf.load_certificates()
    by_key = {c["key"]: c for c in doc["certificates"]}
    for e in doc["errata"]:
        assert e["certificates"], e["label"]
        certs = [by_key[k] for k in e["certificates"]]
        if e["status"] == "corrected":
            # the printed form is refuted and the derived form is proven
            assert any(c["outcome"] == "fail" and c["expected"] == "fail" for c in certs), e["label"]
            assert any(c["outcome"] == "pass" for c in certs), e["label"]
        if e["status"] == "confirmed":
            assert all(c["outcome"] == "pass" for c in certs), e["label"]
