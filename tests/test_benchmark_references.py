"""The benchmark's reference cache takes a committed (seed) value only when it was computed by
the same reference code (benchmarks/references.py: fingerprint of the reference modules)."""

import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))

import references as refs  # noqa: E402


def _seed(tmp_path, fingerprint):
    path = tmp_path / "seed.json"
    path.write_text(json.dumps({"k": {"value": [1.0], "seconds": 9.0, "fingerprint": fingerprint,
                                      "date": "2026-01-01"}}))
    return path


def test_seed_with_the_same_code_is_used(tmp_path):
    cache = refs.ReferenceCache(tmp_path / "cache.json", seed=_seed(tmp_path, refs.code_fingerprint()))
    assert cache.get("k", lambda: [2.0]) == [1.0]
    assert cache.seeded == {"k": "2026-01-01"}


def test_seed_from_other_code_is_recomputed(tmp_path):
    cache = refs.ReferenceCache(tmp_path / "cache.json", seed=_seed(tmp_path, "0" * 16))
    assert cache.get("k", lambda: [2.0]) == [2.0]
    assert cache.seeded == {}


def test_committed_seed_matches_todays_reference_code():
    """A change to the reference integrators must come with a refreshed seed
    (`benchmarks/speed_vs_error.py --quick --no-seed --update-seed`), or the quick benchmark
    silently goes back to computing every reference (~70 s more in `make reproduce`)."""
    seed = json.loads(refs.SEED.read_text())
    assert seed and {rec["fingerprint"] for rec in seed.values()} == {refs.code_fingerprint()}


def test_recorded_tplquad_rows_say_they_were_not_re_measured():
    """Issue #12: quick-mode speed rows taken from the recorded tplquad cache read like this
    run's measurements; their label now says "recorded on <date>, not re-measured"."""
    import speed_vs_error

    rec = json.loads((Path(speed_vs_error.TPLQUAD_CACHE)).read_text())["elastic|table1|3.5|area"]
    method, note = speed_vs_error.tplquad_label("area", rec, measured_now=False)
    assert method == f"scipy tplquad (area only; recorded on {rec['date']}, not re-measured)"
    assert "not re-measured" in note
    method, note = speed_vs_error.tplquad_label("area", rec, measured_now=True)
    assert method == "scipy tplquad (area only)" and "measured in this run" in note


def test_seed_holds_the_twin_at_every_ep_numerics_point():
    """The workflow's ep_numerics checks take the twin from the seed (44–64 s per point
    otherwise): a new or changed check point must come with
    `workflow/scripts/numerics_elastoplastic.py --update-seed`."""
    import importlib.util

    import yaml

    root = Path(__file__).resolve().parents[1]
    spec = importlib.util.spec_from_file_location("numerics_ep", root / "workflow/scripts/numerics_elastoplastic.py")
    script = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(script)
    seed = json.loads(refs.SEED.read_text())
    calls = list(script.twin_calls(yaml.safe_load((root / "config/config.yaml").read_text())))
    assert calls
    for call in calls:
        key = script.twin_key(*call)
        assert key in seed and seed[key]["fingerprint"] == refs.code_fingerprint(), call
