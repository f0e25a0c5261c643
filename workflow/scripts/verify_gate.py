"""The verdict gate of `snakemake verify`: print the summary; fail on any regression
(a check expected "reproduced" in config/expected_verdicts.yaml that is not)."""

import json
import sys
from pathlib import Path

from roughcontact import io


def message(summary):
    lines = [
        f"verification {'PASSED' if summary['passed'] else 'FAILED'}: {summary['checks']} checks, "
        f"{summary['reproduced']} reproduced, {summary['not_reproduced']} not reproduced "
        f"({summary['known']} documented), {summary['improved']} improved, "
        f"{summary['regressions']} regressions"
    ]
    for scene, c in summary["by_scene"].items():
        lines.append(
            f"  {scene}: {c['reproduced']}/{c['checks']} reproduced, {c['known']} documented, "
            f"{c['improved']} improved, {c['regressions']} regressions"
        )
    lines += [f"  REGRESSION {i}" for i in summary["regression_ids"]]
    lines += [f"  improved (update config/expected_verdicts.yaml): {i}" for i in summary["improved_ids"]]
    lines.append("  report: paper_figures/VERIFICATION.md")
    return "\n".join(lines)


def run(summary_path, output, log):
    summary = json.loads(Path(summary_path).read_text())
    text = message(summary)
    print(text, file=sys.stderr)  # the terminal (Snakemake shows a script's stderr)
    with io.log_to(log) as logger:
        logger.info("\n%s", text)
        if not summary["passed"]:
            raise SystemExit(f"{summary['regressions']} verification regression(s): see paper_figures/VERIFICATION.md")
        io.write_text(output, text + "\n")


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.input.summary, sm.output[0], sm.log[0])
