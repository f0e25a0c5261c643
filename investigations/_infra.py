"""Shared integrators for investigations/area_columns.py (not part of the package)."""
import math
import numpy as np
import yaml
from pathlib import Path
from scipy.special import pbdv, gamma
from roughcontact.statistics import SpectralMoments
from roughcontact.integrals.polar import PolarGeometry, ElasticPrefactors
from roughcontact.integrals.rules import theta_rule, settings_for, TanhSinh
from roughcontact.asperity import ellipse

ROOT = Path(__file__).resolve().parents[1]
E_STAR = 1.14e5


def load_tables():
    pv = yaml.safe_load(open(ROOT / "config" / "paper_values.yaml"))
    out = {}
    for key in ("table1", "table2"):
        T = pv[key]
        out[key] = dict(
            S=SpectralMoments(**T["surface"]),
            s=np.array([float(x) for x in T["rows"]]),
            A=np.array([float(x) for x in T["columns"]["anisotropic"]["area_fraction"]]) / 100.0,
            W=np.array([float(x) for x in T["columns"]["anisotropic"]["pressure"]]),
        )
    return out


def Jnu(nu, a):
    """J_ν(a) = ∫_0^∞ t^ν φ(t − a) dt via the parabolic cylinder function."""
    a = np.asarray(a, float)
    with np.errstate(all="ignore"):
        d, _ = pbdv(-nu - 1.0, -a)
        v = gamma(nu + 1.0) / math.sqrt(2 * math.pi) * np.exp(-a * a / 4.0) * d
    return np.nan_to_num(v)


_TS_R = TanhSinh(5).nodes_weights


def theta_nodes(S, extra_breaks=(), level=5):
    geom = PolarGeometry(S)
    breaks = [geom.theta_circle]
    for lam in (ellipse.PAPER_LAMBDA_CLIP,):
        breaks.extend(geom.theta_at_lambda(lam))
    breaks.extend(extra_breaks)
    th, w = theta_rule(breaks, settings_for("table").__class__(level, 4, 4))
    return th, w, geom


def polar_integral(S, l_values, F, r_pow, nu, l_in_t=None, th_level=5, rmax=16.0):
    """∫dθ cs F(θ) ∫dr r^{r_pow} e^{−r²/2} J_ν(r g(θ) − l).

    F: array over the θ nodes (from theta_nodes). r-rule: tanh-sinh on [0, rmax].
    """
    th, w, geom = F["theta"], F["w"], F["geom"]
    vals = F["vals"]
    g = geom.g(th)
    y, wr = _TS_R
    r = rmax * y
    wr = rmax * wr
    base = wr * r ** r_pow * np.exp(-0.5 * r * r)  # (nr,)
    out = []
    for l in np.atleast_1d(l_values):
        J = Jnu(nu, np.outer(g, r) - l)  # (nθ, nr)
        inner = J @ base
        out.append(np.sum(w * np.cos(th) * np.sin(th) * vals * inner))
    return np.array(out)


def polar_integral_g(g, wvals, l_values, r_pow, nu, rmax=16.0, r_shift=None):
    """Σ_θ wvals ∫dr r^{r_pow} e^{−r²/2} J_ν(r g − l): wvals already hold w·|cs|·F(θ)."""
    y, wr = _TS_R
    r = rmax * y
    wr = rmax * wr
    base = wr * r ** r_pow * np.exp(-0.5 * r * r)
    out = []
    for l in np.atleast_1d(l_values):
        J = Jnu(nu, np.outer(g, r) - l)
        out.append(np.sum(wvals * (J @ base)))
    return np.array(out)


def theta_rule_on(a, b, breaks=(), level=5):
    br = [x for x in breaks if a < x < b]
    from roughcontact.integrals.rules import QuadratureSettings
    y, w = TanhSinh(level).nodes_weights
    edges = np.unique(np.concatenate(([a], br, [b])))
    nodes, weights = [], []
    for lo, hi in zip(edges[:-1], edges[1:]):
        nodes.append(lo + (hi - lo) * y)
        weights.append((hi - lo) * w)
    return np.concatenate(nodes), np.concatenate(weights)
