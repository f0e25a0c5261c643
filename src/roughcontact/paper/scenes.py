"""The data of the figure scenes beyond Tables 1–3 and Figs 3–4, as labelled xarray Datasets
ready for :mod:`roughcontact.paper.claims` and :mod:`roughcontact.paper.plots` — exactly the curves each
scene needs. No I/O.

* elasto-plastic (Figs 5–8, stiffness sensitivity): assembled from :mod:`roughcontact.contact.sweep`;
* interface friction law (section 8; Fig. 9, a slip-hardening curve, Fig. 18's cases (a)–(c) at
  one material point): driven through :func:`roughcontact.interface.friction.update`, the same
  implicit return mapping the FE engine calls, so the figures show what the code does.
"""

from __future__ import annotations

from typing import Mapping, Sequence

import numpy as np
import xarray as xr

from ..asperity import effective_modulus, paper_K_v
from ..contact import elastoplastic_contact, resolve_material
from ..contact.sweep import SweepSpec, parameter_units, run_sweep
from ..contact.units import PARAMETER_LONG_NAMES
from ..contact.units import attrs as contact_attrs
from ..examples.section9 import fig18_preset
from ..integrals.reference_elastoplastic import reference_integrals
from ..interface import InterfaceLaw, NormalLawTable, friction
from ..statistics.surface import SpectralMoments

__all__ = [
    "psi_curves", "stiffness_curves", "stiffness_sensitivity",
    "slip_rule_geometry", "hardening_path", "fig18_paths", "fig18_scene", "elastoplastic_numerics",
]

_MOMENTS = ("m00", "m20", "m02", "m40", "m04")


def psi_curves(moments: Mapping[str, float], E_star: float, psi: Sequence[float], s, *,
               closure: str = "yield-from-psi", hertz="exact", accuracy="plot", units=None):
    """Figs 5–6: the elasto-plastic model of one surface for several plasticity indices ψ
    (dims psi, s), with ``material_H`` for the load axis W/(H A0)."""
    spec = SweepSpec(axes={"psi": psi}, s=s, fixed={**moments, "E_star": E_star}, closure=closure,
                     hertz=hertz, accuracy=accuracy, with_elastic=False, **_units(units))
    return run_sweep(spec)


def stiffness_curves(moments: Mapping[str, float], m00: Sequence[float], E_star: float, psi: float,
                     Y: float, closures: Sequence[str], s, *, hertz="exact", accuracy="plot", units=None):
    """Figs 7–8: elasto-plastic and purely elastic K/A0 and W/A0 for several m00 (the other
    moments fixed), one per closure (dims closure, m00, s). The captions give both ψ and Y:
    "material" uses Y (ψ follows), "yield-from-psi" uses ψ, "paper-literal" both."""
    fixed = {k: v for k, v in moments.items() if k != "m00"}
    inputs = {"material": {"Y": Y}, "yield-from-psi": {"psi": psi}, "paper-literal": {"psi": psi, "Y": Y}}
    parts = []
    for closure in closures:
        spec = SweepSpec(axes={"m00": m00}, s=s, fixed={**fixed, "E_star": E_star, **inputs[closure]},
                         closure=closure, hertz=hertz, accuracy=accuracy, **_units(units))
        parts.append(run_sweep(spec).expand_dims(closure=[closure]))
    ds = xr.concat(parts, dim="closure", combine_attrs="drop_conflicts")
    ds["closure"].attrs.update(long_name="plasticity-index closure (roughcontact.contact.closures)")
    ds.attrs.update(psi=float(psi), Y=float(Y))
    return ds


def stiffness_sensitivity(moments: Mapping[str, float], E_star: float, psi: float,
                          variants: Mapping[str, Mapping[str, float]], psi_values: Sequence[float], s, *,
                          closure: str = "yield-from-psi", hertz="exact", accuracy="plot", units=None):
    """Sections 7 and 10: K/A0 vs W/A0 of the base surface and of ``variants`` (each a map
    moment → factor, e.g. {"m20": 2, "m02": 2}; the base is added as "base") at plasticity
    index ``psi`` (dims variant, s), and the elasto-plastic model of the base surface for
    ``psi_values`` (variables psi_pressure, psi_stiffness over psi, s)."""
    rows = {"base": dict(moments)}
    for name, factors in variants.items():
        unknown = set(factors) - set(_MOMENTS)
        if unknown:
            raise ValueError(f"variant {name!r}: unknown moments {', '.join(sorted(unknown))}")
        rows[name] = {k: v * float(factors.get(k, 1.0)) for k, v in moments.items()}
    parts = []
    for name, mom in rows.items():
        spec = SweepSpec(axes={"psi": [psi]}, s=s, fixed={**mom, "E_star": E_star}, closure=closure,
                         hertz=hertz, accuracy=accuracy, **_units(units))
        parts.append(run_sweep(spec).isel(psi=0, drop=True).expand_dims(variant=[name]))
    ds = xr.concat(parts, dim="variant", combine_attrs="drop_conflicts")
    ds["variant"].attrs.update(long_name="surface variant: moments scaled by the factors of variant_<moment>")
    punits = parameter_units(**units) if units else {}
    for k in _MOMENTS:
        ds[f"variant_{k}"] = ("variant", [rows[n][k] for n in rows],
                              {**({"units": punits[k]} if k in punits else {}), "long_name": PARAMETER_LONG_NAMES[k]})
    by_psi = psi_curves(moments, E_star, psi_values, s, closure=closure, hertz=hertz, accuracy=accuracy, units=units)
    for v in ("pressure", "stiffness"):
        ds[f"psi_{v}"] = by_psi[v]
    ds.attrs.update(psi=float(psi), closure=closure)
    return ds


_EP_COLUMNS = ("elastic_area_fraction", "elastoplastic_area_fraction", "plastic_area_fraction",
               "elastic_pressure", "elastoplastic_pressure", "plastic_pressure", "stiffness")


def elastoplastic_numerics(points: Sequence[Mapping], surfaces: Mapping[str, Mapping[str, float]],
                           E_star: float, *, production="table", reference_rtol: float = 1e-10, units=None,
                           reference=reference_integrals):
    """Production (numba, preset ``production``) against the slow twin
    (elastoplastic.reference_integrals, adaptive cubature at ``reference_rtol``) at check points
    (each: surface name, ψ, s, hertz, optional ``paper_K_v_poisson`` for the paper's K_v of (75)).
    Variables over ``point``: ``production_<column>``, ``reference_<column>`` for each column of
    the attribute ``columns`` (the regime parts of A/A0 and W/A0, and K/A0; totals are sums of
    parts), in the unit system ``units`` ({"length", "stress"}). ``reference``: the twin, called
    as reference_integrals is (the workflow passes one that takes the value from a committed seed
    when the twin's code is unchanged)."""
    prod, ref, labels = [], [], []
    for pt in points:
        surface = SpectralMoments(**surfaces[pt["surface"]])
        nu = pt.get("paper_K_v_poisson")
        mat = resolve_material(surface, E_star=E_star, psi=pt["psi"],
                               K_v=None if nu is None else float(paper_K_v(nu)))
        c = elastoplastic_contact(surface, [pt["s"]], mat, hertz=pt["hertz"], accuracy=production)
        prod.append([float(getattr(c, k)[0]) for k in _EP_COLUMNS])
        ref.append(list(reference(surface, pt["s"], mat, hertz=pt["hertz"], rtol=reference_rtol)[:7]))
        labels.append(f"{pt['surface']},psi={pt['psi']:g},s={pt['s']:g},{pt['hertz']}"
                      + ("" if nu is None else f",K_v(nu={nu:g})"))
    data = {}
    for method, values in (("production", np.array(prod)), ("reference", np.array(ref))):
        for j, col in enumerate(_EP_COLUMNS):
            meta = contact_attrs(col, units)
            data[f"{method}_{col}"] = ("point", values[:, j], {**meta, "long_name": f"{meta['long_name']} ({method})"})
    return xr.Dataset(
        data, coords={"point": ("point", labels, {"long_name": "check point: surface, psi, s, Hertz functions"})},
        attrs={"production_preset": str(production), "reference_rtol": reference_rtol, "E_star": E_star,
               "columns": " ".join(_EP_COLUMNS)},
    )


def _units(units):
    return {} if units is None else {"units": dict(units)}


# ---------------------------------------------------------------------------------------
# interface friction law (section 8)
# ---------------------------------------------------------------------------------------
def _drive(model, du_steps, k_N, k_Tx, k_Ty, p_N):
    """Run one material point per row of ``du_steps`` (points, steps, 2) of tangential
    increments at a fixed normal pressure p_N (closure u_N = p_N/k_N, constant k_N); returns
    the states after each step, shape (points, steps, NSTATE)."""
    n_pts, n_steps = du_steps.shape[:2]
    state = friction.initial_state(n_pts, u_N=p_N / k_N, k_N=k_N)
    out = np.empty((n_pts, n_steps, friction.NSTATE))
    du = np.zeros((n_pts, 3))
    for i in range(n_steps):
        du[:, :2] = du_steps[:, i]
        state = friction.update(model, state, du, k_N, k_Tx, k_Ty).state
        out[:, i] = state
    return out


def slip_rule_geometry(mu: Mapping[str, tuple], k_values: Sequence[float], *, directions: int = 24,
                       k_T: float = 1.0, p_N: float = 1.0, overshoot: float = 20.0):
    """Fig. 9: for each parameter set (name → (μ_x, μ_y), no hardening) and potential exponent k
    of (98), a material point is pushed into sliding along ``directions`` imposed directions
    with one large increment (``overshoot`` × the elastic limit; the backward-Euler return
    lands on the limit surface (91)). Variables over (set, k, direction): the final traction
    t_x, t_y [stress], the plastic slip u^p [length], the slip angle α (114) and traction angle
    β (116) [rad], and ν_y/ν_x = (μ_y/μ_x)^k (98)."""
    phi = np.linspace(0.0, 2.0 * np.pi, directions, endpoint=False)
    names, ks = list(mu), [float(k) for k in k_values]
    shape = (len(names), len(ks), directions)
    data = {v: np.empty(shape) for v in ("t_x", "t_y", "up_x", "up_y", "alpha", "beta")}
    ratio = np.empty(shape[:2])
    for a, name in enumerate(names):
        mu_x, mu_y = (float(v) for v in mu[name])
        reach = overshoot * max(mu_x, mu_y) * p_N / k_T
        for b, k in enumerate(ks):
            model = friction.OrthotropicHardening(mu_x, mu_y, k=k)
            du = np.stack([reach * np.cos(phi), reach * np.sin(phi)], axis=-1)[:, None, :]
            s = _drive(model, du, 1.0, k_T, k_T, p_N)[:, -1]
            up = s[:, [friction.UP_X, friction.UP_Y]]
            data["t_x"][a, b], data["t_y"][a, b] = s[:, friction.T_X], s[:, friction.T_Y]
            data["up_x"][a, b], data["up_y"][a, b] = up[:, 0], up[:, 1]
            data["alpha"][a, b] = friction.slip_angle(up)  # eq. (114)
            data["beta"][a, b] = friction.traction_angle(s[:, [friction.T_X, friction.T_Y]])  # eq. (116)
            ratio[a, b] = (mu_y / mu_x) ** k  # eq. (98)
    dims = ("set", "k", "direction")
    # dimensionless demonstration: tractions in units of p_N, slips in units of p_N/k_T
    meta = {"t_x": ("1", "traction t_x / p_N"), "t_y": ("1", "traction t_y / p_N"),
            "up_x": ("1", "plastic slip u^p_x / (p_N/k_T)"), "up_y": ("1", "plastic slip u^p_y / (p_N/k_T)"),
            "alpha": ("rad", "slip angle, eq. (114)"), "beta": ("rad", "traction angle, eq. (116)")}
    ds = xr.Dataset(
        {v: (dims, data[v] / (p_N if v[0] == "t" else p_N / k_T if v[:2] == "up" else 1.0),
             {"units": meta[v][0], "long_name": meta[v][1]}) for v in data},
        coords={"set": ("set", names, {"long_name": "friction parameter set"}),
                "k": ("k", ks, {"units": "1", "long_name": "exponent k of the slip potential, eq. (98)"}),
                "direction": ("direction", phi, {"units": "rad", "long_name": "imposed slip direction"})},
    )
    ds["nu_y_over_nu_x"] = (("set", "k"), ratio, {"units": "1", "long_name": "(mu_y/mu_x)^k, eq. (98)"})
    ds["mu_x"] = ("set", [float(mu[n][0]) for n in names], {"units": "1", "long_name": "friction coefficient along x"})
    ds["mu_y"] = ("set", [float(mu[n][1]) for n in names], {"units": "1", "long_name": "friction coefficient along y"})
    ds.attrs.update(p_N=p_N, k_T=k_T)
    return ds


def hardening_path(mu_m: float, mu_o: float, n: float, *, k_T: float, p_N: float, slip: float, steps: int,
                   length_unit: str = "um"):
    """A material-point slip-hardening curve: monotone slip along x (axis-aligned, so κ_x is
    the plastic slip) in ``steps`` equal increments up to ``slip`` [length] at pressure p_N;
    the traction ratio t_x/p_N against the accumulated slip κ_x, and μ_x(κ_x) of (89).
    ``length_unit``: of the slips (the inverse of n's unit)."""
    model = friction.OrthotropicHardening(mu_m, mu_m, mu_o, mu_o, n, n, k=0.0)
    u = np.linspace(0.0, slip, steps + 1)[1:]
    du = np.zeros((1, steps, 2))
    du[0, :, 0] = slip / steps
    s = _drive(model, du, 1.0, k_T, k_T, p_N)[0]
    kappa = s[:, friction.KAPPA_X]
    return xr.Dataset(
        {
            "traction_ratio": ("step", s[:, friction.T_X] / p_N, {"units": "1", "long_name": "t_x/p_N"}),
            "kappa_x": ("step", kappa, {"units": length_unit, "long_name": "accumulated slip, errata E19"}),
            "mu_x_89": ("step", model.mu(kappa, kappa)[0], {"units": "1", "long_name": "mu_x of eq. (89)"}),
            "u_x": ("step", u, {"units": length_unit, "long_name": "imposed tangential displacement"}),
        },
        coords={"step": ("step", np.arange(steps), {"units": "1", "long_name": "load step"})},
        attrs=dict(mu_m=mu_m, mu_o=mu_o, n=n, k_T=k_T, p_N=p_N),
    )


def fig18_paths(cases: Sequence[str], k_N: float, p_N: float, *, angle_deg: float, u_max: float,
                steps: int, length_unit: str = "um", stress_unit: str = "N/mm^2"):
    """Tractions against imposed slip for the parameter sets (a), (b), (c) of the Fig. 18
    caption (examples.section9.fig18_preset) at one material point under pressure p_N: the tangential
    displacement goes from 0 to ``u_max`` along ``angle_deg`` from x and back to 0 (2 ×
    ``steps`` increments), and — for the symmetry claims — the mirror path with x and y
    exchanged (dim ``path``: "direct", "swapped"). Variables over (case, path, step): imposed
    u_x, u_y, tractions t_x, t_y, plastic slips u^p, dissipation."""
    th = np.radians(angle_deg)
    ramp = np.concatenate([np.linspace(0.0, u_max, steps + 1), np.linspace(u_max, 0.0, steps + 1)[1:]])
    direct = np.stack([ramp * np.cos(th), ramp * np.sin(th)], axis=-1)
    paths = np.stack([direct, direct[:, ::-1]])  # (path, step + 1, 2)
    incr = np.diff(paths, axis=1)
    names = ("t_x", "t_y", "up_x", "up_y", "dissipation")
    cols = (friction.T_X, friction.T_Y, friction.UP_X, friction.UP_Y, friction.DISSIPATION)
    out = {v: np.empty((len(cases), 2, incr.shape[1])) for v in names}
    for c, case in enumerate(cases):
        model, k = fig18_preset(case, k_N, length_unit)
        s = _drive(model, incr, k["k_N"], k["k_Tx"], k["k_Ty"], p_N)
        for v, col in zip(names, cols):
            out[v][c] = s[..., col]
    dims = ("case", "path", "step")
    units = {"t_x": stress_unit, "t_y": stress_unit, "up_x": length_unit, "up_y": length_unit,
             "dissipation": f"{stress_unit} {length_unit}"}
    long = {"t_x": "traction t_x", "t_y": "traction t_y", "up_x": "plastic slip u^p_x", "up_y": "plastic slip u^p_y",
            "dissipation": "frictional dissipation per unit area"}
    ds = xr.Dataset(
        {v: (dims, out[v], {"units": units[v], "long_name": long[v]}) for v in names},
        coords={"case": ("case", list(cases), {"long_name": "Fig. 18 case"}),
                "path": ("path", ["direct", "swapped"], {"long_name": "slip path: direct, or x and y exchanged"}),
                "step": ("step", np.arange(incr.shape[1]), {"units": "1", "long_name": "load step"})},
    )
    ds["u_x"] = (("path", "step"), paths[:, 1:, 0], {"units": length_unit, "long_name": "imposed tangential displacement u_x"})
    ds["u_y"] = (("path", "step"), paths[:, 1:, 1], {"units": length_unit, "long_name": "imposed tangential displacement u_y"})
    ds["loading"] = ("step", np.arange(incr.shape[1]) < steps, {"units": "1", "long_name": "True while u grows"})
    ds.attrs.update(k_N=k_N, p_N=p_N, angle_deg=angle_deg, u_max=u_max)
    return ds


def fig18_scene(surface: Mapping[str, float], cfg: Mapping, units: Mapping[str, str]):
    """Fig. 18's cases (a)–(c) at one material point of the punch interface: E* from the two
    bodies (42), the material from ψ by the scene's closure, the normal law of the surface
    tabulated (interface.NormalLawTable, elasto-plastic) and put in its reference state at the
    initial pressure p0; k_N = k_N(u_N = 0) there, k_T as the preset says (0.7 k_N, or k_N).
    Then :func:`fig18_paths` along the scene's path."""
    moments = SpectralMoments(**surface)
    E = effective_modulus(cfg["E1"], cfg["nu1"], cfg["E2"], cfg["nu2"])  # eq. (42)
    material = resolve_material(moments, E_star=E, psi=cfg["psi"], closure=cfg["closure"])
    p0 = float(cfg["p0"])
    table = NormalLawTable.build(moments, "elastoplastic", material=material, pressure_range=(0.5 * p0, 2.0 * p0))
    p_ref, k_N = InterfaceLaw.from_pressure(table, p0).normal(0.0)
    ds = fig18_paths(cfg["cases"], float(k_N), float(p_ref), angle_deg=cfg["angle_deg"], u_max=cfg["u_max"],
                     steps=cfg["steps"], length_unit=units["length"], stress_unit=units["stress"])
    ds.attrs.update(E_star=E, psi=float(cfg["psi"]), closure=cfg["closure"], Y=material.Y,
                    normal_table_nodes=table.n_nodes)
    return ds
