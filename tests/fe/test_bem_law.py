"""A BEM law in LAW.yaml (roughcontact.fe.bem_law; issue 32): ``normal: {table: FILE}`` routes the
ladder's p_N(u_N), k_N(u_N) into ``roughcontact fe run`` of docs/own-model.md's deck.

* The routing, checked for real: a table made of samples of the statistical law itself gives
  the displacements of the moments' law to the tables' own errors, and a table of a different
  law (pressures × 1.5) gives different ones.
* A genuine BEM ladder (ContactMechanics on a 128² band-limited Table 1 surface) runs the deck
  with its friction step and Mindlin's k_T (skipped without the extra [bem]).
* Every bad BEM law is one line naming the law file and the key; ``kt_over_kn: mindlin``."""

from __future__ import annotations

import json
import math
import shutil
import time
import warnings
from pathlib import Path

import numpy as np
import pytest
import yaml

from roughcontact import cli
from roughcontact.asperity import effective_modulus
from roughcontact.bem.law_table import BEMLawSamples, write_law_table
from roughcontact.contact import elastic_contact
from roughcontact.contact.at_pressure import contact_at_pressure
from roughcontact.fe.bem_law import moments_in
from roughcontact.fe.deck_run import run_deck_file
from roughcontact.fe.laws import LawError, law_file_from_dict, mindlin_poisson, read_law_file
from roughcontact.interface import mindlin_kT_over_kN
from roughcontact.interface.tangential import representative_aspect
from roughcontact.statistics.surface import SpectralMoments

EXAMPLES = Path(__file__).resolve().parents[2] / "docs" / "examples"
TABLE1 = SpectralMoments(m00=0.0625, m20=8.0e-5, m02=8.0e-4, m40=1.04e-6, m04=1.04e-4)
STEEL, ALUMINIUM = (2.1e5, 0.3), (7.0e4, 0.33)  # block.inp's *ELASTIC [N/mm²]
E_DECK = effective_modulus(*STEEL, *ALUMINIUM)  # eq. (42)
#: rtol of the moments' law table in a deck run (NormalLawTable.build's default)
MOMENTS_TABLE_RTOL = 1e-6


def _statistical_samples(per_decade=5, lo=1e-4, hi=100.0, scale=1.0) -> BEMLawSamples:
    """The statistical elastic law (53), (55) at the deck's E*, as if it were a BEM ladder
    (pressures and stiffness × ``scale``: another law)."""
    target = np.logspace(math.log10(lo), math.log10(hi), round(per_decade * math.log10(hi / lo)) + 1)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        s = np.asarray(contact_at_pressure(TABLE1, target, E_star=E_DECK, model="bgk", hertz="exact",
                                           validity="off").s)
        c = elastic_contact(TABLE1, s, E_DECK, model="bgk", hertz="exact", validity="off")
    return BEMLawSamples(pressure=scale * np.asarray(c.pressure), mean_gap=s * TABLE1.height_std,
                         stiffness=scale * np.asarray(c.stiffness), area_fraction=np.asarray(c.area_fraction),
                         length_unit="um", E_star=E_DECK, periodic=True, moments=TABLE1, lay_angle_deg=0.0,
                         source={"file": "the statistical law (53), (55)"}, solver={},
                         stiffness_method="exact, eq. (55)")


def _law_yaml(table: str, **changes) -> dict:
    law = yaml.safe_load((EXAMPLES / "block.yaml").read_text())
    body = law["interactions"]["ROUGH"]
    del body["law"], body["moments"]
    body["normal"] = {"table": table}
    body.update(changes)
    return law


def _fe_run(*argv) -> dict:
    """``roughcontact fe run ... --json`` in this process."""
    import contextlib
    import io

    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        code = cli.main([str(a) for a in ("fe", "run", *argv, "--json", "--quiet")])
    assert code == 0
    return json.loads(out.getvalue())


@pytest.fixture(scope="module")
def deck(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("bemlaw")
    for f in EXAMPLES.iterdir():
        shutil.copy(f, tmp / f.name)
    write_law_table(tmp / "statistical.json", _statistical_samples())
    write_law_table(tmp / "other.json", _statistical_samples(scale=1.5))
    (tmp / "statistical.yaml").write_text(yaml.safe_dump(_law_yaml("statistical.json")))
    (tmp / "other.yaml").write_text(yaml.safe_dump(_law_yaml("other.json")))
    return tmp


def _closures(run) -> np.ndarray:
    return np.array([s["interface"]["u_N_um"] for s in run["steps"]])


def test_a_table_of_the_statistical_law_gives_the_moments_laws_displacements(deck):
    """Both steps of block.inp: u_N and every node's displacement agree to the closure the two
    tables' stated pressure errors allow, δu_N = (ε_BEM + ε_moments) p_N/k_N; the table of another
    law moves them by far more (the table is what the run uses)."""
    law = read_law_file(deck / "statistical.yaml").interactions["ROUGH"]
    assert law.law == "bem" and law.table.law.level == "bem" and law.moments == TABLE1 and law.E_star == E_DECK
    t0 = time.perf_counter()
    bem = _fe_run(deck / "block.inp", "--interface", deck / "statistical.yaml")
    seconds = time.perf_counter() - t0
    ref = _fe_run(deck / "block.inp", "--interface", deck / "block.yaml")
    other = _fe_run(deck / "block.inp", "--interface", deck / "other.yaml")
    table = law.table.law
    p = np.array([s["interface"]["p_N"] for s in ref["steps"]])
    k = np.vectorize(lambda x: table.evaluate(table.separation_at(x))[1])(p)
    bound_um = (table.rtol + MOMENTS_TABLE_RTOL) * np.max(p / k)
    diff_um = np.max(np.abs(_closures(bem) - _closures(ref)))
    assert diff_um <= bound_um, (diff_um, bound_um)  # measured 7e-10 µm within 2e-7 µm
    for a, b in zip(bem["steps"], ref["steps"]):
        for name, values in a["node_sets"].items():
            du_mm = np.max(np.abs(np.array(values["u"]) - np.array(b["node_sets"][name]["u"])))
            assert du_mm <= bound_um * 1e-3, (name, du_mm, bound_um)
    assert np.max(np.abs(_closures(other) - _closures(ref))) > 100 * bound_um
    assert bem["E_star"]["ROUGH"] == pytest.approx(E_DECK, rel=1e-12) and seconds < 60


def test_the_bem_law_file_reads_and_writes(deck):
    f = read_law_file(deck / "statistical.yaml")
    again = law_file_from_dict(yaml.safe_load(f.to_yaml()), "again.yaml", deck)
    assert again == f and again.interactions["ROUGH"].table.file == "statistical.json"
    # moments given in the law file (in nm) are the law's, converted to the table's unit
    nm = {**{m: v for m, v in moments_in(TABLE1, "um", "nm").as_dict().items()}, "unit": "nm"}
    law = law_file_from_dict(_law_yaml("statistical.json", moments=nm), "law.yaml", deck).interactions["ROUGH"]
    assert law.moments_unit == "um"
    for m in ("m00", "m20", "m02", "m40", "m04"):
        assert getattr(law.moments, m) == pytest.approx(getattr(TABLE1, m), rel=1e-12)


@pytest.mark.parametrize("changes, key, message", [
    ({"law": "elastic"}, "ROUGH", "give law: elastic|elastoplastic .* or normal: {table: FILE}"),
    ({"normal": {"table": "missing.json"}}, "ROUGH.normal.table", "BEM law table .*missing.json"),
    ({"normal": {"table": 3}}, "ROUGH.normal.table", "must be the path of a BEM law table"),
    ({"normal": {"table": "statistical.json", "scan": "x"}}, "ROUGH.normal", "unknown key 'scan'"),
    ({"E_star": 70000.0}, "ROUGH.E_star", "differs from the BEM table's E"),
    ({"psi": 0.5}, "ROUGH", "psi, yield_strength and pressure_range belong to law"),
    ({"pressure_range": [1e-3, 10]}, "ROUGH", "a BEM table's range is its ladder's"),
])
def test_bad_bem_laws_name_the_key(deck, changes, key, message):
    with pytest.raises(LawError, match=message) as err:
        law_file_from_dict(_law_yaml("statistical.json", **changes), "law.yaml", deck)
    text = str(err.value)
    assert text.startswith(f"law.yaml: interactions.{key}") and "\n" not in text


def test_the_seating_pressure_lies_in_the_ladder(deck):
    write_law_table(deck / "short.json", _statistical_samples(lo=0.01, hi=10.0))
    (deck / "short.yaml").write_text(yaml.safe_dump(_law_yaml("short.json")))  # seating 1e-3 < 0.01
    with pytest.raises(LawError, match=r"seating_pressure 0.001 lies outside the BEM table's pressures 0.01"):
        run_deck_file(deck / "block.inp", deck / "short.yaml")


def test_mindlin_poisson_closed_forms():
    """Equal materials: ν itself (the paper's (96)); a rigid partner (G₂ → ∞): the soft body's ν;
    steel on aluminium: between the two, nearer aluminium's (the softer body's compliance)."""
    assert mindlin_poisson(2.1e5, 0.3, 2.1e5, 0.3) == pytest.approx(0.3, rel=1e-15)
    assert mindlin_poisson(7e4, 0.33, 1e300, 0.1) == pytest.approx(0.33, rel=1e-12)
    nu = mindlin_poisson(*STEEL, *ALUMINIUM)
    g1, g2 = STEEL[0] / (2 * 1.3), ALUMINIUM[0] / (2 * 1.33)
    assert nu == pytest.approx((0.3 / g1 + 0.33 / g2) / (1 / g1 + 1 / g2), rel=1e-15) and 0.32 < nu < 0.33


def test_kt_over_kn_mindlin(deck):
    """kt_over_kn: mindlin is Mindlin's ratio (96) of the representative summit ellipse with the
    bodies' ν (mindlin_poisson); without ν it is refused; it round-trips through the file."""
    friction_ = {"coulomb": {"mu": 0.3, "kt_over_kn": "mindlin"}}
    f = law_file_from_dict(_law_yaml("statistical.json", friction=friction_), "law.yaml", deck)
    law = f.interactions["ROUGH"]
    assert law_file_from_dict(yaml.safe_load(f.to_yaml()), "law.yaml", deck) == f
    nu = mindlin_poisson(*STEEL, *ALUMINIUM)
    m = law.material("mm", E_DECK, nu)
    expected = mindlin_kT_over_kN(representative_aspect(TABLE1), nu)
    assert (m.normal.kT_over_kN_x, m.normal.kT_over_kN_y) == pytest.approx(expected, rel=1e-15)
    with pytest.raises(LawError, match="kt_over_kn: mindlin needs the bodies' Poisson ratio"):
        law.material("mm", E_DECK)


def test_a_genuine_bem_ladder_runs_the_deck_with_friction(deck):
    """ContactMechanics on a 128² band-limited surface with Table 1's moments, 0.1 … 20 N/mm² at
    4 pressures a decade, K from bem.compare.ladder_stiffness: the deck runs both steps, the
    second (unloading to 1 N/mm²) slips at some points, k_T = Mindlin's ratio × k_N(BEM)."""
    pytest.importorskip("ContactMechanics")
    from roughcontact.bem import BandLimitedSurface
    from roughcontact.bem.compare import ladder_stiffness
    from roughcontact.bem.solver import solve_pressures

    surface = BandLimitedSurface.design(TABLE1)
    n = 128
    dx, dy = surface.spacing(n)
    t0 = time.perf_counter()
    r = solve_pressures(surface.heights(n, 0), dx, dy, E_DECK, np.geomspace(0.1, 20.0, 10))
    bem_seconds = time.perf_counter() - t0
    samples = BEMLawSamples(pressure=r.pressure, mean_gap=r.mean_gap, stiffness=ladder_stiffness(r.pressure, r.mean_gap),
                            area_fraction=r.area_fraction, length_unit="um", E_star=E_DECK, periodic=True,
                            moments=TABLE1, lay_angle_deg=0.0,
                            source={"file": "BandLimitedSurface(table1) seed 0", "shape": [n, n], "dx": dx, "dy": dy},
                            solver=r.settings.as_dict(), stiffness_method="bem.compare.ladder_stiffness")
    write_law_table(deck / "bem.json", samples)
    law = _law_yaml("bem.json", seating_pressure=0.2)
    law["interactions"]["ROUGH"]["friction"]["orthotropic"]["kt_over_kn"] = "mindlin"
    (deck / "bem.yaml").write_text(yaml.safe_dump(law))
    t0 = time.perf_counter()
    run = _fe_run(deck / "block.inp", "--interface", deck / "bem.yaml")
    fe_seconds = time.perf_counter() - t0
    for step in run["steps"]:
        for name in ("u_N_um", "p_N", "t_1", "t_2", "slip_1_um", "slip_2_um"):
            assert np.all(np.isfinite(step["interface"][name])), name
        for values in step["node_sets"].values():
            assert np.all(np.isfinite(values["u"]))
    first, second = run["steps"]
    assert np.allclose(first["interface"]["p_N"], 5.0, rtol=0.2)  # the top's 5 N/mm², redistributed
    assert "slip" in second["interface"]["status"] and max(map(abs, second["interface"]["t_1"])) > 0.0
    m = read_law_file(deck / "bem.yaml").interactions["ROUGH"].material("mm", E_DECK, mindlin_poisson(*STEEL, *ALUMINIUM))
    table = m.normal.table
    assert table.level == "bem" and table.p_max == pytest.approx(20.0, rel=1e-12)
    assert (m.normal.kT_over_kN_x, m.normal.kT_over_kN_y) == pytest.approx(
        mindlin_kT_over_kN(representative_aspect(TABLE1), mindlin_poisson(*STEEL, *ALUMINIUM)), rel=1e-15)
    print(f"\nBEM 128², 10 pressures: {bem_seconds:.2f} s; fe run: {fe_seconds:.2f} s; stated error of the "
          f"BEM law: p {table.max_error_pressure:.3g}, k {table.max_error_stiffness:.3g}")
