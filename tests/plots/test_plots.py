"""roughcontact.plots and `roughcontact plot`: the figures are drawn with their data, nothing is
clipped, and without matplotlib they fail with one line (the library does not need it)."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from roughcontact import cli
from roughcontact.plots import contact_curves, moments_against_scale, save_figure
from roughcontact.plots.style import texts_outside


def result(scale=1.0):
    s = np.linspace(0.5, 3.0, 6)
    p = scale * 100 * np.exp(-2 * s)
    return {"s": list(s), "area_fraction": list(0.1 * np.exp(-1.5 * s)), "pressure": list(p),
            "stiffness": list(2 * p), "k_Tx": list(1.6 * p), "k_Ty": list(1.8 * p), "length_unit": "um"}


def test_contact_curves_draw_every_result_and_quantity():
    fig = contact_curves([result(), result(2.0)], labels=["a", "b"], stress_unit="N/mm^2", length_unit="um")
    axes = fig.axes
    assert len(axes) == 4 and texts_outside(fig) == []
    # the k_T panel: k_Tx and k_Ty of both results, with their data
    lines = axes[3].get_lines()
    assert len(lines) == 4
    np.testing.assert_allclose(lines[0].get_ydata(), result()["k_Tx"])
    assert axes[2].get_ylabel() == "normal stiffness $K_N/A_0$ [N/(mm²·µm)]"
    by_pressure = contact_curves([result()], x="pressure", stress_unit="N/mm^2")
    assert len(by_pressure.axes) == 3 and by_pressure.axes[0].get_xscale() == "log"
    with pytest.raises(ValueError, match="x must be one of"):
        contact_curves([result()], x="time")


def test_moments_against_scale_and_one_file_per_suffix(tmp_path):
    scales = [{"factor": k, "dx": 0.25 * k, "dy": 0.25 * k, "m00": 0.01, "m20": 1e-3 / k, "m02": 1e-2,
               "m40": 3e-4 / k, "m04": 3e-2 / k} for k in (1, 2, 4)]
    fig = moments_against_scale({"m00": 0.01, "unit": "um", "scales": scales,
                                 "uncertainty": {"m20": 1e-5, "m02": 1e-4, "m40": 1e-5, "m04": 1e-3}})
    assert texts_outside(fig) == [] and len(fig.axes) == 2
    assert save_figure(fig, tmp_path / "f.pdf").read_bytes()[:4] == b"%PDF"
    assert not (tmp_path / "f.png").exists()
    with pytest.raises(ValueError, match="suffix"):
        save_figure(fig, tmp_path / "f.jpg")


def test_the_plot_command(capsys, tmp_path):
    for name, scale in (("a", 1.0), ("b", 3.0)):
        (tmp_path / f"{name}.json").write_text(json.dumps(result(scale)))
    code = cli.main(["plot", str(tmp_path / "a.json"), str(tmp_path / "b.json"), "-o", str(tmp_path / "c.png"),
                     "--stress-unit", "N/mm^2"])
    out, err = capsys.readouterr()
    assert code == 0 and "wrote" in out and (tmp_path / "c.png").read_bytes()[:4] == b"\x89PNG"
    (tmp_path / "bad.json").write_text(json.dumps({"m00": 1}))
    code = cli.main(["plot", str(tmp_path / "bad.json"), "-o", str(tmp_path / "d.png")])
    out, err = capsys.readouterr()
    assert code == 2 and len(err.splitlines()) == 1 and "not a contact result" in err


def test_without_matplotlib_one_line():
    """matplotlib hidden (as if not installed): the library and `roughcontact.plots` import, a figure
    fails with one line naming the install, and so do `plot` and `moments --plot`."""
    code = (
        "import sys, json, tempfile, pathlib\n"
        "class Hide:\n"
        "    def find_spec(self, name, path=None, target=None):\n"
        "        if name.split('.')[0] == 'matplotlib':\n"
        "            raise ModuleNotFoundError(name)\n"
        "sys.meta_path.insert(0, Hide())\n"
        "import numpy as np, roughcontact.plots as plots, roughcontact.cli as cli\n"
        "try:\n"
        "    plots.contact_curves([{'s': [1], 'area_fraction': [1], 'pressure': [1], 'stiffness': [1]}])\n"
        "except ImportError as e:\n"
        "    print('IMPORTERROR', e)\n"
        "d = pathlib.Path(tempfile.mkdtemp())\n"
        "(d / 'r.json').write_text(json.dumps({'s': [1], 'area_fraction': [1], 'pressure': [1], 'stiffness': [1]}))\n"
        "np.save(d / 'z.npy', np.random.default_rng(0).random((32, 32)))\n"
        "print('PLOT', cli.main(['plot', str(d / 'r.json'), '-o', str(d / 'f.png')]))\n"
        "print('MOMENTS', cli.main(['moments', str(d / 'z.npy'), '--dx', '1', '--plot', str(d / 'm.png')]))\n"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert "IMPORTERROR figures need matplotlib" in r.stdout and "pip install '.[workflow]'" in r.stdout
    assert "PLOT 2" in r.stdout and "MOMENTS 2" in r.stdout, r.stdout + r.stderr
    errors = [line for line in r.stderr.splitlines() if line.startswith("roughcontact: error")]
    assert len(errors) == 2 and all("matplotlib" in e for e in errors) and "Traceback" not in r.stderr
