"""The paper's data of section 9 (roughcontact.examples.section9): the Fig. 18 presets, E* of the
beam, and that the engine and the interface law hold none of it."""

import ast
from pathlib import Path

import pytest

import roughcontact
from roughcontact.examples import section9
from roughcontact.examples.section9 import fig18_preset
from roughcontact.interface import friction as fr

UN0 = 0.05  # closure -> p_N = 5 N/mm² with k_N = 100


def test_fig18_presets():
    m, k = fig18_preset("a", 100.0, length_unit="um")
    assert (m.mu_m_x, m.mu_m_y, m.mu_o_x, m.k) == (0.2, 0.2, 1.0, 0.0)
    assert k == dict(k_N=100.0, k_Tx=70.0, k_Ty=70.0) and m.n_x == pytest.approx(0.275)
    m, k = fig18_preset("b", 100.0)
    assert (m.mu_m_x, m.mu_o_y, m.n_y) == (0.5, 0.5, 275.0) and k["k_Ty"] == 70.0
    m, k = fig18_preset("c", 100.0)
    assert k["k_Tx"] == 70.0 and k["k_Ty"] == 100.0
    # case (c): μ's equal, circular potential -> slip coaxial with t despite k_Tx != k_Ty
    m, k = fig18_preset("c", 100.0, length_unit="um")
    r = fr.update(m, fr.initial_state(u_N=UN0, k_N=100.0), [0.1, 0.1, 0.0], **k)
    dup = r.state[fr.UP_X:fr.UP_Y + 1]
    assert fr.slip_angle(dup) == pytest.approx(fr.traction_angle(r.state[:2]), abs=1e-12)
    with pytest.raises(ValueError):
        fig18_preset("d", 100.0)


def test_beam_E_star_is_the_texts():
    assert section9.BEAM_E_STAR == pytest.approx(1.127e5, rel=5e-4)  # E1/(1 - nu1^2), eq. (42)


def test_the_library_holds_no_paper_data():
    """fe/, interface/ and the CLI name none of section 9's caption constants: they live in
    roughcontact.examples (DEVELOPERS_GUIDE: the library is not the paper)."""
    src = Path(roughcontact.__file__).resolve().parent
    banned = {"FIG18_CASES", "fig18_preset", "FIG13_MARKERS", "MESH_CAPTIONS"}
    numbers = {1962.0, 4.9, 1.057e5, 275.0, 0.3125}
    for folder in ("fe", "interface"):
        for path in (src / folder).glob("*.py"):
            tree = ast.parse(path.read_text())
            names = {n.id for n in ast.walk(tree) if isinstance(n, ast.Name)} | {
                n.attr for n in ast.walk(tree) if isinstance(n, ast.Attribute)}
            assert not names & banned, path
            assert not {n.value for n in ast.walk(tree) if isinstance(n, ast.Constant)} & numbers, path
    cli = ast.parse((src / "cli" / "fe.py").read_text())
    assert not {n.value for n in ast.walk(cli) if isinstance(n, ast.Constant)} & numbers
