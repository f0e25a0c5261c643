"""Figures of contact results, in the project's one style (:mod:`.style`), for users and for the
paper's figures (``roughcontact.paper.plots`` draws with the same style)."""
