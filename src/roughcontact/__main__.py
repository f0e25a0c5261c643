"""``python -m roughcontact``: the command line (:mod:`roughcontact.cli`)."""

from .cli import main

raise SystemExit(main())
