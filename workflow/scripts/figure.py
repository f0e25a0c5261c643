"""Plot a figure scene (PNG), export its data (CSV), check its prose claims."""

import csv
import io as _io
from pathlib import Path

import numpy as np
import yaml

from roughcontact import SpectralMoments, io
from roughcontact.paper import claims, plots, verify
from roughcontact.plots.style import SYMBOLS, axis_label, parameter_label, pretty_unit


def _csv(header, columns):
    buf = _io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(header)
    for row in zip(*columns):
        w.writerow([repr(float(x)) for x in row])
    return buf.getvalue()


def _draw(draw, plot, *args, **kwargs):
    """The figure, or None where only the CSV and the checks are wanted (the published-CSV anchor
    re-derives the CSV from the curves without drawing)."""
    return plot(*args, **kwargs) if draw else None


def bearing_ratio(scene, cfg, ds, draw=True):
    s = ds["s"].values
    labels = []  # m00 = 3 µm², α = 3: the moments' own values and units (config `units`)
    for i in range(ds.sizes["surface"]):
        moments = {m: float(ds[m].values[i]) for m in ("m00", "m20", "m02", "m40", "m04")}
        alpha = SpectralMoments(**moments).alpha1
        labels.append(f"{parameter_label('m00', moments['m00'], ds['m00'].attrs['units'])}, $\\alpha$ = {alpha:.3g}")
    ratios = {lab: ds["bearing_area_ratio"].values[i] for i, lab in enumerate(labels)}
    markers = {lab: c.get("marker") for lab, c in zip(labels, cfg["curves"])}
    fig = _draw(draw, plots.fig3, s, ratios, markers=markers)
    header = ["s [1]"] + [f"AG_over_AB[{name}] [1]" for name in ds["surface"].values]
    data = _csv(header, [s, *ratios.values()])
    checks = [verify.claim_check(scene, claim, s, ratios, x_name="s") for claim in cfg["claims"]]
    return fig, data, checks


def hertz_factors(scene, cfg, ds, draw=True):
    e = ds["e"].values
    hertz = [str(h) for h in ds["hertz"].values]
    names = {"exact": "exact K, E", "paper": "paper's polynomials (36)-(39)"}
    curves = {names.get(h, h): (ds["f1"].values[i], ds["f2"].values[i]) for i, h in enumerate(hertz)}
    fig = _draw(draw, plots.fig4, e, curves)
    header, columns = ["e [1]"], [e]
    for i, h in enumerate(hertz):
        header += [f"f1[{h}] [1]", f"f2[{h}] [1]"]
        columns += [ds["f1"].values[i], ds["f2"].values[i]]
    checks = []
    for claim in cfg["claims"]:
        i = hertz.index(claim.get("hertz", hertz[0]))
        checks.append(verify.claim_check(scene, claim, e, {"f1": ds["f1"].values[i], "f2": ds["f2"].values[i]}, x_name="e"))
    return fig, _csv(header, columns), checks


def _long_csv(ds, variables):
    """The variables of ``ds`` in long form (one row per coordinate combination), full precision;
    each numeric column headed ``name [units]`` (the netCDF units, from config `units`)."""
    table = ds[list(variables)].to_dataframe().reset_index()
    names = {c: f"{c} [{ds[c].attrs['units']}]" for c in table.columns if c in ds and "units" in ds[c].attrs}
    return table.rename(columns=names).to_csv(index=False, float_format="%.17g")


def _claims(scene, cfg, ds):
    defaults = {k: cfg[k] for k in ("pressure_range",) if k in cfg}
    return [claims.evaluate(scene, {**defaults, **claim}, ds) for claim in cfg["claims"]]


def elastoplastic_psi(scene, cfg, ds, draw=True):
    """Fig. 5 (plot: area_parts) or Fig. 6 (plot: mean_pressure) from the ψ-curves."""
    labels = [parameter_label("psi", p) for p in ds["psi"].values]
    load = dict(zip(labels, claims.load_axis(ds)))
    ds = ds.assign(load_W_over_HA0=(("psi", "s"), claims.load_axis(ds), {"units": "1"}))
    if cfg["plot"] == "area_parts":
        plastic, yielded = claims.fraction(ds, "plastic"), claims.fraction(ds, "yielded")
        fig = _draw(draw, plots.fig5, load, dict(zip(labels, plastic)), dict(zip(labels, yielded)))
        ds = ds.assign(plastic_over_A=(("psi", "s"), plastic, {"units": "1"}),
                       yielded_over_A=(("psi", "s"), yielded, {"units": "1"}))
        table = _long_csv(ds, ["load_W_over_HA0", "plastic_over_A", "yielded_over_A", "area_fraction", "pressure"])
    else:
        ratio = claims.mean_pressure_over_H(ds)
        K_Y, tabor, c_h = 1.62, 0.354, 0.967  # captions; (68); (66)
        levels = {"0.354 (the prose)": tabor, "$(2/3)\\,K_Y Y/H$ = 0.382": 2 / 3 * K_Y * tabor, "$c_h$ = 0.967": c_h}
        fig = _draw(draw, plots.fig6, load, dict(zip(labels, ratio)), levels)
        ds = ds.assign(W_over_AH=(("psi", "s"), ratio, {"units": "1"}))
        table = _long_csv(ds, ["load_W_over_HA0", "W_over_AH", "area_fraction", "pressure"])
    return fig, table, _claims(scene, cfg, ds)


def stiffness_pressure(scene, cfg, ds, draw=True):
    """Figs 7–8: K/A0 vs W/A0, one panel per closure (the figure's closure first)."""
    order = [cfg["figure_closure"]] + [c for c in ds["closure"].values if c != cfg["figure_closure"]]
    panels = {}
    for closure in order:
        e = ds.sel(closure=closure)
        psis = sorted({round(float(p), 2) for p in e["material_psi"].values})
        psi_txt = ", ".join(f"{p:.2f}" for p in psis)
        title = f"closure {closure}" + (" (the figure)" if closure == cfg["figure_closure"] else "") + \
            f"\n{SYMBOLS['psi']} = {psi_txt}"
        panels[title] = {
            parameter_label("m00", m, ds["m00"].attrs.get("units")): (e["elastic_model_pressure"].values[i], e["elastic_model_stiffness"].values[i],
                             e["pressure"].values[i], e["stiffness"].values[i])
            for i, m in enumerate(e["m00"].values)
        }
    fig = _draw(draw, plots.stiffness_vs_pressure, panels, xlim=tuple(cfg["pressure_range"]), units=_pk_units(ds))
    table = _long_csv(ds, ["pressure", "stiffness", "elastic_model_pressure", "elastic_model_stiffness"])
    return fig, table, _claims(scene, cfg, ds)


def _pk_units(ds):
    """(pressure, stiffness) units of a curves file (from config `units`)."""
    return ds["pressure"].attrs["units"], ds["stiffness"].attrs["units"]


def _variant_label(name, factors):
    """{m20: 0.5, m02: 0.5} → "m20, m02 × 0.5" (mathtext); the base surface as such."""
    if not factors:
        return "base surface"
    by_factor = {}
    for k, f in factors.items():
        by_factor.setdefault(float(f), []).append(SYMBOLS.get(k, k))
    return "; ".join(f"{', '.join(ks)} × {f:g}" for f, ks in by_factor.items())


def stiffness_sensitivity(scene, cfg, ds, draw=True):
    variants = {_variant_label(str(v), cfg["variants"].get(str(v), {})):
                (ds["pressure"].sel(variant=v).values, ds["stiffness"].sel(variant=v).values)
                for v in ds["variant"].values}
    by_psi = {parameter_label("psi", p): (ds["psi_pressure"].sel(psi=p).values, ds["psi_stiffness"].sel(psi=p).values)
              for p in ds["psi"].values}
    fig = _draw(draw, plots.stiffness_sensitivity, variants, by_psi, xlim=tuple(cfg["pressure_range"]), units=_pk_units(ds))
    table = _long_csv(ds, ["pressure", "stiffness", "elastic_model_pressure", "elastic_model_stiffness"])
    return fig, table, _claims(scene, cfg, ds)


def friction_slip_rule(scene, cfg, ds, draw=True):
    """Fig. 9: one panel per k for the first (orthotropic) parameter set."""
    first = str(ds["set"].values[0])
    e = ds.sel(set=first)
    panels = {
        f"{first}: $\\mu_x$ = {float(e['mu_x']):g}, $\\mu_y$ = {float(e['mu_y']):g}, $k$ = {k:g}": dict(
            mu_x=float(e["mu_x"]), mu_y=float(e["mu_y"]), ratio=float(e["nu_y_over_nu_x"].sel(k=k)),
            p_N=1.0, **{v: e[v].sel(k=k).values for v in ("t_x", "t_y", "up_x", "up_y")})
        for k in e["k"].values
    }
    fig = _draw(draw, plots.fig9, panels)
    table = _long_csv(ds, ["t_x", "t_y", "up_x", "up_y", "alpha", "beta"])
    return fig, table, _claims(scene, cfg, ds)


def friction_hardening(scene, cfg, ds, draw=True):
    length = ds["kappa_x"].attrs["units"]
    fig = _draw(draw, plots.slip_hardening, ds["kappa_x"].values, ds["traction_ratio"].values, ds["mu_x_89"].values, units=length,
                               title=f"$\\mu_m$ = {cfg['mu_m']:g}, $\\mu_o$ = {cfg['mu_o']:g}, "
                                     f"$n$ = {cfg['n']:g} {pretty_unit(length + '-1')}")
    table = _long_csv(ds, ["u_x", "kappa_x", "traction_ratio", "mu_x_89"])
    return fig, table, _claims(scene, cfg, ds)


def friction_cases(scene, cfg, ds, draw=True):
    panels = {}
    for case in ds["case"].values:
        d = ds.sel(case=case, path="direct")
        u = np.hypot(d["u_x"].values, d["u_y"].values)
        panels[f"case ({case})"] = (np.where(d["loading"].values, u, 2 * u.max() - u),
                                    d["t_x"].values, d["t_y"].values, d["up_x"].values, d["up_y"].values)
    fig = _draw(draw, plots.friction_cases, panels, xlabel=axis_label("imposed slip path, loading then unloading", ds["u_x"].attrs["units"]),
                               ylabel=axis_label("traction", ds["t_x"].attrs["units"]))
    table = _long_csv(ds, ["t_x", "t_y", "up_x", "up_y", "dissipation"])
    return fig, table, _claims(scene, cfg, ds)


MAKERS = {"bearing_ratio": bearing_ratio, "hertz_factors": hertz_factors, "elastoplastic_psi": elastoplastic_psi,
          "stiffness_pressure": stiffness_pressure, "stiffness_sensitivity": stiffness_sensitivity,
          "friction_slip_rule": friction_slip_rule, "friction_hardening": friction_hardening,
          "friction_cases": friction_cases}


def csv_text(scene, cfg, ds):
    """The published CSV of a figure scene from its curves (what run writes), without drawing."""
    return MAKERS[cfg["kind"]](scene, cfg, ds, draw=False)[1]


def run(scene, cfg, data, expected, out, log):
    with io.log_to(log) as logger:
        ds = io.read_netcdf(data)
        fig, table, checks = MAKERS[cfg["kind"]](scene, cfg, ds)
        checks = verify.apply_expectations(checks, yaml.safe_load(Path(expected).read_text()))
        for c in checks:
            logger.info("%s: %s (%s) %s", c.id, c.verdict, c.status, c.detail)
        plots.save(fig, out["png"])
        io.write_text(out["csv"], table)
        io.write_text(out["checks"], verify.checks_to_csv(checks))


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.scene, sm.params.scene_config, sm.input.data, sm.input.expected,
        {"png": sm.output.png, "csv": sm.output.csv, "checks": sm.output.checks}, sm.log[0])
