# roughcontact: reproduction of Buczkowski & Kleiber (2009): Tables 1-2, Figs 3-8, the prose
# claims of sections 3-7 and 10, and parameter sweeps.
#
#   snakemake -n all                        plan everything (works on a fresh clone)
#   snakemake --cores 2 all                 tables, figures, sweeps, VERIFICATION.md, verdict gate
#   snakemake --cores 2 table1 | ... | fig18_point | sweeps | speed_vs_error | verify | gallery
#
# `make reproduce` / `make verify` add the default profile (workflow/profiles/default:
# rerun-incomplete, so a killed run resumes); CI uses workflow/profiles/ci (lower reference
# precision). Everything a scene computes is declared in config/config.yaml.

from snakemake.utils import min_version, validate

min_version("8.0")


configfile: "config/config.yaml"


validate(config, "config/schema.yaml")


include: "workflow/rules/common.smk"


rule all:
    """Every table, figure and the verification report, then the verdict gate."""
    default_target: True
    localrule: True
    input:
        scene_targets(),
        fe_targets(),
        drawing_targets(),
        [f"results/sweeps/{name}.nc" for name in SWEEPS],
        "paper_figures/VERIFICATION.md",
        "paper_figures/index.html",
        "results/verify/passed",


include: "workflow/rules/contact.smk"
include: "workflow/rules/tables.smk"
include: "workflow/rules/figures.smk"
include: "workflow/rules/sweeps.smk"
include: "workflow/rules/benchmarks.smk"
include: "workflow/rules/fe.smk"
include: "workflow/rules/calculix.smk"
include: "workflow/rules/ccx_friction.smk"
include: "workflow/rules/fe_anchors.smk"
include: "workflow/rules/drawings.smk"
include: "workflow/rules/gate_anchors.smk"
include: "workflow/rules/verify.smk"
include: "workflow/rules/gallery.smk"
include: "workflow/rules/bem.smk"
