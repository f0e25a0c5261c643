"""The decks and law files shipped with the project (roughcontact/examples/decks/) are what the
examples' generators write, read cleanly, and mesh to the paper's contact points."""

from __future__ import annotations

import pytest

from roughcontact.examples import shipped
from roughcontact.examples.punch import summary
from roughcontact.fe.deck import read_deck
from roughcontact.fe.deck_mesh import deck_mesh
from roughcontact.fe.laws import read_law_file


def test_shipped_files_are_the_generators_output():
    files = shipped.shipped_files()
    on_disk = {p.name for p in shipped.DECKS.iterdir() if p.suffix in (".inp", ".yaml")}
    assert on_disk == set(files), "run `python -m roughcontact.examples.shipped`"
    for name, text in files.items():
        assert (shipped.DECKS / name).read_text() == text, f"{name} differs: run `python -m roughcontact.examples.shipped`"


@pytest.mark.parametrize("deck, family, points", [("punch.inp", "quadratic", 81), ("punch-fig19.inp", "cubic", 100),
                                                  ("beam.inp", "cubic", 76 * 4)])
def test_shipped_decks_read_and_mesh(deck, family, points):
    d = read_deck(shipped.DECKS / deck)
    assert d.contact_pairs[0].interaction == "ROUGH" and any("ignored" in n for n in d.notes)
    assert summary(deck_mesh(d, family).mesh)["contact_points"] == points


def test_shipped_laws_read():
    for path in sorted(shipped.DECKS.glob("*.yaml")):
        law = read_law_file(path)
        assert law.length_unit == "mm" and set(law.interactions) == {"ROUGH"}, path.name
        assert law.interactions["ROUGH"].moments_unit == "um"
