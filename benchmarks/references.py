"""Reference values of the speed-against-error benchmark, cached in one JSON file so re-runs do
not recompute them.

* elastic: the mpmath integrator (roughcontact.integrals.reference, dps = 20, ≥ 15 correct digits);
* elasto-plastic: there is no mpmath reference — a 3-D mpmath quadrature of the piecewise
  integrand would need ~1e8 evaluations per point — so the reference is the scipy slow twin
  elastoplastic.reference_integrals at rtol 1e-10. Its limits are checked against mpmath:
  ψ → 0 must give the elastic mpmath integrals (:func:`elastic_limit_check`), ψ → ∞ must give
  A = D_sum ∫ 2 f3 π ω/κ_m p_sum (every contacting summit fully plastic, (61)), the elastic area
  integral with f1 replaced by 2 f3, evaluated here with the mpmath inner integral
  (reference.inner_integral) and mpmath's tanh-sinh in θ (:func:`plastic_limit_area`).

Cache keys hold everything a value depends on (moments, s, Hertz option, dps / rtol,
material); a changed input is a new key, never a stale hit.

Seed: the values are deterministic, so a run from scratch takes them from the committed
``benchmarks/data/references.json`` (written by ``speed_vs_error.py --update-seed``) instead
of recomputing them (~70 s of the quick benchmark, on both cores), but only where the record's
fingerprint — a hash of the source of every module the reference integrators run through
(:data:`FINGERPRINT_SOURCES`) — equals today's: changed reference code recomputes. The report
says how many values came from the seed and when they were computed.
"""

from __future__ import annotations

import hashlib
import json
import time
from pathlib import Path

import mpmath as mp
import numpy as np

from roughcontact import SpectralMoments
from roughcontact.asperity import AsperityMaterial
from roughcontact.contact import elastic_contact, resolve_material
from roughcontact.integrals import reference as R
from roughcontact.integrals import reference_functions as RF
from roughcontact.integrals.polar import ElasticPrefactors, PolarGeometry
from roughcontact.integrals.reference_elastoplastic import reference_integrals

E_STAR = 1.14e5  # N/mm², the paper's tables and figures


def material_for(psi: float, surface: SpectralMoments) -> AsperityMaterial:
    """The closure of Figs 5–8: E* fixed, Y from the prescribed ψ ("yield-from-psi")."""
    return resolve_material(surface, E_star=E_STAR, psi=psi)


def first_values(curves) -> np.ndarray:
    """(A/A0, W/A0, K/A0) at the first separation of a contact result."""
    return np.array([curves.area_fraction[0], curves.pressure[0], curves.stiffness[0]], dtype=float)


def twin_values(surface: SpectralMoments, s: float, material: AsperityMaterial, hertz: str = "exact",
                rtol: float = 1e-10) -> np.ndarray:
    """The scipy twin's totals (A/A0, W/A0, K/A0) followed by its parts (A^e, A^ep, A^p, W^e,
    W^ep, W^p)."""
    cols = reference_integrals(surface, s, material, hertz=hertz, rtol=rtol)
    return np.array([cols[:3].sum(), cols[3:6].sum(), cols[6], *cols[:6]], dtype=float)


#: the committed seed of the cache (module docstring)
SEED = Path(__file__).resolve().parent / "data" / "references.json"
#: the library modules the reference values run through (relative to src/roughcontact)
FINGERPRINT_SOURCES = (
    "validation.py", "statistics/surface.py", "asperity/ellipse.py", "asperity/material.py",
    "asperity/laws.py", "integrals/polar.py", "integrals/normal_moments.py", "integrals/_normal_moments_data.py",
    "integrals/reference.py", "integrals/reference_functions.py", "integrals/reference_elastoplastic.py",
    "integrals/rules.py", "contact/elastic.py", "contact/closures.py",
)


def code_fingerprint() -> str:
    """SHA-256 (16 hex digits) of the sources in FINGERPRINT_SOURCES."""
    import roughcontact

    root = Path(roughcontact.__file__).resolve().parent
    h = hashlib.sha256()
    for rel in FINGERPRINT_SOURCES:
        h.update(rel.encode() + b"\0" + (root / rel).read_bytes())
    return h.hexdigest()[:16]


class ReferenceCache:
    """A JSON file of {key: record}; :meth:`get` computes and stores on a miss, after looking in
    the ``seed`` file for a record computed by the same reference code (module docstring)."""

    def __init__(self, path: Path, seed: Path | None = None):
        self.path = Path(path)
        self.data = json.loads(self.path.read_text()) if self.path.exists() else {}
        self.seed = json.loads(Path(seed).read_text()) if seed is not None and Path(seed).exists() else {}
        self.fingerprint = code_fingerprint()
        self.seeded: dict[str, str] = {}  # key -> date the seed record was computed

    def get(self, key: str, compute):
        if key not in self.data:
            rec = self.seed.get(key)
            if rec is not None and rec.get("fingerprint") == self.fingerprint:
                self.data[key] = {"value": rec["value"], "seconds": rec["seconds"], "seeded": rec["date"]}
                self.seeded[key] = rec["date"]
            else:
                t0 = time.perf_counter()
                value = compute()
                self.data[key] = {"value": value, "seconds": time.perf_counter() - t0}
            self.save()
        return self.data[key]["value"]

    def update_seed(self, path: Path = SEED) -> int:
        """Write every record computed by this code into the seed file (merged); returns how many."""
        path = Path(path)
        seed = json.loads(path.read_text()) if path.exists() else {}
        date = time.strftime("%Y-%m-%d")
        n = 0
        for key, rec in self.data.items():
            if "seeded" not in rec:
                seed[key] = {"value": rec["value"], "seconds": rec["seconds"], "fingerprint": self.fingerprint,
                             "date": date}
                n += 1
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(seed, indent=1, sort_keys=True) + "\n")
        return n

    def save(self) -> None:
        self.path.parent.mkdir(parents=True, exist_ok=True)
        tmp = self.path.with_suffix(".part")
        tmp.write_text(json.dumps(self.data, indent=1, sort_keys=True))
        tmp.replace(self.path)


def _surface_key(surface: SpectralMoments) -> str:
    return ",".join(f"{v!r}" for v in surface.as_dict().values())


def elastic(cache: ReferenceCache, surface: SpectralMoments, s: float, hertz: str = "exact", dps: int = 20):
    """(A/A0, W/A0, K/A0) at E* = 1 from the mpmath integrator."""
    key = f"elastic|{_surface_key(surface)}|s={s!r}|{hertz}|dps={dps}"

    return np.array(cache.get(key, lambda: mpmath_values(surface, s, hertz=hertz, dps=dps).tolist()))


def elastoplastic(cache: ReferenceCache, surface: SpectralMoments, s: float, psi: float, hertz: str = "exact",
                  rtol: float = 1e-10):
    """(A/A0, W/A0, K/A0) and the parts (A^e, A^ep, A^p, W^e, W^ep, W^p) from the scipy twin."""
    mat = material_for(psi, surface)
    key = f"elastoplastic|{_surface_key(surface)}|s={s!r}|psi={psi!r}|{hertz}|rtol={rtol!r}|Y={mat.Y!r}"

    return np.array(cache.get(key, lambda: twin_values(surface, s, mat, hertz=hertz, rtol=rtol).tolist()))


def elastic_limit_check(cache: ReferenceCache, surface: SpectralMoments, s: float, psi: float = 1e-3) -> float:
    """Largest relative difference of the twin at small ψ (every summit elastic) from the
    elastic mpmath reference, over A, W, K (E* = 1.14e5 for both)."""
    twin = elastoplastic(cache, surface, s, psi)[:3]
    ref = elastic(cache, surface, s) * np.array([1.0, E_STAR, E_STAR])
    return float(np.max(np.abs(twin / ref - 1.0)))


def plastic_limit_area(cache: ReferenceCache, surface: SpectralMoments, s: float, dps: int = 16) -> float:
    """A/A0 when every contacting summit is fully plastic: π D_sum √(m00 μ) ∫ dθ cs 2f3/c
    ∫ dr r² e^{−r²/2} J_1(r g − l), by mpmath (inner integral reference.inner_integral,
    f3 = E/(2 e1 B) from mpmath's Carlson forms, tanh-sinh in θ split at θ*)."""
    key = _plastic_limit_key(surface, s, dps)

    def compute():
        geom = PolarGeometry(surface)
        l = float(surface.l_from_s(s))
        with mp.workdps(dps):
            def integrand(theta):
                th = float(theta)
                lam2 = float(geom.lambda_squared(th))
                e1 = RF.exact_e1(lam2)
                with mp.extradps(15):
                    _, E, _, B = RF._carlson(e1 * e1)
                    f3 = E / (2 * e1 * B)  # (59) rearranged, ellipse.f3
                cs = mp.cos(theta) * mp.sin(theta)
                inner, _ = R.inner_integral("area", float(geom.g(th)), l, dps=dps)
                return cs * 2 * f3 / float(geom.c(th)) * inner

            val = mp.quad(integrand, [0, geom.theta_circle, mp.pi / 2])
        return float(ElasticPrefactors.of(surface).area * val)

    return float(cache.get(key, compute))


def _plastic_limit_key(surface: SpectralMoments, s: float, dps: int = 16) -> str:
    return f"plastic_limit_area|{_surface_key(surface)}|s={s!r}|dps={dps}"


def plastic_limit_cached(cache: ReferenceCache, surface: SpectralMoments, s: float) -> bool:
    """Whether :func:`plastic_limit_area` at (surface, s) is already in the cache."""
    return _plastic_limit_key(surface, s) in cache.data


def plastic_limit_check(cache: ReferenceCache, surface: SpectralMoments, s: float, psi: float = 1e4) -> float:
    """Relative difference of the twin's area at large ψ from :func:`plastic_limit_area`."""
    twin = elastoplastic(cache, surface, s, psi)[0]
    return float(abs(twin / plastic_limit_area(cache, surface, s) - 1.0))


def mpmath_time(surface: SpectralMoments, s: float, hertz: str = "exact", dps: int = 20) -> float:
    """Wall time of one elastic mpmath reference separation (A, W, K), after a first call on
    the surface has memoised its θ-node Hertz factors."""
    l = float(surface.l_from_s(s))
    R.elastic_integrals(surface, l + 0.01, hertz=hertz, dps=dps)  # set-up: θ-node factors
    t0 = time.perf_counter()
    R.elastic_integrals(surface, l, hertz=hertz, dps=dps)
    return time.perf_counter() - t0


def mpmath_values(surface: SpectralMoments, s: float, hertz: str = "exact", dps: int = 12) -> np.ndarray:
    """(A/A0, W/A0, K/A0) at E* = 1 from the mpmath integrator at ``dps`` digits."""
    return first_values(elastic_contact(surface, [s], 1.0, hertz=hertz, method="reference", dps=dps))
