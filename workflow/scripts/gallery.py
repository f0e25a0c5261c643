"""The figure gallery paper_figures/index.html (rule gallery): thin, reads config/gallery.yaml,
the figures' check rows and numbers, renders with roughcontact.paper.gallery."""

import csv
import json
from pathlib import Path

import yaml

from roughcontact import io
from roughcontact.paper import gallery


def run(entries_path, checks_dir, geometry_dir, summary_path, output, log):
    with io.log_to(log) as logger:
        entries = yaml.safe_load(Path(entries_path).read_text())["figures"]
        checks, verdicts = {}, {}
        for name, entry in entries.items():
            rows = []
            for f in entry.get("checks", []):
                with open(Path(checks_dir) / f"{f}.checks.csv", newline="", encoding="utf-8") as fh:
                    rows += list(csv.DictReader(fh))
            if "match" in entry:
                rows = [r for r in rows if any(m in r["id"] for m in entry["match"])]
            checks[name] = rows
            if "geometry" in entry:
                numbers = json.loads((Path(geometry_dir) / f"{entry['geometry']}.json").read_text())
                verdicts[name] = gallery.geometry_verdict(entry["geometry"], numbers)
            elif entry.get("checks"):
                verdicts[name] = gallery.verdict_of(rows)
            else:
                verdicts[name] = ("none", "— (a drawing; no numerical claim)")
            logger.info("%s: %s", name, verdicts[name][1])
        prov = f"roughcontact {io.provenance_attrs(timestamp=False)['roughcontact_version']}, commit {io.git_commit()[:12]}"
        summary = json.loads(Path(summary_path).read_text())
        io.write_text(output, gallery.render(entries, checks, verdicts, prov, summary=summary,
                                             report="VERIFICATION.html"))


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.input.entries, "results/verify", "results/geometry", sm.input.summary, sm.output[0], sm.log[0])
