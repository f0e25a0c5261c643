"""The verdict gate of `snakemake verify`: print the summary; fail on any regression
(a check expected "reproduced" in config/expected_verdicts.yaml that is not, a documented
discrepancy outside its band, a scene with fewer checks than expected_checks declares) and on
any check improved beyond its documented expectation (unexplained until the file says why)."""

import json
import sys
from pathlib import Path

from roughcontact import io
from roughcontact.paper import verify


def message(summary):
    lines = [
        f"verification {'PASSED' if summary['passed'] else 'FAILED'}: {summary['checks']} checks, "
        f"{summary['reproduced']} reproduced, {summary['not_reproduced']} not reproduced "
        f"({summary['known']} documented), {summary.get('within_residual', 0)} within a documented residual, "
        f"{summary['improved']} improved, "
        f"{summary['regressions']} regressions"
    ]
    for scene, c in summary["by_scene"].items():
        lines.append(
            f"  {scene}: {c['reproduced']}/{c['checks']} reproduced, {c['known']} documented, "
            f"{c['improved']} improved, {c['regressions']} regressions"
        )
    coverage = summary.get("coverage") or {}
    lines += [f"  MISSING CHECKS {m['scene']}: {m['found']} of {m['expected']} declared" for m in coverage.get("missing", [])]
    lines += [f"  {m['scene']} ({m.get('checks', '?')} checks) {verify.skipped_text(m['requires'], m.get('install', ''))}"
              for m in coverage.get("skipped", [])]
    lines += [f"  more checks than declared in {m['scene']}: {m['found']} of {m['expected']} (update expected_checks)"
              for m in coverage.get("unexpected", [])]
    details = summary.get("regression_details") or {}
    lines += [f"  REGRESSION {i}" + (f": {details[i]}" if details.get(i) else "") for i in summary["regression_ids"]]
    lines += [f"  IMPROVED beyond expectation (update config/expected_verdicts.yaml with the reason): {i}"
              for i in summary["improved_ids"]]
    lines.append("  report: paper_figures/VERIFICATION.md")
    return "\n".join(lines)


def run(summary_path, output, log):
    summary = json.loads(Path(summary_path).read_text())
    text = message(summary)
    print(text, file=sys.stderr)  # the terminal (Snakemake shows a script's stderr)
    with io.log_to(log) as logger:
        logger.info("\n%s", text)
        if not summary["passed"]:
            missing = len((summary.get("coverage") or {}).get("missing", []))
            raise SystemExit(f"{summary['regressions']} verification regression(s), {summary['improved']} check(s) "
                             f"improved beyond their documented expectation, {missing} scene(s) missing "
                             f"checks, {summary['checks']} checks: see paper_figures/VERIFICATION.md")
        io.write_text(output, text + "\n")


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.input.summary, sm.output[0], sm.log[0])
