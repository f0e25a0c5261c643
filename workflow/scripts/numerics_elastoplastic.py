"""Elasto-plastic production vs slow twin at the scene's check points (rule
numerics_elastoplastic); netCDF with provenance.

The twin's values are deterministic (scipy cubature at a fixed rtol), so they are taken from the
committed seed of the benchmark references (benchmarks/data/references.json, via
benchmarks/references.py) when the record was computed by the same twin code — the seed's
fingerprint hashes every module the twin runs through — and computed otherwise (44–64 s per
point). Production is always computed. The netCDF's ``reference_source`` says which.
Refresh the seed after a change to the twin's code:

    .venv/bin/python workflow/scripts/numerics_elastoplastic.py --update-seed
"""

import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "benchmarks"))

import references as refs  # noqa: E402

from roughcontact import io  # noqa: E402
from roughcontact.integrals.reference_elastoplastic import reference_integrals  # noqa: E402
from roughcontact.paper import scenes  # noqa: E402


def twin_key(surface, s, material, hertz, rtol) -> str:
    """Everything the twin's value depends on besides its code."""
    return (f"ep_numerics_twin|{refs._surface_key(surface)}|s={float(s)!r}|{hertz}|rtol={float(rtol)!r}"
            f"|{material!r}")


def seeded_twin(cache: refs.ReferenceCache):
    """reference_integrals through ``cache`` (seed first, else computed)."""
    def twin(surface, s, material, *, hertz, rtol):
        key = twin_key(surface, s, material, hertz, rtol)
        return cache.get(key, lambda: [float(v) for v in reference_integrals(surface, s, material, hertz=hertz,
                                                                               rtol=rtol)])
    return twin


def run(scene, cfg, surfaces, output, log, seed=refs.SEED, units=None):
    with io.log_to(log) as logger, tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        cache = refs.ReferenceCache(Path(tmp) / "twin.json", seed=seed)
        ds = scenes.elastoplastic_numerics(cfg["points"], surfaces, cfg["E_star"], production=cfg["production"],
                                           reference_rtol=cfg["reference_rtol"], units=units,
                                           reference=seeded_twin(cache))
        source = (f"seed {refs.SEED.relative_to(REPO)} (computed {', '.join(sorted(set(cache.seeded.values())))} "
                  f"by the same twin code, fingerprint {cache.fingerprint})" if cache.seeded else "computed")
        logger.info("%s: %d points in %.1f s; twin values %s", scene, ds.sizes["point"], time.perf_counter() - t0,
                    source)
        ds.attrs.update(scene=scene, reference_source=source)
        io.write_netcdf(ds, output, config={"scene": scene, "scene_config": cfg, "surfaces": surfaces},
                        settings={"production": cfg["production"], "reference_rtol": cfg["reference_rtol"]})


def twin_calls(config: dict):
    """(surface, s, material, hertz, rtol) of the twin at every ep_numerics point of a parsed
    config/config.yaml, as scenes.elastoplastic_numerics builds them."""
    from roughcontact import SpectralMoments
    from roughcontact.asperity import paper_K_v
    from roughcontact.contact import resolve_material

    cfg = config["scenes"]["ep_numerics"]
    for pt in cfg["points"]:
        surface = SpectralMoments(**config["surfaces"][pt["surface"]])
        nu = pt.get("paper_K_v_poisson")
        mat = resolve_material(surface, E_star=cfg["E_star"], psi=pt["psi"],
                               K_v=None if nu is None else float(paper_K_v(nu)))
        yield surface, pt["s"], mat, pt["hertz"], cfg["reference_rtol"]


def update_seed() -> int:
    """Compute the twin at every ep_numerics point of config/config.yaml and merge the values
    into the seed (ReferenceCache.update_seed)."""
    import yaml

    config = yaml.safe_load((REPO / "config" / "config.yaml").read_text())
    with tempfile.TemporaryDirectory() as tmp:
        cache = refs.ReferenceCache(Path(tmp) / "twin.json", seed=refs.SEED)
        twin = seeded_twin(cache)
        for surface, s, mat, hertz, rtol in twin_calls(config):
            twin(surface, s, mat, hertz=hertz, rtol=rtol)
            print(f"s = {s}, {mat}: done", flush=True)
        return cache.update_seed()


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.scene, sm.params.scene_config, sm.params.surfaces, sm.output[0], sm.log[0], units=sm.config["units"])
elif __name__ == "__main__" and sys.argv[1:] == ["--update-seed"]:
    print(f"{update_seed()} twin values written to {refs.SEED}")
