# Anchors of the gate for what a 5 % scale of a finished run left green (issue 29;
# roughcontact.paper.gate_anchors, config gate_anchors): the elasto-plastic curves and the sweeps
# against the slow twins at sampled points (scene curve_anchors), and every published CSV against
# the files it was written from (scene published_csv).

from roughcontact.paper import gate_anchors as _gate_anchors

GATE_ANCHORS = config["gate_anchors"]
#: {curve file name: (its path, the twin points)}: elasto-plastic scenes and sweeps with samples
CURVE_SOURCES = {}
for _name, _samples in GATE_ANCHORS["curves"]["samples"].items():
    if _name in SWEEPS:
        CURVE_SOURCES[_name] = (f"results/sweeps/{_name}.nc",
                                _gate_anchors.sample_points("sweep", _name, SWEEPS[_name], _samples))
    elif _name in EP_SCENES:
        CURVE_SOURCES[_name] = (f"results/curves/{_name}.nc",
                                _gate_anchors.sample_points(SCENES[_name]["kind"], _name, SCENES[_name], _samples,
                                                            config["surfaces"]))
    else:
        raise ValueError(f"gate_anchors.curves.samples.{_name}: not an elasto-plastic scene computing its own "
                         f"curves ({', '.join(EP_SCENES)}) nor a sweep ({', '.join(SWEEPS)})")
#: the twin's code: the reference integrals and what they stand on (not the production kernels)
TWIN_SOURCES = library_sources("validation.py", "statistics", "asperity", "integrals/reference.py",
                               "integrals/reference_functions.py", "integrals/reference_elastoplastic.py",
                               "integrals/polar.py", "integrals/rules.py", "contact/closures.py",
                               "paper/gate_anchors.py")
GATE_ANCHOR_SOURCES = REPORT_SOURCES + library_sources("paper/gate_anchors.py")


rule curve_twin:
    """The slow twins at the sample points of one curve file, from the configuration alone (never
    from the file they judge): the elasto-plastic twin (scipy cubature) and the elastic mpmath
    integrals."""
    input:
        code=TWIN_SOURCES,
    output:
        "results/anchors/twin/{source}.json",
    log:
        "logs/anchors/twin/{source}.log",
    benchmark:
        "results/benchmarks/anchors/twin/{source}.tsv"
    wildcard_constraints:
        source=_alternation(list(CURVE_SOURCES)),
    params:
        points=lambda w: [p.to_json() for p in CURVE_SOURCES[w.source][1]],
        twin_rtol=float(GATE_ANCHORS["curves"]["twin_rtol"]),
        dps=REFERENCE_DPS,
    threads: 1
    script:
        "../scripts/gate_curve_twin.py"


rule curve_anchors:
    """Every sampled point of the elasto-plastic curves and sweeps against its twin."""
    input:
        twins=[f"results/anchors/twin/{name}.json" for name in CURVE_SOURCES],
        data=[path for path, _ in CURVE_SOURCES.values()],
        expected="config/expected_verdicts.yaml",
        code=GATE_ANCHOR_SOURCES,
    output:
        checks="results/verify/curve_anchors.checks.csv",
    log:
        "logs/anchors/curve_anchors.log",
    params:
        files={name: path for name, (path, _) in CURVE_SOURCES.items()},
        tolerance=GATE_ANCHORS["curves"]["tolerance"],
    localrule: True
    script:
        "../scripts/gate_curve_anchors.py"


def published_csv_jobs():
    """{published CSV: how to re-derive it}: the kind of writer and what it reads (the same
    arguments its rule passes)."""
    jobs = {}
    for name in PRINTED_TABLES:
        sc = SCENES[name]
        jobs[f"paper_figures/{name}.csv"] = {
            "kind": "table", "scene": name, "scene_config": sc, "models": table_columns(name),
            "numerics_rtol": float(config["numerics_rtol"]), "reference_dps": REFERENCE_DPS,
            "production": [f"results/production/{name}/{m}.nc" for m in table_columns(name)],
            "reference": ([f"results/reference/dps{REFERENCE_DPS}/{name}/{m}.nc" for m in sc["models"]]
                          if sc.get("accuracy", {}).get("reference") else []),
            "paper": "config/paper_values.yaml", "expected": "config/expected_verdicts.yaml"}
    for name in FIGURE_SCENES:
        jobs[f"paper_figures/{name}.csv"] = {"kind": "figure", "scene": name, "scene_config": SCENES[name],
                                             "data": f"results/curves/{curves_of(name)}.nc"}
    for name in NUMERICS_SCENES:
        jobs[f"paper_figures/{name}.csv"] = {
            "kind": "numerics", "data": [f"results/numerics/{name}/point-{i}.nc" for i in range(len(SCENES[name]["points"]))]}
    # the FE tables and figures (workflow/rules/fe.smk: the same runs and parameters as their rules)
    paper = {"paper": "config/paper_values.yaml", "expected": "config/expected_verdicts.yaml"}
    jobs["paper_figures/table4.csv"] = {
        "kind": "fe_table4", "runs": {n: FE_BEAM_RUNS[n] for n in FE_BEAM_MAIN}, "paths": fe_beam_paths(FE_BEAM_MAIN),
        "cfg": FE_BEAM, "inputs": fe_beam_dirs(FE_BEAM_MAIN), **paper}
    fig13 = [n for n in FE_BEAM_MAIN if n.startswith("cubic-") and FE_BEAM_RUNS[n].law == "elastic"]
    jobs["paper_figures/fig13.csv"] = {"kind": "fe_fig13", "runs": {n: FE_BEAM_RUNS[n] for n in fig13},
                                       "paths": fe_beam_paths(fig13), "inputs": fe_beam_dirs(fig13),
                                       "paper": "config/paper_values.yaml"}
    jobs["paper_figures/fe_beam_study.csv"] = {"kind": "fe_beam_study", "runs": FE_BEAM_RUNS,
                                               "paths": fe_beam_paths(FE_BEAM_RUNS), "inputs": fe_beam_dirs(FE_BEAM_RUNS)}
    punch = {"runs": FE_PUNCH_RUNS, "paths": fe_punch_paths(FE_PUNCH_RUNS), "cfg": FE_PUNCH,
             "inputs": [f"results/fe/punch/{g}" for g in FE_PUNCH_GROUPS], **paper}
    jobs["paper_figures/table5.csv"] = {"kind": "fe_table5", "part": "table5", **punch}
    jobs["paper_figures/fe_punch_readings.csv"] = {"kind": "fe_table5", "part": "readings", **punch}
    for fig, family in (("fig18", "quadratic"), ("fig19", "cubic")):
        jobs[f"paper_figures/{fig}.csv"] = {
            "kind": "fe_punch_slips", "family": family, "readings": ["main", FE_PUNCH["sensitivity"]["reading"]],
            "paths": fe_punch_paths(FE_PUNCH_RUNS),
            "inputs": [f"results/fe/punch/{g}" for g in FE_PUNCH_GROUPS if not g.split("-", 1)[1].startswith("sens-")]}
    # the exported pressure-overclosure tables of docs/fe-export.md (from the configuration)
    jobs["paper_figures/fe_export.csv"] = {"kind": "fe_export", "cfg": CALCULIX, "beam_cfg": FE_BEAM}
    # the element drawings (the engine's own element definitions) and Figs 1-2 (from the configuration)
    for name, (element, _) in DRAWINGS.items():
        jobs[f"paper_figures/{name}.csv"] = {"kind": "drawing", "element": element}
    for name in GEOMETRY_FIGURES:
        jobs[f"paper_figures/{name}.csv"] = {
            "kind": "geometry", "name": name, "cfg": config["geometry_figures"][name],
            "surface": dict(config["surfaces"][config["geometry_figures"][name]["surface"]]),
            "length": config["units"]["length"]}
    return jobs


PUBLISHED_CSV = published_csv_jobs()


def _published_csv_inputs():
    files = set(PUBLISHED_CSV)
    for job in PUBLISHED_CSV.values():
        for key in ("production", "reference", "data", "inputs"):
            value = job.get(key, [])
            files.update([value] if isinstance(value, str) else value)
        files.update(job[k] for k in ("paper", "expected") if k in job)
    return sorted(files)


rule published_csv:
    """Every published CSV re-derived from the files it was written from, compared cell by cell."""
    input:
        files=_published_csv_inputs(),
        writers=[f"workflow/scripts/{w}.py" for w in ("table", "figure", "numerics_report", "fe_table4", "fe_table5",
                                                      "fe_fig13", "fe_beam_study", "fe_punch_slips", "drawing",
                                                      "geometry_figure", "fe_export_figure")],
        expected="config/expected_verdicts.yaml",
        code=GATE_ANCHOR_SOURCES,
    output:
        checks="results/verify/published_csv.checks.csv",
    log:
        "logs/anchors/published_csv.log",
    params:
        jobs=PUBLISHED_CSV,
        tolerance=GATE_ANCHORS["csv"]["tolerance"],
    localrule: True
    script:
        "../scripts/gate_published_csv.py"


def gate_anchor_checks():
    """The checks files of the gate's anchors (issue 29), collected by VERIFICATION.md."""
    return ["results/verify/curve_anchors.checks.csv", "results/verify/published_csv.checks.csv"]


GATE_ANCHOR_TITLES = {
    "curve_anchors": "The elasto-plastic curves and sweeps at sampled points against the slow twins (issue 29)",
    "published_csv": "Every published CSV against the files it was written from, cell by cell (issue 29)",
}
