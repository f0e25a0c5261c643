"""The command-line interface (roughcontact.cli): output, units, and one-line input errors."""

from __future__ import annotations

import json
import math
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from roughcontact import __version__, cli
import roughcontact.cli.contact  # noqa: F401  (cli.contact, monkeypatched below)

# The paper's Table 1 surface (lengths in µm).
M = dict(m00=0.0625, m20=8e-5, m02=8e-4, m40=1.04e-6, m04=1.04e-4)
MOMENT_ARGS = [a for k, v in M.items() for a in (f"--{k}", repr(v))]
E_STAR = "1.14e5"


def run(capsys, *argv):
    code = cli.main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def run_json(capsys, *argv):
    code, out, err = run(capsys, *argv, "--json")
    assert code == 0, err
    # nothing on stderr but one-line warnings (results outside the model's quantitative range)
    assert all(line.startswith("roughcontact: warning: ") for line in err.splitlines()), err
    # strict JSON: no NaN/Infinity tokens
    return json.loads(out, parse_constant=lambda tok: pytest.fail(f"non-strict token {tok}"))


# ---------------------------------------------------------------------------------------
# surface
# ---------------------------------------------------------------------------------------
def test_surface_json_matches_closed_forms(capsys):
    d = run_json(capsys, "surface", *MOMENT_ARGS)
    m00, m20, m02, m40, m04 = (M[k] for k in ("m00", "m20", "m02", "m40", "m04"))
    b1, b2 = m20**2 / (m00 * m40), m02**2 / (m00 * m04)
    expected = {
        "alpha1": m00 * m40 / m20**2,
        "alpha2": m00 * m04 / m02**2,
        "mu": 1 - m20**2 / (m00 * m40) - m02**2 / (m00 * m04),
        "summit_density": (2 * math.pi) ** -2 * math.sqrt(m40 * m04 / (m20 * m02)),
        "mean_summit_curvature": math.sqrt(math.pi / 8) * (math.sqrt(m40) + math.sqrt(m04)),
        "summit_height_std": math.sqrt(m00 * (1 - (math.pi / 2 - 1) * (b1 + b2))),
        "summit_mean_height": math.sqrt(math.pi * m00 / 2) * (math.sqrt(b1) + math.sqrt(b2)),
    }
    for key, value in expected.items():
        assert d[key] == pytest.approx(value, rel=1e-14), key
    assert d["alpha1"] == pytest.approx(10.15625, rel=1e-14)  # the paper's α = 10.16
    units = d["units"]
    assert units["summit_density"] == "1/L^2"
    assert units["mean_summit_curvature"] == "1/L"
    assert units["summit_height_std"] == units["summit_mean_height"] == "L"
    assert units["mu"] == units["alpha1"] == "1"
    assert set(expected) <= set(units)


def test_surface_text_is_aligned_listing(capsys):
    code, out, err = run(capsys, "surface", *MOMENT_ARGS)
    assert code == 0 and err == ""
    lines = out.splitlines()
    names = [line.split()[0] for line in lines]
    assert {"alpha1", "mu", "summit_density", "summit_mean_height"} <= set(names)
    # values right-aligned in one column, followed by the unit: the unit starts at one column
    assert len({len(line) - len(line.split()[-1]) for line in lines}) == 1
    assert any(line.endswith("1/L^2") for line in lines if line.startswith("summit_density"))


# ---------------------------------------------------------------------------------------
# elastic
# ---------------------------------------------------------------------------------------
def test_elastic_gw_reproduces_table1(capsys):
    d = run_json(capsys, "elastic", *MOMENT_ARGS, "--E-star", E_STAR, "--s", "1.0", "--model", "gw")
    # Table 1, GW column at s = 1.0 (5 significant digits printed)
    assert d["area_fraction"][0] == pytest.approx(0.051497, rel=1e-4)
    assert d["pressure"][0] == pytest.approx(86.5534, rel=1e-4)
    assert d["model"] == "gw" and d["hertz"] is None and d["method"] == "production"


def test_elastic_bgk_json_shape_and_monotone(capsys):
    s = ["0.5", "1.0", "1.5", "2.0"]
    d = run_json(capsys, "elastic", *MOMENT_ARGS, "--E-star", E_STAR, "--s", *s, "--accuracy", "plot")
    for key in ("s", "area_fraction", "pressure", "stiffness", "units", "model", "hertz", "method"):
        assert key in d, key
    assert d["s"] == [float(x) for x in s]
    assert len(d["area_fraction"]) == len(d["pressure"]) == len(d["stiffness"]) == len(s)
    assert (d["model"], d["hertz"], d["method"]) == ("bgk", "exact", "production")
    for key in ("area_fraction", "pressure", "stiffness"):
        v = d[key]
        assert all(x > 0 for x in v)
        assert all(a > b for a, b in zip(v, v[1:])), key
    assert all(0 < a < 1 for a in d["area_fraction"])  # a fraction, not a percentage
    assert set(d["units"]) >= {"s", "area_fraction", "pressure", "stiffness"}
    assert "E*" in d["units"]["pressure"] and "L" in d["units"]["stiffness"]


def test_elastic_pressure_scales_with_E_star(capsys):
    a = run_json(capsys, "elastic", *MOMENT_ARGS, "--E-star", "1", "--s", "1", "--model", "gw")
    b = run_json(capsys, "elastic", *MOMENT_ARGS, "--E-star", "2", "--s", "1", "--model", "gw")
    assert b["pressure"][0] == pytest.approx(2 * a["pressure"][0], rel=1e-14)
    assert b["area_fraction"] == a["area_fraction"]


def test_elastic_text_table(capsys):
    code, out, err = run(capsys, "elastic", *MOMENT_ARGS, "--E-star", E_STAR, "--s", "1", "2",
                         "--model", "gw", "--hertz", "paper")
    assert code == 0 and err == ""
    lines = out.splitlines()
    assert "model=gw" in lines[0]
    assert lines[1].split() == ["s", "h", "area_fraction", "pressure", "stiffness", "k_Tx", "k_Ty"]
    rows = [list(map(float, line.split())) for line in lines[3:5]]
    assert [r[0] for r in rows] == [1.0, 2.0]
    assert rows[0][2] == pytest.approx(0.051497, rel=1e-4)


def test_choices_match_library():
    from roughcontact.contact import closures, elastic, elastoplastic
    from roughcontact.integrals import rules

    assert cli.MODELS == elastic.MODELS
    assert cli.HERTZ == elastic.HERTZ == elastoplastic.HERTZ
    assert cli.METHODS == elastic.METHODS == elastoplastic.METHODS
    assert set(cli.ACCURACIES) == set(rules.PRESETS) == set(rules.ELASTOPLASTIC_PRESETS)
    assert cli.CLOSURES == tuple(closures.CLOSURES)
    assert cli.EP_DEFAULTS == closures.DEFAULTS


# ---------------------------------------------------------------------------------------
# elastoplastic
# ---------------------------------------------------------------------------------------
EP = ["elastoplastic", *MOMENT_ARGS, "--E-star", E_STAR]


def test_elastoplastic_json_matches_library(capsys):
    """--psi: closure yield-from-psi (psi is kept); the numbers are the library's."""
    from roughcontact import SpectralMoments
    from roughcontact.contact.closures import resolve_material
    from roughcontact.contact.elastoplastic import elastoplastic_contact

    s = ["0.0", "1.0", "2.5"]
    d = run_json(capsys, *EP, "--psi", "0.5", "--s", *s, "--accuracy", "plot")
    for key in ("s", "area_fraction", "pressure", "stiffness", "plastic_area_fraction",
                "elastoplastic_area_fraction", "psi", "units"):
        assert key in d, key
    assert d["closure"] == "yield-from-psi" and d["psi"] == pytest.approx(0.5, rel=1e-14)
    surface = SpectralMoments(**M)
    lib = elastoplastic_contact(surface, [float(x) for x in s],
                                resolve_material(surface, E_star=float(E_STAR), psi=0.5), accuracy="plot")
    for key in ("area_fraction", "pressure", "stiffness", "plastic_area_fraction", "elastoplastic_area_fraction"):
        assert d[key] == [float(x) for x in getattr(lib, key)], key
    assert all(0 < a < 1 for a in d["area_fraction"])
    assert d["material"]["H"] == pytest.approx(d["material"]["Y"] / 0.354, rel=1e-15)
    assert "E*" in d["units"]["pressure"] and d["units"]["psi"] == "1"


def test_elastoplastic_yield_strength_gives_physical_psi(capsys):
    """--yield-strength: the material is physical and ψ an output (0.88 for the caption's
    E* = 1.14e5, Y = 2070 N/mm² on the Table 1 surface, docs/independent-studies.md)."""
    d = run_json(capsys, *EP, "--yield-strength", "2070", "--s", "1", "--accuracy", "plot")
    assert d["closure"] == "material"
    assert d["psi"] == pytest.approx(0.88, abs=0.005)
    assert d["material"]["Y"] == 2070.0 and d["material"]["yield_coefficient"] == 1.62
    assert (d["material"]["c_h"], d["material"]["wp_over_wc"]) == (0.967, 45.0)


def test_elastoplastic_overrides_and_paper_literal(capsys):
    d = run_json(capsys, *EP, "--psi", "0.35", "--yield-strength", "2070", "--closure", "paper-literal",
                 "--s", "1", "--c-h", "0.9", "--wp-over-wc", "30", "--accuracy", "plot")
    assert d["closure"] == "paper-literal" and d["psi"] == pytest.approx(0.35, rel=1e-14)
    assert (d["material"]["c_h"], d["material"]["wp_over_wc"]) == (0.9, 30.0)
    assert d["material"]["H"] == pytest.approx(2070 / 0.354, rel=1e-15)


def test_elastoplastic_text_table(capsys):
    code, out, err = run(capsys, *EP, "--psi", "0.5", "--s", "1", "2", "--accuracy", "plot")
    assert code == 0 and err == ""
    lines = out.splitlines()
    assert "psi=0.5" in lines[0] and "closure=yield-from-psi" in lines[0]
    assert lines[1].split() == ["s", "h", "area_fraction", "pressure", "stiffness",
                                "elastic_area_fraction", "elastoplastic_area_fraction",
                                "plastic_area_fraction", "elastic_pressure",
                                "elastoplastic_pressure", "plastic_pressure", "k_Tx", "k_Ty"]


def test_version(capsys):
    code, out, err = run(capsys, "--version")
    assert code == 0
    assert out.strip() == f"roughcontact {__version__}"


def test_nonfinite_result_is_exit_1(capsys, monkeypatch):
    monkeypatch.setattr(cli.contact, "_run_surface", lambda args: {"mu": float("nan"), "units": {}})
    code, out, err = run(capsys, "surface", *MOMENT_ARGS, "--json")
    assert code == 1 and out == ""
    assert err.startswith("roughcontact: error:") and "mu" in err and len(err.splitlines()) == 1


# ---------------------------------------------------------------------------------------
# bad input: exit 2, exactly one stderr line, no traceback
# ---------------------------------------------------------------------------------------
def _moments(**override):
    m = {**{k: repr(v) for k, v in M.items()}, **override}
    return [a for k, v in m.items() for a in (f"--{k}", v)]


ELASTIC = ["--E-star", E_STAR, "--s", "1"]
BAD = {
    "non-numeric moment": ["surface", *_moments(m00="abc")],
    "negative moment": ["surface", *_moments(m20="-8e-5")],
    "zero moment": ["surface", *_moments(m40="0")],
    "infinite moment": ["surface", *_moments(m04="inf")],
    "mu <= 0": ["surface", *_moments(m04="1e-5")],
    "missing moment": ["surface", *_moments()[2:]],
    "no command": [],
    "unknown command": ["plastic", *_moments()],
    "unknown option": ["surface", *_moments(), "--frobnicate"],
    "non-finite s": ["elastic", *_moments(), "--E-star", E_STAR, "--s", "nan"],
    "infinite s": ["elastic", *_moments(), "--E-star", E_STAR, "--s", "1", "1e999"],
    "non-numeric s": ["elastic", *_moments(), "--E-star", E_STAR, "--s", "one"],
    "missing s": ["elastic", *_moments(), "--E-star", E_STAR],
    "zero E*": ["elastic", *_moments(), "--E-star", "0", "--s", "1"],
    "negative E*": ["elastic", *_moments(), "--E-star", "-2", "--s", "1"],
    "non-numeric E*": ["elastic", *_moments(), "--E-star", "steel", "--s", "1"],
    "unknown model": ["elastic", *_moments(), *ELASTIC, "--model", "jkr"],
    "unknown hertz": ["elastic", *_moments(), *ELASTIC, "--hertz", "approx"],
    "unknown method": ["elastic", *_moments(), *ELASTIC, "--method", "fast"],
    "unknown accuracy": ["elastic", *_moments(), *ELASTIC, "--accuracy", "best"],
    "elastic mu <= 0": ["elastic", *_moments(m40="1e-7"), *ELASTIC],
    "ep neither psi nor Y": ["elastoplastic", *_moments(), *ELASTIC],
    "ep psi and Y, no closure": ["elastoplastic", *_moments(), *ELASTIC, "--psi", "0.5", "--yield-strength", "2070"],
    "ep negative psi": ["elastoplastic", *_moments(), *ELASTIC, "--psi", "-0.5"],
    "ep zero Y": ["elastoplastic", *_moments(), *ELASTIC, "--yield-strength", "0"],
    "ep closure needs psi": ["elastoplastic", *_moments(), *ELASTIC, "--yield-strength", "2070",
                             "--closure", "yield-from-psi"],
    "ep unknown closure": ["elastoplastic", *_moments(), *ELASTIC, "--psi", "0.5", "--closure", "gw"],
    "ep wp/wc <= 1": ["elastoplastic", *_moments(), *ELASTIC, "--psi", "0.5", "--wp-over-wc", "1"],
    "ep nan c_h": ["elastoplastic", *_moments(), *ELASTIC, "--psi", "0.5", "--c-h", "nan"],
    "ep non-finite s": ["elastoplastic", *_moments(), "--E-star", E_STAR, "--s", "inf", "--psi", "0.5"],
    # issue #12: finite inputs whose products overflow (were tracebacks, exit 1)
    "ep psi 1e-160": ["elastoplastic", *_moments(), *ELASTIC, "--psi", "1e-160"],
    "ep Y 1e200": ["elastoplastic", *_moments(), *ELASTIC, "--yield-strength", "1e200"],
    "moments 1e-300": ["surface", *_moments(**{k: "1e-300" for k in M})],
    "moments 1e300": ["surface", *_moments(**{k: "1e300" for k in M})],
    # issue #12: no meaning (A/A0 > 1), now refused; negative values reach the library
    "A/A0 above 1": ["elastic", *_moments(), "--E-star", E_STAR, "--s", "-5"],
    "negative exponent moment": ["surface", *_moments(m04="-1.04e-4")],
}


MINDLIN_BAD = {
    "zero ratio": ["mindlin", "--b2-over-a2", "0", "--nu", "0.25"],
    "negative ratio": ["mindlin", "--b2-over-a2", "1", "-1", "--nu", "0.25"],
    "nan ratio": ["mindlin", "--b2-over-a2", "nan", "--nu", "0.25"],
    "infinite ratio": ["mindlin", "--b2-over-a2", "1e999", "--nu", "0.25"],
    "non-numeric ratio": ["mindlin", "--b2-over-a2", "round", "--nu", "0.25"],
    "missing ratio": ["mindlin", "--nu", "0.25"],
    "missing nu": ["mindlin", "--b2-over-a2", "1"],
    "nu above 0.5": ["mindlin", "--b2-over-a2", "1", "--nu", "0.7"],
    "nu -1": ["mindlin", "--b2-over-a2", "1", "--nu", "-1"],
    "nan nu": ["mindlin", "--b2-over-a2", "1", "--nu", "nan"],
    "moments not accepted": ["mindlin", "--b2-over-a2", "1", "--nu", "0.25", "--m00", "1"],
}


@pytest.mark.parametrize("argv", [*BAD.values(), *MINDLIN_BAD.values()], ids=[*BAD, *MINDLIN_BAD])
def test_bad_input_exit_2_one_line(capsys, argv):
    code, out, err = run(capsys, *argv)
    assert code == 2
    assert out == ""
    assert len(err.splitlines()) == 1, err
    assert err.startswith("roughcontact: error: ")
    assert "Traceback" not in err and "usage:" not in err


def test_negative_numbers_are_values_not_options(capsys):
    """argparse read "--s -1e6" / "--m04 -1.04e-4" as options ("expected one argument")."""
    _, _, err = run(capsys, "surface", *_moments(m04="-1.04e-4"))
    assert "m04 must be positive" in err
    _, _, err = run(capsys, "elastic", *_moments(), "--E-star", E_STAR, "--s", "-1e6")
    assert "A/A0" in err and "> 1" in err
    data = run_json(capsys, "elastic", *_moments(), "--E-star", E_STAR, "--s", "3", "1e0")
    assert data["s"] == [3.0, 1.0]


def test_every_subcommand_parser_inherits_the_negative_number_rule():
    """Fixed once in the parser class: a subcommand added later (here a new one) inherits it."""
    parser = cli.build_parser()
    sub = next(a for a in parser._actions if isinstance(a, cli.argparse._SubParsersAction))
    assert all(type(p) is cli._Parser for p in sub.choices.values())
    new = sub.add_parser("later")
    new.add_argument("--x", type=float)
    assert new.parse_args(["--x", "-2.5e-3"]).x == -2.5e-3


def test_results_outside_the_model_range_warn_in_one_line(capsys):
    code, out, err = run(capsys, "elastic", *_moments(), "--E-star", E_STAR, "--s", "-1", "--json")
    assert code == 0 and json.loads(out)["area_fraction"][0] == pytest.approx(0.4215, rel=1e-3)
    lines = err.splitlines()
    assert len(lines) == 2 and all(line.startswith("roughcontact: warning: ") for line in lines)
    assert "exceeds 0.1" in lines[0] and "s = -1 < 0" in lines[1]


def test_library_messages_pass_through(capsys):
    _, _, err = run(capsys, "surface", *_moments(m04="1e-5"))
    assert "mu = 1 - 1/alpha1 - 1/alpha2 > 0" in err
    _, _, err = run(capsys, "elastic", *_moments(), "--E-star", "0", "--s", "1")
    assert "E_star must be finite and positive" in err


# ---------------------------------------------------------------------------------------
# the installed console script
# ---------------------------------------------------------------------------------------
def _script() -> str:
    local = Path(sys.executable).parent / "roughcontact"
    found = str(local) if local.exists() else shutil.which("roughcontact")
    if found is None:
        pytest.skip("console script 'roughcontact' not installed (pip install -e .)")
    return found


def test_console_script():
    exe = _script()
    ok = subprocess.run([exe, "surface", *MOMENT_ARGS, "--json"], capture_output=True, text=True,
                        timeout=120)
    assert ok.returncode == 0, ok.stderr
    assert json.loads(ok.stdout)["alpha1"] == pytest.approx(10.15625, rel=1e-14)

    bad = subprocess.run([exe, "surface", *_moments(m00="-1")], capture_output=True, text=True,
                         timeout=120)
    assert bad.returncode == 2 and bad.stdout == ""
    assert bad.stderr.splitlines() == ["roughcontact: error: m00 must be positive, got -1.0"]


# ---------------------------------------------------------------------------------------
# mindlin (k_N/k_T, corrected eq. (96); Table 3)
# ---------------------------------------------------------------------------------------
def _table3_rows():
    import yaml

    table = yaml.safe_load((Path(__file__).parents[2] / "config" / "paper_values.yaml").read_text())["table3"]
    columns = [table["columns"][c]["kn_over_kt"] for c in table["columns"]]  # nu = 0, 1/4, 1/2
    # reading of the first column: "10.E-03" -> B^2/A^2 = 1e-3 (see tests/interface/test_tangential.py)
    return [(10.0 ** int(label.split("E")[1]), [col[i] for col in columns]) for i, label in enumerate(table["rows"])]


@pytest.mark.parametrize("nu,col", [("0", 0), ("0.25", 1), ("0.5", 2)])
def test_mindlin_json_reproduces_table3(capsys, nu, col):
    rows = _table3_rows()
    d = run_json(capsys, "mindlin", "--b2-over-a2", *(repr(r) for r, _ in rows), "--nu", nu)
    assert set(d) >= {"b2_over_a2", "kn_over_kt"}
    assert d["b2_over_a2"] == [r for r, _ in rows]
    assert len(d["kn_over_kt"]) == len(rows)
    for value, (r, printed) in zip(d["kn_over_kt"], rows):
        assert value == pytest.approx(float(printed[col]), rel=1e-5), r


def test_mindlin_circle_closed_form(capsys):
    d = run_json(capsys, "mindlin", "--b2-over-a2", "1", "--nu", "0.3")
    assert d["kn_over_kt"] == [pytest.approx((2 - 0.3) / (2 * (1 - 0.3)), rel=1e-15)]


def test_mindlin_text_table(capsys):
    code, out, err = run(capsys, "mindlin", "--b2-over-a2", "0.001", "1000", "--nu", "0.25")
    assert code == 0 and err == ""
    lines = out.splitlines()
    assert "nu=0.25" in lines[0]
    assert lines[1].split() == ["b2_over_a2", "kn_over_kt"]
    rows = [list(map(float, line.split())) for line in lines[2:]]
    assert [r[0] for r in rows] == [0.001, 1000.0]
    assert rows[0][1] == pytest.approx(1.06874, rel=1e-5)  # Table 3
    assert rows[1][1] == pytest.approx(1.26459, rel=1e-5)




def test_mindlin_library_messages_pass_through(capsys):
    _, _, err = run(capsys, "mindlin", "--b2-over-a2", "0", "--nu", "0.25")
    assert "b2_over_a2 = B^2/A^2 must be finite and > 0" in err
    _, _, err = run(capsys, "mindlin", "--b2-over-a2", "1", "--nu", "0.6")
    assert "-1 < nu <= 0.5" in err


# ---------------------------------------------------------------------------------------
# load control, h, E* from two bodies, two rough surfaces
# ---------------------------------------------------------------------------------------
def test_pressure_option_inverts_the_s_option(capsys):
    a = run_json(capsys, "elastic", *MOMENT_ARGS, "--E-star", E_STAR, "--s", "1", "2.5")
    b = run_json(capsys, "elastic", *MOMENT_ARGS, "--E-star", E_STAR, "--pressure",
                 *map(repr, a["pressure"]))
    assert b["s"] == pytest.approx(a["s"], abs=1e-9)
    assert b["h"] == pytest.approx([s * M["m00"] ** 0.5 for s in a["s"]], abs=1e-9)
    assert b["pressure_requested"] == a["pressure"]
    assert b["stiffness"] == pytest.approx(a["stiffness"], rel=1e-8)
    assert a["pressure_requested"] is None and a["warnings"] == [] and a["units"]["h"].startswith("L")
    c = run_json(capsys, "elastic", *MOMENT_ARGS, "--E-star", E_STAR, "--h", *map(repr, a["h"]))
    assert c["s"] == pytest.approx(a["s"], rel=1e-15)


def test_elastoplastic_pressure_text_shows_every_field(capsys):
    code, out, err = run(capsys, *EP, "--psi", "0.5", "--pressure", "10", "100")
    assert code == 0 and err == ""
    d = run_json(capsys, *EP, "--psi", "0.5", "--pressure", "10", "100")
    for key, value in d.items():
        if key == "units":
            continue
        assert key in out, key
    assert d["pressure"] == pytest.approx([10.0, 100.0], rel=1e-10)


def test_modulus_from_two_bodies_and_two_surfaces(capsys):
    """E* of (42) from (E1, nu1, E2, nu2) and the sum of the moments of two surfaces."""
    E1, nu1, E2, nu2 = 2.1e5, 0.3, 1.1e5, 0.34
    E = 1 / ((1 - nu1**2) / E1 + (1 - nu2**2) / E2)
    a = run_json(capsys, "elastic", *MOMENT_ARGS, "--E1", str(E1), "--nu1", str(nu1), "--E2", str(E2),
                 "--nu2", str(nu2), "--s", "2")
    assert a["E_star"] == pytest.approx(E, rel=1e-15)
    b = run_json(capsys, "elastic", *MOMENT_ARGS, "--E-star", E_STAR, "--s", "2",
                 "--second-surface", *map(repr, M.values()))
    assert b["moments"] == {k: 2 * v for k, v in M.items()}
    code, out, err = run(capsys, "elastic", *MOMENT_ARGS, "--E1", "2e5", "--s", "2")
    assert code == 2 and "--nu1" in err
    code, out, err = run(capsys, "elastic", *MOMENT_ARGS, "--E-star", E_STAR, "--nu1", "0.3", "--s", "2")
    assert code == 2 and "not with --E-star" in err and len(err.splitlines()) == 1


def test_cli_relays_warnings(capsys, monkeypatch):
    import warnings

    from roughcontact.contact import elastic as elastic_module

    real = elastic_module.elastic_contact

    def warns(*args, **kwargs):
        warnings.warn("A/A0 above 10 % (test)", UserWarning)
        return real(*args, **kwargs)

    monkeypatch.setattr("roughcontact.contact.elastic_contact", warns)
    d = run_json(capsys, "elastic", *MOMENT_ARGS, "--E-star", E_STAR, "--s", "1")
    assert d["warnings"] == ["UserWarning: A/A0 above 10 % (test)"]
    code, out, err = run(capsys, "elastic", *MOMENT_ARGS, "--E-star", E_STAR, "--s", "1")
    assert "warning: UserWarning: A/A0 above 10 % (test)" in out


def test_validity_warnings_reach_the_json_and_stderr_at_a_height(capsys):
    """--h (a length) below the mean plane: the library's ModelValidityWarning is in the JSON list
    ``warnings`` and on stderr, once each (issue 14's relay and issue 12's one-line print)."""
    code, out, err = run(capsys, "elastic", *_moments(), "--E-star", E_STAR, "--h", "-0.25", "--json")
    payload = json.loads(out)
    assert code == 0 and payload["s"][0] == pytest.approx(-1.0)  # sigma = sqrt(m00) = 0.25 µm
    assert len(payload["warnings"]) == 2
    assert all(m.startswith("ModelValidityWarning: ") for m in payload["warnings"])
    assert len(err.splitlines()) == 2 and "s = -1 < 0" in err
