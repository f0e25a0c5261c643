# Helpers shared by the rules: scenes from config, the library sources results depend on,
# and the slice of the configuration recorded as provenance in each result.

import ast
import copy
import hashlib
import os
import sys
from pathlib import Path

REPO = Path(workflow.basedir)
# Shell rules call `python`: the interpreter running Snakemake comes first on PATH (a parameter
# holding sys.executable would bake the venv's absolute path into every job's record).
os.environ["PATH"] = f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}"


def _one_reevaluation_timer():
    """Snakemake 9 (job_scheduler._schedule_reevalutation, under the default
    --max-jobs-per-timespan 100/1s): every pass of the scheduling loop that leaves ready jobs
    waiting starts one more 1-s timer that wakes the loop again, and every finished job adds a
    pass, so the timers multiply while jobs queue for the cores: over 15 000 timer threads in one
    reproduction, whose passes (input sizes, job selection: with the default ILP scheduler a pulp
    model each) made the Snakemake process's own CPU 291 s of the run's ~890 s (benchmarks/workflow_profile.py, 2 cores; cf. snakemake/snakemake#3804).
    One pending timer wakes the loop just as well: a timer is started only when none is pending
    (a daemon thread: an exit never waits for it). Left alone where the installed Snakemake has
    no such method (another version, its own scheduler)."""
    import threading

    try:
        from snakemake.scheduling.job_scheduler import JobScheduler
    except ImportError:
        return
    original = getattr(JobScheduler, "_schedule_reevalutation", None)
    if original is None or getattr(original, "_roughcontact_single", False):
        return

    def schedule_reevaluation(self, delay):
        pending = getattr(self, "_roughcontact_timer", None)
        if pending is not None and pending.is_alive():
            return
        timer = threading.Timer(delay, lambda: self._open_jobs.release())
        timer.daemon = True
        self._roughcontact_timer = timer
        timer.start()

    schedule_reevaluation._roughcontact_single = True
    JobScheduler._schedule_reevalutation = schedule_reevaluation


_one_reevaluation_timer()
SCENES = config["scenes"]
REFERENCE_DPS = int(config["reference_dps"])

TABLE_SCENES = [name for name, sc in SCENES.items() if sc["kind"] == "table"]
MINDLIN_SCENES = [name for name, sc in SCENES.items() if sc["kind"] == "mindlin_table"]
PRINTED_TABLES = TABLE_SCENES + MINDLIN_SCENES  # scenes compared cell by cell with a printed table
BEARING_SCENES = [name for name, sc in SCENES.items() if sc["kind"] == "bearing_ratio"]
HERTZ_SCENES = [name for name, sc in SCENES.items() if sc["kind"] == "hertz_factors"]
# elasto-plastic scenes that compute their own curves (a scene with `uses:` draws another's)
EP_KINDS = ("elastoplastic_psi", "stiffness_pressure", "stiffness_sensitivity")
EP_SCENES = [name for name, sc in SCENES.items() if sc["kind"] in EP_KINDS and "uses" not in sc]
FRICTION_KINDS = ("friction_slip_rule", "friction_hardening", "friction_cases")
FRICTION_SCENES = [name for name, sc in SCENES.items() if sc["kind"] in FRICTION_KINDS]
FIGURE_SCENES = (BEARING_SCENES + HERTZ_SCENES + [n for n, sc in SCENES.items() if sc["kind"] in EP_KINDS]
                 + FRICTION_SCENES)
NUMERICS_SCENES = [name for name, sc in SCENES.items() if sc["kind"] == "elastoplastic_numerics"]
MODEL_NAMES = list(config["models"])
SWEEPS = config.get("sweeps", {})


def curves_of(scene):
    """The scene whose curves a figure scene draws: its own, or those it `uses`."""
    return SCENES[scene].get("uses", scene)


def _alternation(names):
    """A regex matching exactly one of ``names`` (a never-matching one if empty)."""
    return "|".join(names) if names else "(?!x)x"


# Library modules whose code determines the numbers: editing one re-runs the computations
# that use it. The layers below the FE engine, plus the scene definitions of paper/; the
# reports (paper/claims, verify, report, plots; io) are the inputs of the report rules only, so
# restyling a figure or rewording a claim never re-runs the mpmath reference.
#
# A rule does not take the .py files themselves as inputs but their CODE FINGERPRINTS
# (results/code/<module>.<digest>.sha256, named by the SHA-256 of the module's syntax tree
# without comments and docstrings): a comment, a docstring or a reformatting keeps the name and
# re-plans no job; a code change gives a new name, which the jobs that use the module see as a
# changed set of inputs. The files are written by the rule code_fingerprint, never while the
# workflow is parsed, so a dry run (-n) writes nothing; they travel with a copied results tree.
# All paths are relative to the workflow directory (the working directory of every rule), so a
# copied checkout plans nothing new.
LIB = REPO / "src" / "roughcontact"
FINGERPRINTS = Path("results") / "code"


#: {SHA-256 of a file's bytes: its code digest}: the rules name the same modules ~200 times, and
#: parsing and dumping a syntax tree costs milliseconds, so each text is digested once per parse
_CODE_DIGESTS = {}


def _code_digest(path):
    """SHA-256 of the module's syntax tree, docstrings removed (comments never reach it)."""
    text = Path(path).read_bytes()
    key = hashlib.sha256(text).hexdigest()
    if key not in _CODE_DIGESTS:
        _CODE_DIGESTS[key] = _syntax_digest(text.decode("utf-8"))
    return _CODE_DIGESTS[key]


def _syntax_digest(text):
    tree = ast.parse(text)
    for node in ast.walk(tree):
        body = getattr(node, "body", None)
        if (isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)) and body
                and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant)
                and isinstance(body[0].value.value, str)):
            node.body = body[1:] or [ast.Pass()]
    return hashlib.sha256(ast.dump(tree, include_attributes=False).encode()).hexdigest()


#: {fingerprint file name: the source file it stands for (relative to the workflow directory)}
FINGERPRINTED = {}


def code_fingerprint(path):
    """The fingerprint file of one source file (relative to the workflow directory): its name
    carries the code's digest; rule code_fingerprint writes it. Nothing is written here."""
    rel = Path(path).resolve().relative_to(REPO)
    name = f"{str(rel).replace('/', '__')}.{_code_digest(REPO / rel)[:16]}.sha256"
    FINGERPRINTED[name] = rel
    return str(FINGERPRINTS / name)


def library_sources(*parts):
    """The code fingerprints of the .py files of the named packages (folders) and modules of
    src/roughcontact."""
    out = []
    for part in parts:
        path = LIB / part
        out += sorted(path.rglob("*.py")) if path.is_dir() else [path]
    return [code_fingerprint(p) for p in out]


PHYSICS_SOURCES = library_sources(
    "validation.py", "statistics", "asperity", "integrals", "contact", "interface", "paper/scenes.py"
)
#: stamp of the numba_warmup job: the rules that call the numba kernels take it as input, so
#: that a cold cache is compiled once, not once per parallel job (docs/performance.md).
KERNELS_WARM = "results/numba/warm.stamp"
REPORT_SOURCES = library_sources(
    "paper/claims.py", "paper/verify.py", "paper/report.py", "paper/plots.py", "plots/style.py", "io.py",
    "files.py",
)


def scene_targets():
    """The user-facing files of every scene: tables (md, csv) and figures (png, csv)."""
    out = []
    for name in PRINTED_TABLES:
        out += [f"paper_figures/{name}.md", f"paper_figures/{name}.csv"]
    for name in FIGURE_SCENES:
        out += [f"paper_figures/{name}.png", f"paper_figures/{name}.csv"]
    out += [f"paper_figures/{name}.csv" for name in NUMERICS_SCENES]
    return out


def scene_checks():
    """The per-scene verification rows collected by VERIFICATION.md."""
    return [f"results/verify/{name}.checks.csv" for name in PRINTED_TABLES + FIGURE_SCENES + NUMERICS_SCENES]


def table_columns(scene):
    """{column name: {paper_column, label, ...}} of a printed-table scene: its model levels
    (Tables 1-2) or its own columns (Table 3)."""
    sc = SCENES[scene]
    if sc["kind"] == "mindlin_table":
        return dict(sc["columns"])
    return {m: config["models"][m] for m in sc["models"]}


def surface_of(name):
    return dict(config["surfaces"][name])


def contact_job(scene, model, method, dps=None):
    """Everything one contact computation needs (and records as provenance): one table scene,
    one model level, one integrator. Only the scene's quantities are kept in the result."""
    sc = SCENES[scene]
    m = config["models"][model]
    job = {
        "scene": scene,
        "model_name": model,
        "surface_name": sc["surface"],
        "surface": surface_of(sc["surface"]),
        "E_star": float(sc["E_star"]),
        "s": [float(x) for x in sc["s"]],
        "quantities": list(sc["quantities"]),
        "level": m["level"],
        "model": "gw" if m["level"] == "gw" else "bgk",
        "hertz": m["hertz"],
        "method": method,
        "units": dict(config["units"]),
    }
    if method == "reference":
        job["dps"] = int(dps)  # the reference has no preset: its precision is dps
    else:
        job["accuracy"] = sc["accuracy"]["production"]
    return job


# Keys of a scene that only affect reports, never computed numbers: editing them must not
# re-run a computation (Snakemake's params trigger), least of all the mpmath reference.
REPORT_ONLY_KEYS = {"title", "tolerances", "claims", "figure_closure", "pressure_range"}


def compute_config(scene):
    """The part of a scene's configuration that determines its computed numbers."""
    return {k: copy.deepcopy(v) for k, v in SCENES[scene].items() if k not in REPORT_ONLY_KEYS}


def scene_provenance(scene):
    """The configuration slice a figure scene's curves depend on (stored as config_json)."""
    sc = compute_config(scene)
    surfaces = [c["surface"] for c in sc.get("curves", [])] + ([sc["surface"]] if "surface" in sc else [])
    return {
        "scene": scene,
        "scene_config": sc,
        "surfaces": {name: surface_of(name) for name in surfaces},
        "units": dict(config["units"]),
    }


def sweep_parts(name):
    """The part files of a sweep: one Snakemake job per part (roughcontact.contact.sweep.split)."""
    from roughcontact.contact.sweep import spec_from_config, split

    cfg = SWEEPS[name]
    n = len(split(spec_from_config(cfg, config["units"]), cfg["split"]["axis"], cfg["split"]["jobs"]))
    return [f"results/sweeps/{name}/part-{i}.nc" for i in range(n)]


# ---------------------------------------------------------------------------------------------
# finite elements (config: fe)
# ---------------------------------------------------------------------------------------------
#: the FE engine and what it stands on (the runs' recipes: roughcontact/examples)
FE_SOURCES = PHYSICS_SOURCES + library_sources("fe", "examples")
FE_REPORT_SOURCES = REPORT_SOURCES + library_sources("paper/fe_beam.py")
FE_BEAM = config["fe"]["beam"]

from roughcontact.examples import runs as fe_runs  # noqa: E402  (typed run specs from the configuration)

#: {run name: BeamRun}: the main runs of Table 4 (every family and case), then the study's
FE_BEAM_RUNS = fe_runs.beam_runs(FE_BEAM)
FE_BEAM_MAIN = [name for name in FE_BEAM_RUNS if name.endswith("-main")]
#: one job per (family, case) solves the case's runs (its main run and study variants)
FE_BEAM_GROUPS = fe_runs.beam_groups(FE_BEAM_RUNS)


def fe_beam_group(name):
    """The job (family-case) of a run name family-case-variant."""
    return "-".join(name.split("-", 2)[:2])


def fe_beam_dirs(names):
    """The job directories holding the runs ``names``."""
    return sorted({f"results/fe/beam/{fe_beam_group(n)}" for n in names})


def fe_beam_paths(names):
    """{run name: its netCDF file}."""
    return {n: f"results/fe/beam/{fe_beam_group(n)}/{n.split('-', 2)[2]}.nc" for n in names}


def fe_targets():
    """The user-facing files of the FE scenes."""
    return [f"paper_figures/{name}" for name in ("table4.md", "table4.csv", "fig13.png", "fig13.csv",
                                                 "fe_beam_study.md", "fe_beam_study.csv", "fig10.png",
                                                 "table5.md", "table5.csv", "fe_punch_readings.md",
                                                 "fe_punch_readings.csv", "fig14.png", "fig15.png",
                                                 "fig18.png", "fig18.csv", "fig19.png", "fig19.csv",
                                                 "fe_benchmark.md", "fe_export.png", "calculix.md",
                                                 "ccx_friction.md")]


FE_TITLES = {
    "table4": "Table 4: interface deflections of the beam on a rigid base (example 9.1)",
    "fe_beam_study": "Example 9.1: tangential restraint, E* and mesh convergence",
    "table5": "Table 5 and section 9.2: the punch with orthotropic hardening friction (example 9.2)",
    "calculix": "The exported pressure-overclosure table in CalculiX (optional tool ccx; issue 14)",
    "ccx_friction": "The full law, friction included, inside CalculiX against the engine (optional: a ccx built with the law; issue 30)",
    "fe_beam_anchor": "Example 9.1 against a 2D plane-stress solution by a separate code (engine-free anchor)",
    "fe_punch_anchor": "Example 9.2 against its equilibrium, friction limit, dissipation and bound (engine-free anchor)",
}


def drawing_targets():
    """The element drawings and Figs 1-2 (workflow/rules/drawings.smk)."""
    figs = ("fig11", "fig12", "fig16", "fig17", *config.get("geometry_figures", {}))
    return [f"paper_figures/{fig}.{ext}" for fig in figs for ext in ("png", "csv")]


def fe_checks():
    return [f"results/verify/{name}.checks.csv" for name in ("table4", "fe_beam_study", "table5", "calculix",
                                                             "ccx_friction", "fe_beam_anchor", "fe_punch_anchor")]


FE_PUNCH = config["fe"]["punch"]
#: {job: {run name: PunchRun}}; each frictional run names the frictionless run of its bound
FE_PUNCH_GROUPS = fe_runs.punch_groups(FE_PUNCH)
FE_PUNCH_RUNS = {name: run for group in FE_PUNCH_GROUPS.values() for name, run in group.items()}


def fe_punch_paths(names):
    """{run name: its netCDF file} (results/fe/punch/<job>/<case>.nc)."""
    out = {}
    for group, runs in FE_PUNCH_GROUPS.items():
        for name in runs:
            if name in names:
                out[name] = f"results/fe/punch/{group}/{name[len(group) + 1:]}.nc"
    return out


rule code_fingerprint:
    """The code fingerprint of one source file (see code_fingerprint): written once per version
    of its code, by a job, so that a dry run writes nothing; the fingerprints of the file's
    earlier versions are removed (no job reads them any more). A shell job: a `run:` job would
    start a whole Snakemake process (~15 s) per file."""
    output:
        f"{FINGERPRINTS}/{{fingerprint}}",
    log:
        "logs/code/{fingerprint}.log",
    wildcard_constraints:
        fingerprint=r"[^/]+\.py\.[0-9a-f]{16}\.sha256",
    params:
        source=lambda w: str(FINGERPRINTED[w.fingerprint]),
        digest=lambda w: _code_digest(REPO / FINGERPRINTED[w.fingerprint]),
        earlier=lambda w: w.fingerprint[: -len("0123456789abcdef.sha256")] + "????????????????.sha256",
    localrule: True
    # before everything (milliseconds each): numba_warmup, which most jobs wait for, needs them
    priority: 100
    shell:
        "find {FINGERPRINTS} -maxdepth 1 -name '{params.earlier}' ! -name '{wildcards.fingerprint}' -delete"
        " && echo {params.digest} > {output} && echo '{params.source}: {params.digest}' > {log}"


onstart:
    # a run resumed after a hard kill: the killed run's jobs, which outlive a Snakemake killed with
    # SIGKILL and go on writing, are stopped (one line each); then no job of this directory is
    # writing (the lock keeps other runs out) and their half-written temporaries go; dry runs do
    # not call onstart
    from roughcontact.files import remove_partial_files
    from roughcontact.orphan_jobs import stop_orphan_jobs

    stop_orphan_jobs(REPO, report=lambda line: print(line, file=sys.stderr))
    for _part in remove_partial_files("results", "paper_figures", "logs"):
        print(f"removed the temporary of a killed job: {_part}", file=sys.stderr)
