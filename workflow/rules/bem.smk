# The statistical model against a deterministic boundary-element solution on the same surfaces
# (issue 21; config: bem; docs/bem.md). Target `bem`, NOT part of `all`. OPTIONAL: it needs the
# extra [bem] (ContactMechanics); without it `snakemake bem` prints one line, SKIP_MESSAGE, and
# computes nothing.
#
# One job per (family, grid, seed) solves the whole load ladder of one realisation and is cached
# by its file results/bem/runs/<family>/n<grid>/seed<seed>.nc: it depends on the BEM code and
# the surface statistics only (not on the contact model), so editing the model re-runs the
# cheap comparison, never the BEM; a resumed run redoes only the missing realisations. The plastic
# runs (config bem: plastic:, a hardness cap from the model's material) are jobs of their own, cached
# likewise by results/bem/plastic/<family>/n<grid>/seed<seed>.nc.

BEM = config["bem"]
BEM_SCALE = str(config.get("bem_scale", BEM["scale"]))
if BEM_SCALE not in BEM["scales"]:
    raise ValueError(f"bem_scale {BEM_SCALE!r} is not one of bem.scales: {', '.join(BEM['scales'])}")
BEM_GRIDS = {int(n): g for n, g in BEM["scales"][BEM_SCALE].items()}
BEM_SOURCES = library_sources("validation.py", "statistics/surface.py", "bem/surfaces.py", "bem/solver.py")
BEM_CHECK_SOURCES = BEM_SOURCES + library_sources("asperity", "bem/checks.py")
BEM_REPORT_SOURCES = (PHYSICS_SOURCES + REPORT_SOURCES
                      + library_sources("bem/compare.py", "paper/bem.py", "paper/bem_law.py", "paper/bem_plastic.py",
                                        "statistics/summits.py"))
BEM_PLASTIC = BEM["plastic"]
BEM_PLASTIC_GRIDS = {int(n): int(seeds) for n, seeds in BEM_PLASTIC["scales"].get(BEM_SCALE, {}).items()}
BEM_PLASTIC_SOURCES = BEM_SOURCES + library_sources("asperity", "bem/compare.py")  # compare: the material of a psi


def bem_available():
    """Whether the extra [bem] imports: asked only when a job of the target bem is planned
    (importing ContactMechanics costs ~1 s, which every other invocation would pay)."""
    from roughcontact.bem.solver import available

    return available()


def bem_runs():
    """results/bem/runs/<family>/n<grid>/seed<seed>.nc of the current scale."""
    return [f"results/bem/runs/{fam}/n{n}/seed{seed}.nc"
            for fam in BEM["families"] for n, g in BEM_GRIDS.items() for seed in range(g["seeds"])]


def bem_plastic_runs():
    """results/bem/plastic/<family>/n<grid>/seed<seed>.nc of the current scale (bem.plastic.scales)."""
    return [f"results/bem/plastic/{fam}/n{n}/seed{seed}.nc"
            for fam in BEM["families"] for n, seeds in BEM_PLASTIC_GRIDS.items() for seed in range(seeds)]


def bem_max_pressure(grid, family):
    """The largest W/A0 solved on a grid: one number, or one per family."""
    mp = grid["max_pressure"]
    return float(mp[family]) if isinstance(mp, dict) else float(mp)


def bem_run_job(family, n, seed):
    """What one BEM job computes (and records as provenance)."""
    g = BEM_GRIDS[int(n)]
    return {"family": family, "moments": dict(BEM["families"][family]), "n": int(n), "seed": int(seed),
            "hurst": BEM["hurst"], "k_high": BEM["k_high"], "E_star": BEM["E_star"],
            "pressures": [p for p in BEM["pressures"] if p <= bem_max_pressure(g, family)],
            "solver": dict(BEM["solver"]), "units": dict(config["units"])}


def bem_plastic_job(family, n, seed):
    """What one plastic BEM job computes (and records as provenance)."""
    return {"family": family, "moments": dict(BEM["families"][family]), "n": int(n), "seed": int(seed),
            "hurst": BEM["hurst"], "k_high": BEM["k_high"], "E_star": BEM["E_star"], "psi": list(BEM_PLASTIC["psi"]),
            "yield_coefficient": BEM_PLASTIC["yield_coefficient"], "pressures": list(BEM_PLASTIC["pressures"]),
            "solver": dict(BEM["solver"]), "units": dict(config["units"])}


BEM_OUTPUTS = ["results/bem/summary.csv", "results/bem/summary.nc", "results/bem/summits.csv", "paper_figures/bem.png",
               "paper_figures/bem.md", "results/verify/bem.checks.csv", "results/bem/law.csv", "results/bem/law.nc",
               "results/bem/plastic.csv", "results/bem/plastic.nc"]


rule bem:
    """The BEM comparison: summary, figure, the "where the model holds" report and the BEM's
    closed-form checks (or one line saying why it was skipped)."""
    input:
        lambda w: BEM_OUTPUTS if bem_available() else [],
    localrule: True
    params:
        available=lambda w: bem_available(),
    run:
        from roughcontact.bem.solver import SKIP_MESSAGE

        print(f"bem ({BEM_SCALE}): results/bem/summary.csv, paper_figures/bem.md" if params.available
              else SKIP_MESSAGE, file=sys.stderr)


rule bem_run:
    """One realisation (family, grid, seed): its map and the BEM solution at every pressure of
    the ladder up to the grid's max_pressure."""
    input:
        code=BEM_SOURCES,
    output:
        "results/bem/runs/{family}/n{n}/seed{seed}.nc",
    log:
        "logs/bem/{family}/n{n}/seed{seed}.log",
    benchmark:
        "results/benchmarks/bem/{family}/n{n}/seed{seed}.tsv"
    wildcard_constraints:
        family=_alternation(list(BEM["families"])),
        n=r"\d+",
        seed=r"\d+",
    params:
        job=lambda w: bem_run_job(w.family, w.n, w.seed),
    threads: 1
    resources:
        mem_mb=lambda w: 400 + int(w.n) ** 2 * 8 * 40 // 2**20,
    script:
        "../scripts/bem_run.py"


rule bem_plastic_run:
    """One realisation (family, grid, seed) with the hardness cap c_h H of every plasticity
    index of the config's bem: plastic:, at the plastic ladder's pressures (the elastic runs are untouched)."""
    input:
        code=BEM_PLASTIC_SOURCES,
    output:
        "results/bem/plastic/{family}/n{n}/seed{seed}.nc",
    log:
        "logs/bem/plastic/{family}/n{n}/seed{seed}.log",
    benchmark:
        "results/benchmarks/bem/plastic/{family}/n{n}/seed{seed}.tsv"
    wildcard_constraints:
        family=_alternation(list(BEM["families"])),
        n=r"\d+",
        seed=r"\d+",
    params:
        job=lambda w: bem_plastic_job(w.family, w.n, w.seed),
    threads: 1
    resources:
        mem_mb=lambda w: 400 + int(w.n) ** 2 * 8 * 40 // 2**20,
    script:
        "../scripts/bem_plastic_run.py"


rule bem_checks:
    """The BEM on closed forms (Hertz sphere and elliptic paraboloid, Westergaard's wave) on the
    grids of this scale and the families' pixels."""
    input:
        code=BEM_CHECK_SOURCES,
    output:
        "results/bem/checks.csv",
    log:
        "logs/bem/checks.log",
    benchmark:
        "results/benchmarks/bem/checks.tsv"
    params:
        grids=sorted(BEM_GRIDS),
        families={fam: dict(m) for fam, m in BEM["families"].items()},
        hurst=BEM["hurst"],
        k_high=BEM["k_high"],
        solver=dict(BEM["solver"]),
    threads: 1
    script:
        "../scripts/bem_checks.py"


rule bem_report:
    """summary.csv/.nc (A_BEM/A_BGK, separations, κ, stiffness per family, grid and load), the
    figure, the measured summit statistics, law.csv/.nc (the law against the converged BEM),
    plastic.csv/.nc (the elasto-plastic model against the capped BEM), and paper_figures/bem.md
    with "Where the model holds", "Where the law holds" and "Plastic contact"."""
    input:
        runs=bem_runs(),
        plastic=bem_plastic_runs(),
        checks="results/bem/checks.csv",
        code=BEM_REPORT_SOURCES,
    output:
        csv="results/bem/summary.csv",
        nc="results/bem/summary.nc",
        summits="results/bem/summits.csv",
        png="paper_figures/bem.png",
        md="paper_figures/bem.md",
        checks="results/verify/bem.checks.csv",
        law_csv="results/bem/law.csv",
        law_nc="results/bem/law.nc",
        plastic_csv="results/bem/plastic.csv",
        plastic_nc="results/bem/plastic.nc",
    log:
        "logs/bem/report.log",
    params:
        cfg={k: v for k, v in BEM.items() if k not in ("scales", "scale")},
        scale=BEM_SCALE,
        grids={n: dict(g) for n, g in BEM_GRIDS.items()},
        units=dict(config["units"]),
        benchmarks="results/benchmarks/bem",
    threads: 1
    script:
        "../scripts/bem_report.py"
