"""The package's front door: the top-level names the library's examples use (docs/usage.md), ``python -m roughcontact``."""

import subprocess
import sys

import roughcontact


def test_top_level_exports_what_the_readme_uses():
    from roughcontact import (AsperityMaterial, InterfaceLaw, NormalLawTable, SpectralMoments, elastic_contact,
                              elastoplastic_contact, friction, resolve_material)
    from roughcontact.contact import elastic_contact as from_contact
    from roughcontact.interface import NormalLawTable as from_interface

    assert elastic_contact is from_contact and NormalLawTable is from_interface
    assert callable(elastoplastic_contact) and callable(resolve_material) and callable(friction.update)
    assert SpectralMoments and AsperityMaterial and InterfaceLaw
    assert set(roughcontact.__all__) <= set(dir(roughcontact))


def test_unknown_top_level_name_is_an_attribute_error():
    try:
        roughcontact.no_such_name  # noqa: B018
    except AttributeError as err:
        assert "no_such_name" in str(err)
    else:
        raise AssertionError("no AttributeError")


def test_python_dash_m_runs_the_cli():
    r = subprocess.run([sys.executable, "-m", "roughcontact", "mindlin", "--b2-over-a2", "1", "--nu", "0.25", "--json"],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert '"kn_over_kt"' in r.stdout


def test_the_library_needs_no_workflow_package():
    """`pip install .` (no extras) has no snakemake, matplotlib, pyyaml, jsonschema:
    the library and the CLI work with them absent (only roughcontact.paper, the reproduction,
    uses them). They are hidden by a meta-path finder, as if not installed."""
    code = (
        "import sys\n"
        "class Hide:\n"
        "    def find_spec(self, name, path=None, target=None):\n"
        "        if name.split('.')[0] in ('snakemake', 'matplotlib', 'yaml', 'jsonschema'):\n"
        "            raise ModuleNotFoundError(name)\n"
        "sys.meta_path.insert(0, Hide())\n"
        "import roughcontact, roughcontact.contact, roughcontact.interface, roughcontact.examples.beam, roughcontact.examples.punch\n"
        "import roughcontact.fe.vtu, roughcontact.io, roughcontact.cli, roughcontact.statistics.synthetic\n"
        "from roughcontact import elastic_contact, SpectralMoments\n"
        "s = SpectralMoments(m00=0.0625, m20=8e-5, m02=8e-4, m40=1.04e-6, m04=1.04e-4)\n"
        "print(float(elastic_contact(s, [1.0], 1.14e5).pressure[0]))\n"
        "sys.exit(roughcontact.cli.main(['mindlin', '--b2-over-a2', '1', '--nu', '0.25']))\n"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert float(r.stdout.split()[0]) > 0 and "kn_over_kt" in r.stdout
