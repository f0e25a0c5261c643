"""The Snakemake workflow: config vs schema, the DAG plans on a fresh clone, rule hygiene,
one small scene run end to end (then a re-run does nothing), the cluster profiles (SLURM plans;
a sweep dispatched through the generic cluster executor with a local submit script)."""

import re
import shutil
import subprocess
import sys
from pathlib import Path

import jsonschema
import pytest
import yaml

ROOT = Path(__file__).resolve().parents[1]
CONFIG = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())
SCHEMA = yaml.safe_load((ROOT / "config" / "schema.yaml").read_text())
PAPER = yaml.safe_load((ROOT / "config" / "paper_values.yaml").read_text())
SNAKEMAKE = [sys.executable, "-m", "snakemake"]


def fresh_clone(tmp_path) -> Path:
    """The tracked workflow files in a new directory (no results/, no .snakemake/)."""
    dest = tmp_path / "clone"
    dest.mkdir()
    shutil.copy2(ROOT / "Snakefile", dest / "Snakefile")
    for d in ("workflow", "config", "src", "docs", "benchmarks"):  # benchmarks/: the seed of the twin checks
        if (ROOT / d).exists():
            shutil.copytree(ROOT / d, dest / d, ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
    return dest


def snakemake(cwd, *args, timeout=300):
    return subprocess.run(
        [*SNAKEMAKE, *args], cwd=cwd, capture_output=True, text=True, timeout=timeout
    )


# -- configuration -----------------------------------------------------------------------
def test_config_validates_against_schema():
    jsonschema.validate(CONFIG, SCHEMA)
    from snakemake.utils import validate

    validate(dict(CONFIG), str(ROOT / "config" / "schema.yaml"))


@pytest.mark.parametrize(
    "mutate, message",
    [
        (lambda c: c["surfaces"]["table1"].update(m00=-1.0), "m00"),
        (lambda c: c["scenes"]["table1"]["tolerances"]["gw"]["pressure"].pop("why"), "why"),
        (lambda c: c["scenes"]["table1"]["accuracy"].update(production="fast"), "fast"),
        (lambda c: c["scenes"]["fig4"].update(hertz=["approximate"]), "approximate"),
        (lambda c: c.update(reference_dps="twelve"), "twelve"),
        (lambda c: c["scenes"]["fig3"].pop("s"), "'s'"),
        # the gate's anchors (issue 29): a tolerance states why, a sample names its s
        (lambda c: c["gate_anchors"]["curves"]["tolerance"].pop("why"), "why"),
        (lambda c: c["gate_anchors"]["curves"]["samples"]["fig5"][0].pop("s"), "'s'"),
        (lambda c: c["fe_anchors"]["punch"]["tolerances"].pop("energy"), "energy"),
    ],
)
def test_schema_rejects_bad_configs(mutate, message):
    import copy

    bad = copy.deepcopy(CONFIG)
    mutate(bad)
    with pytest.raises(jsonschema.ValidationError, match=message):
        jsonschema.validate(bad, SCHEMA)


def test_scenes_refer_to_defined_surfaces_models_and_printed_rows():
    for name, scene in CONFIG["scenes"].items():
        if scene["kind"] == "mindlin_table":
            printed = PAPER[name]
            assert len(printed["rows"]) == len(scene[printed["row_key"]])
            assert {c["paper_column"] for c in scene["columns"].values()} == set(printed["columns"])
        if scene["kind"] == "table":
            assert scene["surface"] in CONFIG["surfaces"]
            assert set(scene["models"]) <= set(CONFIG["models"])
            printed = PAPER[name]
            assert printed["row_key"] == "s"
            assert [float(x) for x in printed["rows"]] == [float(x) for x in scene["s"]]
            assert printed["surface"] == CONFIG["surfaces"][scene["surface"]]
            assert float(printed["E_star"]) == scene["E_star"]
            for model in scene["models"]:
                column = printed["columns"][CONFIG["models"][model]["paper_column"]]
                for q in scene["quantities"]:
                    assert len(column[q]) == len(scene["s"])
                    assert q in scene["tolerances"][model], f"{name}/{model}/{q} has no tolerance"
        for curve in scene.get("curves", []):
            assert curve["surface"] in CONFIG["surfaces"]


def test_paper_values_are_printed_strings():
    for table in ("table1", "table2", "table3"):
        for column in PAPER[table]["columns"].values():
            for values in column.values():
                assert all(isinstance(v, str) and float(v) > 0 for v in values)


# -- rule hygiene --------------------------------------------------------------------------
def _rule_blocks():
    for smk in sorted((ROOT / "workflow" / "rules").glob("*.smk")):
        text = smk.read_text()
        for m in re.finditer(r"^rule (\w+):\n(.*?)(?=^\S|\Z)", text, flags=re.M | re.S):
            yield smk.name, m.group(1), m.group(2)


def test_every_rule_has_a_log_and_compute_rules_a_benchmark():
    blocks = list(_rule_blocks())
    assert {name for _, name, _ in blocks} >= {"reference", "production", "table", "figure", "verify"}
    for smk, name, body in blocks:
        if "output:" in body:
            assert "log:" in body, f"{smk}: rule {name} has no log:"
        if "PHYSICS_SOURCES" in body:  # rules that compute with the library
            assert "benchmark:" in body, f"{smk}: compute rule {name} has no benchmark:"


def test_profiles_and_entry_points_exist():
    ci = yaml.safe_load((ROOT / "workflow" / "profiles" / "ci" / "config.yaml").read_text())
    slurm = yaml.safe_load((ROOT / "workflow" / "profiles" / "slurm" / "config.yaml").read_text())
    assert slurm["executor"] == "slurm"
    local = yaml.safe_load((ROOT / "workflow" / "profiles" / "cluster-local" / "config.yaml").read_text())
    assert local["executor"] == "cluster-generic"
    assert (ROOT / local["cluster-generic-submit-cmd"]).stat().st_mode & 0o111
    assert "make test-slow" in (ROOT / ".ci" / "run").read_text()
    assert "reference_dps=12" in ci["config"] and ci["cores"] == 2
    default = yaml.safe_load((ROOT / "workflow" / "profiles" / "default" / "config.yaml").read_text())
    assert default["rerun-incomplete"] is True
    makefile = (ROOT / "Makefile").read_text()
    for target in ("reproduce:", "test:", "test-slow:", "verify:", "clean:"):
        assert re.search(rf"^{target}", makefile, flags=re.M)
    run = ROOT / ".ci" / "run"
    assert run.stat().st_mode & 0o111, ".ci/run must be executable"
    assert "set -euo pipefail" in run.read_text()
    readme = (ROOT / "README.md").read_text().split("\n")
    commands = [line.strip() for line in readme if line.strip().startswith("make ")]
    assert commands[:2] == ["make reproduce", "make test"]


# -- the DAG -----------------------------------------------------------------------------------
def _files_outside_snakemake_state(root):
    return {p for p in root.rglob("*") if ".snakemake" not in p.relative_to(root).parts}


def test_dry_run_plans_all_targets_on_a_fresh_clone(tmp_path):
    clone = fresh_clone(tmp_path)
    before = _files_outside_snakemake_state(clone)
    r = snakemake(clone, "-n", "all")
    assert r.returncode == 0, r.stdout + r.stderr
    # issue 22: a dry run wrote results/code/*.sha256; it writes nothing (Snakemake's own
    # .snakemake/ state aside), and plans the code fingerprints as jobs instead
    assert _files_outside_snakemake_state(clone) == before
    out = r.stdout + r.stderr
    assert re.search(r"^code_fingerprint\s+\d+$", out, flags=re.M), out
    tables = [n for n, s in CONFIG["scenes"].items() if s["kind"] == "table"]
    n_models = sum(len(CONFIG["scenes"][t]["models"]) for t in tables)
    assert re.search(rf"^reference\s+{n_models}$", out, flags=re.M), out
    assert re.search(rf"^production\s+{n_models}$", out, flags=re.M), out
    for rule in ("table", "figure", "verification_report", "verify", "all"):
        assert re.search(rf"^{rule}\s+\d+$", out, flags=re.M), rule
    # every named target plans (one invocation), and the CI profile plans the reference at
    # its lower precision
    r = snakemake(clone, "-n", "table1", "table2", "fig3", "fig4", "verify",
                  "--profile", "workflow/profiles/ci", "--workflow-profile", "none")
    assert r.returncode == 0, r.stdout + r.stderr
    assert "results/reference/dps12/table1/gw.nc" in r.stdout + r.stderr
    # a table scene only asks for its own cells: no figure curves in its DAG
    r = snakemake(clone, "-n", "table1")
    assert "curves" not in (r.stdout + r.stderr).split("Job stats")[-1]
    # elasto-plastic scenes: one curves job per computing scene (Fig. 6 uses Fig. 5's), the
    # sweeps split into their configured parts, every figure target plans
    ep = [n for n, s in CONFIG["scenes"].items()
          if s["kind"] in ("elastoplastic_psi", "stiffness_pressure", "stiffness_sensitivity") and "uses" not in s]
    assert re.search(rf"^curves_elastoplastic\s+{len(ep)}$", out, flags=re.M), out
    parts = sum(sw["split"]["jobs"] for sw in CONFIG.get("sweeps", {}).values())
    assert re.search(rf"^sweep_part\s+{parts}$", out, flags=re.M), out
    r = snakemake(clone, "-n", "fig5", "fig6", "fig7", "fig8", "stiffness_sensitivity", "sweeps")
    assert r.returncode == 0, r.stdout + r.stderr
    r = snakemake(clone, "-n", "fig6")
    assert "results/curves/fig5.nc" in r.stdout + r.stderr and "results/curves/fig6.nc" not in r.stdout + r.stderr


def test_fig4_scene_end_to_end_then_nothing_to_do(tmp_path):
    clone = fresh_clone(tmp_path)
    # issue 22: what a hard kill of an earlier run left behind (roughcontact.files.atomic_path's
    # temporaries) is removed when the next run starts
    stale = [clone / "paper_figures" / ".fig18.pdf.k1ll3d.part", clone / "results" / "curves" / ".fig4.nc.x2y.part"]
    for part in stale:
        part.parent.mkdir(parents=True, exist_ok=True)
        part.write_bytes(b"half")
    r = snakemake(clone, "--cores", "1", "fig4")
    assert r.returncode == 0, r.stdout + r.stderr
    assert not any(p.exists() for p in stale) and not list(clone.rglob("*.part"))
    for f in ("paper_figures/fig4.png", "paper_figures/fig4.csv", "results/curves/fig4.nc",
              "results/verify/fig4.checks.csv", "logs/curves/fig4.log", "logs/figure/fig4.log",
              "results/benchmarks/curves/fig4.tsv"):
        assert (clone / f).is_file(), f
    from roughcontact import io
    from roughcontact.paper import verify

    ds = io.read_netcdf(clone / "results/curves/fig4.nc")
    assert ds.sizes["e"] == CONFIG["scenes"]["fig4"]["e"]["num"]
    assert ds["f1"].attrs["units"] == "1"
    prov = io.read_provenance(ds)
    assert prov["config"]["scene"] == "fig4" and prov["roughcontact_version"]
    checks = verify.checks_from_csv((clone / "results/verify/fig4.checks.csv").read_text())
    assert {c.status for c in checks} == {"ok"}, [c.detail for c in checks]
    r = snakemake(clone, "-n", "fig4")
    assert r.returncode == 0 and "Nothing to be done" in r.stdout + r.stderr

    # issue #12: relocatable. The same checkout and results under another path plan nothing
    # (rule inputs were absolute paths: a copied results tree was planned again from scratch)
    moved = clone.rename(tmp_path / "moved")
    r = snakemake(moved, "-n", "fig4")
    assert r.returncode == 0 and "Nothing to be done" in r.stdout + r.stderr, r.stdout + r.stderr
    # issue #12: a comment or docstring in claims.py changes no number and re-plans nothing
    # (it re-planned 9 jobs); code re-plans the figure job that checks the claims, not the curves
    claims = moved / "src" / "roughcontact" / "paper" / "claims.py"
    text = claims.read_text()
    claims.write_text(text.replace('"""', '"""Reworded. ', 1) + "\n# a comment\n")
    r = snakemake(moved, "-n", "fig4")
    assert r.returncode == 0 and "Nothing to be done" in r.stdout + r.stderr, r.stdout + r.stderr
    claims.write_text(text + "\nRESOLUTION_NOTE = 1.0\n")
    r = snakemake(moved, "-n", "fig4")
    plan = (r.stdout + r.stderr).split("Job stats")[-1]
    assert re.search(r"^figure\s+1$", plan, flags=re.M) and "curves_hertz_factors" not in plan, plan


def test_rules_bake_no_interpreter_or_absolute_path():
    """Issue #12: `params.py = sys.executable` put the venv's absolute path into the jobs'
    records (a params change re-runs them elsewhere)."""
    for smk in sorted((ROOT / "workflow" / "rules").glob("*.smk")) + [ROOT / "Snakefile"]:
        text = smk.read_text()
        assert not re.search(r"^\s+\w+=sys\.executable", text, flags=re.M), smk
        assert "{params.py}" not in text, smk


# -- cluster profiles ----------------------------------------------------------------------------
TINY_SWEEP = {
    "description": "two parts, one per m00",
    "axes": {"m00": [0.0625, 0.3125], "psi": [0.5]},
    "s": {"start": 0.0, "stop": 2.0, "num": 3},
    "fixed": {"m20": 8e-5, "m02": 8e-4, "m40": 1.04e-6, "m04": 1.04e-4, "E_star": 1.14e5},
    "closure": "yield-from-psi",
    "hertz": "exact",
    "accuracy": "plot",
    "split": {"axis": "m00", "jobs": 2},
}


def _clone_with_tiny_sweep(tmp_path):
    clone = fresh_clone(tmp_path)
    cfg = yaml.safe_load((clone / "config" / "config.yaml").read_text())
    cfg["sweeps"] = {"tiny": TINY_SWEEP}
    # the gate samples the configured sweep (gate_anchors.curves.samples): sample the tiny one
    cfg["gate_anchors"]["curves"]["samples"].pop("m00_psi")
    cfg["gate_anchors"]["curves"]["samples"]["tiny"] = [{"m00": 0.3125, "psi": 0.5, "s": 1.0}]
    (clone / "config" / "config.yaml").write_text(yaml.safe_dump(cfg, sort_keys=False))
    return clone


def test_slurm_profile_plans_the_sweep_jobs(tmp_path):
    clone = _clone_with_tiny_sweep(tmp_path)
    r = snakemake(clone, "--profile", str(ROOT / "workflow/profiles/slurm"), "--workflow-profile", "none",
                  "-n", "sweeps")
    assert r.returncode == 0, r.stdout + r.stderr
    assert re.search(r"^sweep_part\s+2$", r.stdout + r.stderr, flags=re.M), r.stdout + r.stderr


@pytest.mark.slow
@pytest.mark.ci_elsewhere
def test_sweep_dispatched_through_generic_cluster_executor(tmp_path):
    """Each sweep part goes through the submit script (as through sbatch) and the merged
    sweep equals a direct evaluation. CI (ci_elsewhere): the SLURM tier submits the same
    sweep's parts to a real scheduler (tests/test_slurm.py)."""
    import numpy as np

    from roughcontact import io
    from roughcontact.contact.sweep import run_sweep, spec_from_config

    clone = _clone_with_tiny_sweep(tmp_path)
    env_path = f"{Path(sys.executable).parent}:{__import__('os').environ.get('PATH', '')}"
    r = subprocess.run(
        [*SNAKEMAKE, "--profile", "workflow/profiles/cluster-local", "--workflow-profile", "none", "sweeps"],
        cwd=clone, capture_output=True, text=True, timeout=600, env={**__import__("os").environ, "PATH": env_path},
    )
    assert r.returncode == 0, r.stdout + r.stderr
    submitted = (clone / ".snakemake/cluster-local/submissions.txt").read_text().splitlines()
    assert len(submitted) == 2 and all("sweep_part" in line for line in submitted), submitted
    merged = io.read_netcdf(clone / "results/sweeps/tiny.nc")
    direct = run_sweep(spec_from_config(TINY_SWEEP, CONFIG["units"]))
    for v in direct.data_vars:
        np.testing.assert_array_equal(merged[v].values, direct[v].values, err_msg=v)
    prov = io.read_provenance(merged)
    assert prov["config"]["sweep"] == "tiny" and prov["roughcontact_version"]
    assert merged["pressure"].attrs["units"] == CONFIG["units"]["stress"]


# -- the BEM comparison (issue 21): optional, not part of all -------------------------------------
def _hide_contact_mechanics(tmp_path):
    """An environment in which `import ContactMechanics` fails, as without the extra [bem]."""
    import os

    fake = tmp_path / "no_bem" / "ContactMechanics"
    fake.mkdir(parents=True, exist_ok=True)
    (fake / "__init__.py").write_text("raise ImportError('ContactMechanics hidden by the test')\n")
    return {**os.environ, "PYTHONPATH": os.pathsep.join(filter(None, [str(fake.parent), os.environ.get("PYTHONPATH")]))}


def test_bem_plans_one_job_per_realisation(tmp_path):
    """The CI scale: 2 families x 2 seeds on 256^2, the checks, the report; cached per file."""
    from roughcontact.bem.solver import available

    if not available():
        pytest.skip("the present path needs the extra [bem]")
    clone = fresh_clone(tmp_path)
    r = snakemake(clone, "-n", "bem", "--config", "bem_scale=ci")
    assert r.returncode == 0, r.stderr
    assert re.search(r"bem_run\s+4\b", r.stdout) and re.search(r"bem_checks\s+1\b", r.stdout), r.stdout
    for fam in CONFIG["bem"]["families"]:
        assert f"results/bem/runs/{fam}/n256/seed1.nc" in r.stdout


def test_bem_without_the_extra_says_skipped_in_one_line(tmp_path):
    clone = fresh_clone(tmp_path)
    r = subprocess.run([*SNAKEMAKE, "--cores", "1", "bem"], cwd=clone, capture_output=True, text=True, timeout=300,
                       env=_hide_contact_mechanics(tmp_path))
    assert r.returncode == 0, r.stderr
    from roughcontact.bem.solver import SKIP_MESSAGE

    assert [line for line in (r.stdout + r.stderr).splitlines() if "[bem]" in line] == [SKIP_MESSAGE]
    assert not (clone / "results" / "bem").exists()
    r = subprocess.run([*SNAKEMAKE, "-n", "all"], cwd=clone, capture_output=True, text=True, timeout=300,
                       env=_hide_contact_mechanics(tmp_path))
    assert r.returncode == 0, r.stderr  # the rest of the workflow is unaffected, and bem is not part of all
    assert "bem_run" not in r.stdout and "bem_report" not in r.stdout


def test_verify_after_a_ci_scale_bem_does_not_run_the_full_bem(tmp_path):
    """CI runs `snakemake bem --config bem_scale=ci`, then `verify`: the BEM report (present) is
    read as it is, not rebuilt at the configured (full) scale, which ran the full BEM inside
    CI's verify."""
    clone = fresh_clone(tmp_path)
    (clone / "paper_figures").mkdir(exist_ok=True)
    (clone / "paper_figures" / "bem.md").write_text("# BEM\n")
    (clone / "results" / "verify").mkdir(parents=True, exist_ok=True)
    (clone / "results" / "verify" / "bem.checks.csv").write_text("")
    r = snakemake(clone, "-n", "verify")
    assert r.returncode == 0, r.stderr
    assert "bem_run" not in r.stdout and "bem_report" not in r.stdout


def test_bad_bem_scale_is_refused(tmp_path):
    clone = fresh_clone(tmp_path)
    r = snakemake(clone, "-n", "bem", "--config", "bem_scale=huge")
    assert r.returncode != 0 and "bem_scale 'huge'" in r.stdout + r.stderr


# -- optional tools: the absent path runs for real (issue 22) ---------------------------------
def test_fe_calculix_rule_succeeds_without_ccx(tmp_path, hide_programs):
    """The skip path wrote no directory("results/calculix") and every run without CalculiX
    stopped with MissingOutputException. Run here with ccx hidden from PATH (CI has ccx), on
    stand-ins for the beam runs it would compare with (the skip path reads none of them)."""
    clone = fresh_clone(tmp_path)
    for case in CONFIG["calculix"]["cases"]:
        (clone / "results" / "fe" / "beam" / f"{CONFIG['calculix']['family']}-{case}").mkdir(parents=True)
    r = subprocess.run([*SNAKEMAKE, "--cores", "1", "paper_figures/calculix.md", "--allowed-rules", "fe_calculix",
                        "code_fingerprint", "numba_warmup"],
                       cwd=clone, capture_output=True, text=True, timeout=300, env=hide_programs("ccx"))
    assert r.returncode == 0, r.stdout + r.stderr
    from roughcontact.paper import calculix, verify

    assert (clone / "results" / "calculix" / "SKIPPED.txt").read_text().startswith("skipped: ccx not installed")
    assert calculix.skipped_line() in (clone / "paper_figures" / "calculix.md").read_text()
    assert verify.checks_from_csv((clone / "results" / "verify" / "calculix.checks.csv").read_text()) == []


def test_ccx_friction_rule_succeeds_without_the_build(tmp_path, monkeypatch):
    """Without the ccx built with the law (an empty cache: ROUGHCONTACT_CCX_CACHE) the scene
    writes every output, no checks, the one line of why; it does not build (minutes)."""
    import os

    clone = fresh_clone(tmp_path)
    env = {**os.environ, "ROUGHCONTACT_CCX_CACHE": str(tmp_path / "no-cache")}
    r = subprocess.run([*SNAKEMAKE, "--cores", "1", "paper_figures/ccx_friction.md", "--allowed-rules", "ccx_friction",
                        "code_fingerprint"], cwd=clone, capture_output=True, text=True, timeout=300, env=env)
    assert r.returncode == 0, r.stdout + r.stderr
    from roughcontact.paper import ccx_friction, verify

    line = (clone / "results" / "ccx_friction" / "SKIPPED.txt").read_text()
    assert line.startswith("skipped: ccx-with-the-law not installed") and "make ccx-build" in line
    assert not (tmp_path / "no-cache").exists()  # nothing was built
    assert "skipped: ccx-with-the-law not installed" in (clone / "paper_figures" / "ccx_friction.md").read_text()
    assert verify.checks_from_csv((clone / "results" / "verify" / "ccx_friction.checks.csv").read_text()) == []
    # and VERIFICATION.md, the gate and the gallery count the scene as skipped
    monkeypatch.setenv("ROUGHCONTACT_CCX_CACHE", str(tmp_path / "no-cache"))
    assert ccx_friction.installed_tools({"expected_checks": {"ccx_friction": {"checks": 12,
                                                                              "requires": ccx_friction.TOOL}}}) == []
