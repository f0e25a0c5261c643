"""The workflow's runs of section 9 as typed run specs, from the configuration (config.yaml ``fe``).

:func:`beam_runs` gives every run of example 9.1 (:class:`~.beam.BeamRun`): Table 4's main runs
(every element family and case), then the study's variants; :func:`punch_groups` every run of
example 9.2 (:class:`~.punch.PunchRun`) grouped by job: per element family and reading cases
a, b, c and the frictionless problem of their bound, and the sensitivity's variants. The names
are those of the result files: "<family>-<case>-<variant>" (beam), "<family>-<reading>-<case>"
(punch). workflow/rules/common.smk, the tests and the CLI build their runs here or from the
run classes, never as dicts.
"""

from __future__ import annotations

from typing import Any, Mapping

from .beam import BeamRun, BeamSpec
from .punch import PunchRun, PunchSpec
from .punch_geometry import PunchGeometry

__all__ = ["beam_run", "beam_runs", "beam_groups", "punch_run", "punch_groups", "SAME_FRICTIONLESS"]


def beam_run(cfg: Mapping[str, Any], family: str, case: str) -> BeamRun:
    """The main run of Table 4 case ``case`` with ``family`` elements (cfg: config.yaml fe.beam)."""
    c = cfg["cases"][case]
    return BeamRun(spec=BeamSpec(elements=family, **cfg["spec"]), m00=c["m00"], law=c["law"],
                   psi=cfg["psi"] if c["law"] == "elastoplastic" else None, E_star=cfg["E_star"],
                   tangential=cfg["tangential"], surface=tuple(cfg["surface"].items()), case=case)


def beam_runs(cfg: Mapping[str, Any]) -> dict[str, BeamRun]:
    """{run name: run}: the main runs of Table 4 (every family and case), then the study's
    (tangential restraints and the caption's E* on the elastic rows, the printed Y on the
    elasto-plastic ones, meshes on the first elastic case)."""
    runs = {f"{f}-{case}-main": beam_run(cfg, f, case) for f in cfg["families"] for case in cfg["cases"]}
    study = cfg["study"]
    fam = study["variants_family"]
    elastic = [case for case, c in cfg["cases"].items() if c["law"] == "elastic"]
    for case in elastic:
        base = beam_run(cfg, fam, case)
        for t in study["tangential"]:
            name = t["tangential"] + (f"-{t['mu']:g}" if "mu" in t else "")
            runs[f"{fam}-{case}-{name}"] = base.with_(tangential=t["tangential"], mu=t.get("mu"))
        runs[f"{fam}-{case}-estar-caption"] = base.with_(E_star=study["E_star_caption"])
    for case, c in cfg["cases"].items():
        if c["law"] == "elastoplastic":
            runs[f"{fam}-{case}-printed-Y"] = beam_run(cfg, fam, case).with_(psi=None, Y=study["printed_Y"])
    for f in cfg["families"]:
        for nx, nz in study["meshes"]:
            runs[f"{f}-{elastic[0]}-mesh-{nx}x{nz}"] = beam_run(cfg, f, elastic[0]).with_(spec={"n_x": nx, "n_z": nz})
    return runs


def beam_groups(runs: Mapping[str, BeamRun]) -> dict[str, dict[str, BeamRun]]:
    """{job "<family>-<case>": {variant: run}}: one job per case and family solves its runs
    (the job's fixed cost — interpreter, imports, normal-law table — paid once per case)."""
    out: dict[str, dict[str, BeamRun]] = {}
    for name, run in runs.items():
        out.setdefault(f"{run.family}-{run.case}", {})[name.split("-", 2)[2]] = run
    return out


#: fields of a reading or variant that leave the frictionless problem unchanged (its bound is
#: then the one of the run's base)
SAME_FRICTIONLESS = {"tangential_form", "increments", "unload_increments"}
_RUN_FIELDS = {"law", "tangential_form", "E_star", "m00"}
_SPEC_FIELDS = {"load", "load_on", "seating_pressure", "increments", "unload_increments", "E", "nu"}


def punch_run(cfg: Mapping[str, Any], family: str, case: str, *overrides: Mapping[str, Any]) -> PunchRun:
    """One run of example 9.2 (cfg: config.yaml fe.punch): its main reading with ``overrides``
    applied in turn (run fields, spec fields and ``geometry``)."""
    main = dict(cfg["main"])
    geometry = {"family": family, **main.pop("geometry", {})}
    fields = {"law": cfg["law"], "tangential_form": main.pop("tangential_form", "incremental-end")}
    spec = dict(main)
    for over in overrides:
        unknown = set(over) - _RUN_FIELDS - _SPEC_FIELDS - {"geometry"}
        if unknown:
            raise ValueError(f"punch run: unknown field(s) {sorted(unknown)}")
        geometry.update(over.get("geometry", {}))
        fields.update({k: v for k, v in over.items() if k in _RUN_FIELDS})
        spec.update({k: v for k, v in over.items() if k in _SPEC_FIELDS})
    law = fields.pop("law")
    return PunchRun(case=case, spec=PunchSpec(geometry=PunchGeometry(**geometry), **spec), m00=cfg["m00"], law=law,
                    psi=cfg["psi"] if law == "elastoplastic" else None, surface=tuple(cfg["surface"].items()),
                    **fields)


def _group(cfg, group, family, cases, overrides, inherited_bound=None) -> dict[str, PunchRun]:
    """The runs of one job: ``cases`` of ``family`` with the overrides (the last one is the
    job's own), each naming the frictionless run of its bound: the job's own where the last
    override changes the frictionless problem (or nothing is inherited), else ``inherited_bound``."""
    own = inherited_bound is None or bool(set(overrides[-1]) - SAME_FRICTIONLESS)
    bound = f"{group}-frictionless" if own else inherited_bound
    runs = {f"{group}-{c}": punch_run(cfg, family, c, *overrides).with_(bound=bound) for c in cases}
    if own:
        runs[f"{group}-frictionless"] = punch_run(cfg, family, "frictionless", *overrides)
    return runs


def punch_groups(cfg: Mapping[str, Any]) -> dict[str, dict[str, PunchRun]]:
    """{job: {run name: run}}: per element family and reading, cases a, b, c and the frictionless
    problem (where the reading changes it); the sensitivity's variants (case b, 21-node)."""
    groups = {}
    for fam in cfg["families"]:
        groups[f"{fam}-main"] = _group(cfg, f"{fam}-main", fam, "abc", ({},))
        for reading, over in cfg["readings"].items():
            groups[f"{fam}-{reading}"] = _group(cfg, f"{fam}-{reading}", fam, "abc", (over,), f"{fam}-main-frictionless")
    sens = cfg["sensitivity"]
    base = cfg["readings"][sens["reading"]]
    for variant, over in sens["variants"].items():
        groups[f"quadratic-sens-{variant}"] = _group(cfg, f"quadratic-sens-{variant}", "quadratic", "b", (base, over),
                                                     f"quadratic-{sens['reading']}-frictionless")
    return groups
