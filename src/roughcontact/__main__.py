"""``python -m roughcontact``: the command line (:mod:`roughcontact.cli`)."""

from .cli import entry_point

raise SystemExit(entry_point())
