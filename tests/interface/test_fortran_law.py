"""The Fortran interface law (interface/fortran/*.f90 + interface.fortran_export, docs/fortran-law.md)
against the Python/numba law it ports (interface.friction.update), through a gfortran harness.

Issue 30's acceptance: along loading, slip along x and along y (the two lay directions), reversal,
unloading, opening and reclosing, the Fortran tractions, tangent, state and status agree with
friction.update step by step within 1e-10 relative (each quantity against its largest magnitude
along the path), and the Fortran tangent agrees with central differences of the Fortran
tractions within 1e-6. The Abaqus wrapper UINTER is called with its documented signature along
the same paths (Abaqus conventions: RDISP(1) > 0 penetration, STRESS(1) pressure positive in
compression, DDSDDR = dSTRESS/dDRDISP in deck units) and compared with the same Python law.

The laws come from law files (docs/examples/block.yaml: the orthotropic hardening friction of
docs/own-model.md; variants: isotropic Coulomb, the elasto-plastic law with an associated
anisotropic potential and the secant form) built exactly as ``fe run`` builds them
(fe.laws.InteractionLaw.material). Without gfortran the harness tests skip with one line
(tested by hiding it from PATH). The harness build is cached under the temp directory, keyed
by the hash of its sources.
"""

import hashlib
import math
import os
import shutil
import subprocess
import tempfile
from pathlib import Path

import numpy as np
import pytest

from roughcontact.asperity import effective_modulus
from roughcontact.fe.laws import law_file_from_dict, read_law_file
from roughcontact.interface import friction
from roughcontact.interface.fortran_export import DATA_FILE, SOURCES, fortran_source, law_data_module

ROOT = Path(__file__).resolve().parents[2]
DRIVER = Path(__file__).parent / "fortran_harness" / "driver.f90"
#: issue 30's acceptance: Fortran vs Python law, relative
RTOL = 1e-10
#: issue 30's acceptance: the Fortran tangent vs central differences of the Fortran tractions
FD_RTOL = 1e-6
#: E* of docs/examples/block.inp: its *ELASTIC cards STEEL 210000, 0.3 and ALUMINIUM 70000, 0.33, eq. (42)
BLOCK_E_STAR = effective_modulus(210000.0, 0.3, 70000.0, 0.33)
NO_GFORTRAN = "gfortran not on PATH: install it (apt-get install gfortran) to run the Fortran harness"


def _gfortran(path=None) -> str:
    exe = shutil.which("gfortran", path=path)
    if exe is None:
        pytest.skip(NO_GFORTRAN)
    return exe


def test_the_harness_skips_in_one_line_without_gfortran(hide_programs):
    env = hide_programs("gfortran")
    with pytest.raises(pytest.skip.Exception) as info:
        _gfortran(env["PATH"])
    assert info.value.msg == NO_GFORTRAN and "\n" not in info.value.msg


# ---------------------------------------------------------------------------------------------
# laws and the harness build
# ---------------------------------------------------------------------------------------------
def _block_dict():
    import yaml

    return yaml.safe_load((ROOT / "docs/examples/block.yaml").read_text())


def _variant(**changes):
    data = _block_dict()
    data["interactions"]["ROUGH"].update(changes)
    return data


LAW_FILES = {
    "block-orthotropic": _block_dict,
    "coulomb": lambda: _variant(friction={"coulomb": {"mu": 0.3, "kt_over_kn": 0.8}}),
    "elastoplastic-associated-secant": lambda: _variant(
        law="elastoplastic", psi=1.0, tangential_form="secant",
        friction={"orthotropic": {"mu_m": [0.5, 0.3], "mu_o": [0.5, 0.8], "n_x": 275, "n_y": 100, "k": 1.0,
                                  "kt_over_kn": [0.7, 1.0]}}),
}


class Harness:
    """A compiled driver for one law: runs the ``points``, ``path`` and ``uinter`` modes."""

    def __init__(self, exe, law, model, form, per):
        self.exe, self.law, self.model, self.form, self.per = exe, law, model, form, per

    def run(self, lines):
        out = subprocess.run([str(self.exe)], input="\n".join(lines) + "\n", capture_output=True, text=True,
                             timeout=60)
        assert out.returncode == 0, out.stdout + out.stderr
        return np.array([[float(v) for v in line.split()] for line in out.stdout.splitlines()])


def _numbers(values):
    return " ".join(repr(float(v)) for v in np.ravel(values))


def _build(data_text: str) -> Path:
    """The driver compiled with the law's data module, cached in the temp directory by hash."""
    compiler = _gfortran()
    texts = [fortran_source(SOURCES[0]), data_text, fortran_source(SOURCES[1]), DRIVER.read_text()]
    key = hashlib.sha256("\0".join(texts).encode()).hexdigest()[:16]
    cache = Path(tempfile.gettempdir()) / "roughcontact-fortran-harness" / key
    exe = cache / "driver"
    if exe.exists():
        return exe
    work = Path(tempfile.mkdtemp(prefix="build-", dir=cache.parent if cache.parent.exists() else None))
    names = [SOURCES[0], DATA_FILE, SOURCES[1], "driver.f90"]
    for name, text in zip(names, texts):
        (work / name).write_text(text)
    subprocess.run([compiler, "-O2", "-std=f2008", "-Wall", "-Werror", "-Wno-compare-reals",
                    "-Wno-unused-dummy-argument", *names, "-o", "driver"], cwd=work, check=True,
                   capture_output=True, timeout=300)
    cache.parent.mkdir(parents=True, exist_ok=True)
    try:
        os.replace(work, cache)  # atomic: a parallel build of the same key leaves one
    except OSError:
        shutil.rmtree(work, ignore_errors=True)
    return exe


@pytest.fixture(scope="module", params=sorted(LAW_FILES))
def harness(request):
    _gfortran()
    laws = law_file_from_dict(LAW_FILES[request.param](), "law file", ROOT / "docs/examples")
    law = laws.interactions["ROUGH"]
    material = law.material(laws.length_unit, BLOCK_E_STAR, None)
    text = law_data_module(material.normal, material.model, interaction="ROUGH", law_per_deck=material.length_per_mm,
                           lay_direction=law.lay_direction, tangential_form=material.tangential_form)
    exe = _build(text)
    return Harness(exe, material.normal.extrapolated(), material.model, material.tangential_form,
                   material.length_per_mm)


# ---------------------------------------------------------------------------------------------
# the paths
# ---------------------------------------------------------------------------------------------
def _path(law, model):
    """Increments (du_Tx, du_Ty, du_N) [law length]: loading to 1 N/mm², slip along x, along y,
    reversal, slip with loading, unloading with slip, opening, reclosing. Tangential steps in
    units of the slip onset δ = μ p/k_T at the loaded state."""
    u1 = law.h_ref - law.table.separation_at(1.0)
    p1, k1 = law.normal(u1)
    mu = min(model.mu_m_x, model.mu_m_y) * min(model.mu_o_x, model.mu_o_y) if hasattr(model, "mu_m_x") else (
        model.mu_m * model.mu_o)
    dx = mu * p1 / (law.kT_over_kN_x * k1)
    dy = mu * p1 / (law.kT_over_kN_y * k1)
    u_open = law.u_open
    steps = [(0.0, 0.0, u1 / 8)] * 8
    steps += [(0.29 * dx, 0.0, 0.0)] * 12  # stick, then slip along x (the lay); 0.29: no step ends on the limit
    steps += [(0.0, 0.29 * dy, 0.0)] * 12  # along y (across the lay)
    steps += [(-0.4 * dx, -0.2 * dy, 0.0)] * 12  # reversal
    steps += [(0.1 * dx, 0.1 * dy, u1 / 20)] * 6  # slip while loading
    steps += [(0.05 * dx, -0.05 * dy, -0.1 * u1)] * 8  # unloading with slip
    steps += [(0.2 * dx, 0.1 * dy, (u_open - 0.5 * abs(u_open) - 0.5 * u1) / 4)] * 4  # opening
    steps += [(0.1 * dx, 0.0, (0.5 * u1 - u_open + 0.5 * abs(u_open)) / 4)] * 4  # reclosing
    return np.array(steps)


def _python_path(law, model, steps, form):
    s = friction.initial_state((), k_N=law)
    out = []
    for du in steps:
        r = friction.update(model, s, du, law, tangential=form)
        out.append((int(r.status), r.state, r.D))
        s = r.state
    return out


def _params(model):
    par = np.zeros(7)
    par[:model.params().size] = model.params()
    code = {friction.OrthotropicHardening: 2, friction.IsotropicHardening: 1}.get(type(model), 0)
    return code, par


FORMS = {name: i for i, name in enumerate(friction.TANGENTIAL_FORMS)}


def _fortran_path(h, model, steps, form, law=None, constant=None):
    """The driver's ``path`` mode: the Fortran state carried from step to step."""
    code, par = _params(model)
    if constant is None:
        stiff, tab, s0 = (h.law.kT_over_kN_x, h.law.kT_over_kN_y, 1.0), 1, friction.initial_state((), k_N=h.law)
    else:
        stiff, tab, s0 = constant, 0, friction.initial_state((), u_N=0.0)
    head = f"{code} {_numbers(par)} {_numbers(stiff)} {FORMS[form]} {tab} 1e-12 {_numbers(s0)}"
    rows = h.run(["path", head, str(len(steps)), *(_numbers(du) for du in steps)])
    return rows[:, 0].astype(int), rows[:, 1:10], rows[:, 10:19].reshape(-1, 3, 3)


def _relative_error(fortran, python):
    """max over the path of |Fortran − Python| / (largest |Python| of that quantity); a quantity
    that is 0 all along must be exactly 0 (∞ otherwise)."""
    scale = np.abs(python).max(axis=0)
    err = np.abs(fortran - python).max(axis=0)
    rel = np.where(scale > 0, err / np.where(scale > 0, scale, 1.0), np.where(err > 0, np.inf, 0.0))
    return float(rel.max())


def _compare(status, state, D, expected):
    st_p = np.array([e[0] for e in expected])
    S_p = np.array([e[1] for e in expected])
    D_p = np.array([e[2] for e in expected])
    np.testing.assert_array_equal(status, st_p)
    return _relative_error(state, S_p), _relative_error(D.reshape(len(D), -1), D_p.reshape(len(D_p), -1))


def test_the_path_visits_stick_slip_and_open(harness):
    steps = _path(harness.law, harness.model)
    status = [e[0] for e in _python_path(harness.law, harness.model, steps, harness.form)]
    assert {friction.OPEN, friction.SLIP, friction.STICK} <= set(status) or (
        isinstance(harness.model, friction.Frictionless))


def test_fortran_law_agrees_with_python_along_the_path(harness):
    steps = _path(harness.law, harness.model)
    expected = _python_path(harness.law, harness.model, steps, harness.form)
    err_state, err_D = _compare(*_fortran_path(harness, harness.model, steps, harness.form), expected)
    assert err_state <= RTOL and err_D <= RTOL, (err_state, err_D)


@pytest.mark.parametrize("form", friction.TANGENTIAL_FORMS)
def test_isotropic_hardening_and_every_tangential_form(harness, form):
    """Models the law files do not write (isotropic slip hardening, 8.2; the orthotropic law
    with k = -0.5) through the same table, in every tangential form."""
    for model in (friction.IsotropicHardening(mu_m=0.4, mu_o=0.5, n=0.3),
                  friction.OrthotropicHardening(0.45, 0.3, 0.6, 0.9, 0.2, 0.05, k=-0.5)):
        steps = _path(harness.law, model)
        expected = _python_path(harness.law, model, steps, form)
        err_state, err_D = _compare(*_fortran_path(harness, model, steps, form), expected)
        assert err_state <= RTOL and err_D <= RTOL, (type(model).__name__, err_state, err_D)


def test_constant_stiffness_law_and_the_models_without_limit(harness):
    """The empty table (constant k_N, k_Tx, k_Ty, eq. (117)) and Frictionless / NoSlip."""
    k = (0.7e3, 1.0e3, 1.0e3)
    u1 = 1e-3
    steps = np.array([(0, 0, u1 / 4)] * 4 + [(2e-4, 0, 0)] * 6 + [(0, 3e-4, 0)] * 6 + [(-4e-4, -1e-4, -u1 / 5)] * 8)
    for model in (friction.IsotropicHardening(0.3), friction.OrthotropicHardening(0.5, 0.3, k=1.0),
                  friction.Frictionless(), friction.NoSlip()):
        s = friction.initial_state(())
        expected = []
        for du in steps:
            r = friction.update(model, s, du, k[2], k[0], k[1])
            expected.append((int(r.status), r.state, r.D))
            s = r.state
        err_state, err_D = _compare(*_fortran_path(harness, model, steps, "incremental-end", constant=k), expected)
        assert err_state <= RTOL and err_D <= RTOL, (type(model).__name__, err_state, err_D)


def test_fortran_tangent_is_the_derivative_of_the_fortran_tractions(harness):
    steps = _path(harness.law, harness.model)
    status, state, _ = _fortran_path(harness, harness.model, steps, harness.form)
    starts = np.vstack([friction.initial_state((), k_N=harness.law), state[:-1]])
    code, par = _params(harness.model)
    head = f"{code} {_numbers(par)} {_numbers((harness.law.kT_over_kN_x, harness.law.kT_over_kN_y, 1.0))} " \
           f"{FORMS[harness.form]} 1 1e-12"
    scale = np.abs(steps).max(axis=0)  # a length per component
    rows, picked = [], [i for i in range(len(steps)) if status[i] != friction.OPEN]
    for i in picked:
        for j in range(3):
            for sign in (1.0, -1.0):
                du = steps[i].copy()
                du[j] += sign * 1e-6 * scale[j]
                rows.append(f"{head} {_numbers(starts[i])} {_numbers(du)}")
        rows.append(f"{head} {_numbers(starts[i])} {_numbers(steps[i])}")
    out = harness.run(["points", str(len(rows)), *rows]).reshape(len(picked), 7, -1)
    checked = {friction.STICK: 0, friction.SLIP: 0}
    worst = 0.0
    for block in out:
        st = block[:, 0].astype(int)
        if len(set(st)) > 1:
            continue  # a kink (stick/slip or open/closed) inside ±h: no derivative
        D = block[6, 10:19].reshape(3, 3)
        fd = np.column_stack([(block[2 * j, 1:4] - block[2 * j + 1, 1:4]) / (2e-6 * scale[j]) for j in range(3)])
        worst = max(worst, np.abs(fd - D).max() / np.abs(D).max())
        checked[st[0]] += 1
    assert worst <= FD_RTOL, worst
    assert checked[friction.STICK] >= 5 and checked[friction.SLIP] >= 10, checked


# ---------------------------------------------------------------------------------------------
# the Abaqus wrapper
# ---------------------------------------------------------------------------------------------
def _local_frame(theta):
    """ALOCALDIR: normal z, slip directions t1 at θ from the deck's x (the lay), t2 = n × t1."""
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[0.0, 0.0, 1.0], [c, s, 0.0], [-s, c, 0.0]]).T  # columns n, t1, t2


@pytest.mark.parametrize("theta_deg", [0.0, 30.0, -120.0])
def test_uinter_agrees_with_python_in_abaqus_conventions(harness, theta_deg):
    """UINTER along the path: local (t1, t2) at θ from the lay; in the lay frame the increments
    are Qᵀ Δu_loc with Q = [[cos θ, sin θ], [−sin θ, cos θ]] (the lay's components in t1, t2)."""
    theta = math.radians(theta_deg)
    c, s = math.cos(theta), math.sin(theta)
    Q = np.array([[c, s], [-s, c]])  # local (t1, t2) components of the lay frame's (x, y) axes, column-wise
    steps = _path(harness.law, harness.model)
    expected = _python_path(harness.law, harness.model, steps, harness.form)
    per = harness.per
    rdisp = np.zeros(3)
    lines = ["uinter", f"{_numbers(_local_frame(theta).T.ravel())} 3 {_numbers(np.zeros(9))}", str(len(steps))]
    for du in steps:
        drdisp = np.concatenate([[du[2]], Q @ du[:2]]) / per  # (penetration, slip t1, slip t2) [deck length]
        rdisp = rdisp + drdisp
        lines.append(f"{_numbers(rdisp)} {_numbers(drdisp)}")
    rows = harness.run(lines)
    lopen, lstate, pnewdt, sfd = rows[:, 0], rows[:, 1], rows[:, 2], rows[:, 3]
    stress, ddsddr, statev = rows[:, 4:7], rows[:, 7:16].reshape(-1, 3, 3), rows[:, 16:25]
    status = np.array([e[0] for e in expected])
    S_p = np.array([e[1] for e in expected])
    # the expected values in Abaqus's order (normal, t1, t2): P picks (N, x, y), R rotates x, y
    R = np.eye(3)
    R[1:, 1:] = Q
    P = np.array([[0, 0, 1], [1, 0, 0], [0, 1, 0]], dtype=float)
    T = R @ P
    stress_p = S_p[:, :3] @ T.T
    ddsddr_p = np.array([T @ e[2] @ T.T * per for e in expected])
    dissipation = np.diff(np.concatenate([[0.0], S_p[:, friction.DISSIPATION]])) / per
    np.testing.assert_array_equal(lstate, status)
    np.testing.assert_array_equal(lopen, (status != friction.OPEN).astype(float))
    np.testing.assert_array_equal(pnewdt, 1.0)
    errors = {"stress": _relative_error(stress, stress_p), "ddsddr": _relative_error(
        ddsddr.reshape(len(rows), -1), ddsddr_p.reshape(len(rows), -1)), "statev": _relative_error(statev, S_p),
        "sfd": _relative_error(sfd[:, None], dissipation[:, None])}
    assert max(errors.values()) <= RTOL, errors


# ---------------------------------------------------------------------------------------------
# the export (no compiler needed)
# ---------------------------------------------------------------------------------------------
def test_data_module_holds_the_engine_table_to_the_bit():
    laws = read_law_file(ROOT / "docs/examples/block.yaml")
    law = laws.interactions["ROUGH"]
    material = law.material(laws.length_unit, BLOCK_E_STAR)
    text = law_data_module(material.normal, material.model, interaction="rough", law_per_deck=1000.0)
    tab, h_ref, _ = material.normal.extrapolated().kernel_data()
    rows = []
    lines = text.splitlines()
    for i, line in enumerate(lines):
        if line.lstrip().startswith("data rc_tab("):
            joined = line.split("/")[1].rstrip(" &") + lines[i + 1].split("/")[0]
            rows.append([float(v.replace("d", "e")) for v in joined.split(",")])
    np.testing.assert_array_equal(np.array(rows), tab)  # 17 digits read back to the same doubles
    assert "rc_h_ref = " + f"{h_ref:.17e}".replace("e", "d") in text and "rc_interaction = 'ROUGH'" in text
    assert max(map(len, lines)) <= 132  # free-form line length


def test_export_law_command_writes_the_three_sources(tmp_path):
    from roughcontact.cli import main

    out = tmp_path / "law"
    assert main(["export-law", str(ROOT / "docs/examples/block.yaml"), "--E1", "210000", "--nu1", "0.3", "--E2",
                 "70000", "--nu2", "0.33", "-o", str(out)]) == 0
    assert sorted(p.name for p in out.iterdir()) == sorted([*SOURCES, DATA_FILE])
    assert f"{BLOCK_E_STAR!r}" in (out / DATA_FILE).read_text()
    assert (out / "uinter.f90").read_text() == fortran_source("uinter.f90")


def test_export_law_needs_an_effective_modulus(tmp_path, capsys):
    from roughcontact.cli import main

    assert main(["export-law", str(ROOT / "docs/examples/block.yaml"), "-o", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err
    assert "gives no E_star" in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "x").exists()
