"""Material points of the interface friction law (rule curves_friction): call roughcontact.paper.scenes
with what the scene declares, write netCDF with provenance."""

import time

from roughcontact import io
from roughcontact.paper import scenes


def run(scene, cfg, surface, units, provenance, output, log):
    with io.log_to(log) as logger:
        t0 = time.perf_counter()
        if cfg["kind"] == "friction_slip_rule":
            ds = scenes.slip_rule_geometry({k: tuple(v) for k, v in cfg["sets"].items()}, cfg["k"],
                                           directions=cfg["directions"])
        elif cfg["kind"] == "friction_hardening":
            ds = scenes.hardening_path(cfg["mu_m"], cfg["mu_o"], cfg["n"], k_T=cfg["k_T"], p_N=cfg["p_N"],
                                       slip=cfg["slip"], steps=cfg["steps"], length_unit=units["length"])
        elif cfg["kind"] == "friction_cases":
            ds = scenes.fig18_scene(surface, cfg, units)
        else:
            raise ValueError(f"{scene}: not a friction scene kind: {cfg['kind']!r}")
        logger.info("%s: %s in %.2f s", scene, dict(ds.sizes), time.perf_counter() - t0)
        ds.attrs["scene"] = scene
        io.write_netcdf(ds, output, config=provenance, settings={"method": "friction.update"})


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.scene, sm.params.scene_config, sm.params.surface, sm.params.units, sm.params.provenance,
        sm.output[0], sm.log[0])
