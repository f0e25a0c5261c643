"""The paper's examples, as data and as input decks (not the library).

* :mod:`.section9`: the numbers of section 9 and its captions (surfaces, materials, loads,
  the friction cases of Fig. 18);
* :mod:`.beam`: example 9.1, the beam on a rigid base, as a CalculiX/Abaqus deck and laws run by
  the engine's deck reader (``roughcontact fe beam``);
* :mod:`.punch_geometry`, :mod:`.punch`: example 9.2, the punch on an elastic foundation,
  likewise (``roughcontact fe punch``);
* ``decks/``: the decks and law files of both examples with the paper's defaults
  (``roughcontact fe run`` runs them; tests check that they equal what the generators write).

The engine (:mod:`roughcontact.fe`) knows none of this.
"""
