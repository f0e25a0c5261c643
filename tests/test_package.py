"""The package's front door: the top-level names the README uses, ``python -m roughcontact``."""

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
