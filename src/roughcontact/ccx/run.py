"""``roughcontact ccx run MODEL.inp --interface LAW.yaml``: the deck with its law through the built
CalculiX (:mod:`.build`), rewritten by :mod:`.deck_rewrite`, read back by :mod:`.results`
(docs/ccx.md).

The job runs in ``keep`` (kept: the rewritten deck ``<model>_ccx.inp`` and ccx's files, to run
again in one's own build) or in a temporary folder removed afterwards; ccx's output goes to
``<model>_ccx.log`` and every increment it starts is a progress line.
"""

from __future__ import annotations

import os
import subprocess
import tempfile
import time
from pathlib import Path

from .. import __version__
from .deck_rewrite import pair_elements, rewrite
from .results import summary

__all__ = ["CCXRunError", "run_deck_in_ccx", "NOTES"]

#: what differs from `fe run` on the same deck, said in every run's notes
NOTES = ("ccx: the interface elements sample the deck's 8-node (C3D20) faces at the engine's points (3 x 3 "
         "Lobatto: the node pairs and the face centre), where the engine's 21-node elements have a node of their own "
         "at the face centre",)


class CCXRunError(RuntimeError):
    """ccx failed or stopped early: the message ends with the tail of its output."""


def _job(exe: Path, name: str, folder: Path, threads: int, timeout: float | None, progress) -> tuple[str, float]:
    env = {**os.environ, "OMP_NUM_THREADS": str(threads), "CCX_NPROC_EQUATION_SOLVER": str(threads),
           "CCX_NPROC_RESULTS": str(threads), "CCX_NPROC_STIFFNESS": str(threads)}
    lines = []
    t0 = time.perf_counter()
    with subprocess.Popen([str(exe), name], cwd=folder, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          env=env) as p:
        try:
            for line in p.stdout:
                lines.append(line)
                text = line.strip()
                if text.startswith(("STEP", "increment", "*ERROR")) and "attempt" not in text:
                    progress(f"ccx: {text}")
                if timeout is not None and time.perf_counter() - t0 > timeout:
                    p.kill()
                    raise CCXRunError(f"ccx did not finish within {timeout:g} s (killed)")
        finally:
            log = "".join(lines)
            (folder / f"{name}.log").write_text(log)
        p.wait()
    seconds = time.perf_counter() - t0
    if p.returncode != 0 or "*ERROR" in log or not (folder / f"{name}.dat").exists():
        tail = "\n".join(log.splitlines()[-12:])
        raise CCXRunError(f"ccx failed on {name}.inp (exit {p.returncode}); its last lines:\n{tail}")
    return log, seconds


def run_deck_in_ccx(deck_path, law_path, executable, *, keep=None, threads: int = 1, timeout: float | None = None,
                    progress=print, build_info: dict | None = None, increments: int | None = None) -> dict:
    """Run a deck and its law file in the built ccx ``executable``; the ``fe run --json``
    contract (:func:`.results.summary`) with ``ccx`` (the build, the job folder, the rewritten
    deck) added. DeckError/LawError for the inputs, CCXRunError for the run."""
    from ..fe.deck import read_deck
    from ..fe.deck_increments import grows, with_incrementation
    from ..fe.deck_mesh import deck_mesh
    from ..fe.deck_run import check_law_file, law_notes
    from ..fe.deck_syntax import read_blocks
    from ..fe.laws import read_law_file

    deck = with_incrementation(read_deck(deck_path), increments)
    laws = read_law_file(law_path)
    check_law_file(deck, laws)
    pairs = pair_elements(deck_mesh(deck, "quadratic"), laws)
    name = f"{Path(deck_path).stem}_ccx"
    header = (f"{name}.inp: {deck_path} with the interface law of {law_path} as user elements,",
              f"written by roughcontact {__version__} (roughcontact ccx run, docs/ccx.md); run it with the ccx",
              "that `roughcontact ccx build` makes (its user elements URCQ8/URCT6 carry the law)")
    text = rewrite(read_blocks(deck_path), pairs, list(deck.nsets), header, deck.steps)
    with tempfile.TemporaryDirectory(prefix="roughcontact-ccx-") as tmp:
        folder = Path(keep) if keep is not None else Path(tmp)
        folder.mkdir(parents=True, exist_ok=True)
        (folder / f"{name}.inp").write_text(text)
        progress(f"ccx run: {folder / (name + '.inp')}: {sum(p.ids.size for p in pairs)} interface elements")
        log, seconds = _job(Path(executable), name, folder, threads, timeout, progress)
        dat = (folder / f"{name}.dat").read_text()
        sta = (folder / f"{name}.sta").read_text() if (folder / f"{name}.sta").exists() else ""
        out = summary(deck, laws, pairs, dat, sta, log, seconds, extra={
            "ccx": {"executable": str(executable), "build": build_info or {}, "threads": threads,
                    "job": str(folder) if keep is not None else None, "deck": f"{name}.inp"}})
    beyond = sum(s["interface"]["status"].count("beyond") for s in out["steps"])
    out["notes"] = [*deck.notes, *law_notes(deck, laws), *NOTES]
    out["notes"] += [f"{s.static_where}: step {s.index}'s increments grow: ccx by its rule (x1.5 after fast "
                     "convergence), the engine by doubling; friction is path-dependent (--increments N fixes both)"
                     for s in deck.steps if grows(s)]
    if beyond:
        out["notes"].append(f"ccx: {beyond} converged point states lie past the heavy end of their tabulated law "
                            "(p_N above the law's p_max): widen its pressure_range")
    return out
