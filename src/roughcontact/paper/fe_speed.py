"""Speed and size of the FE runs of section 9 (beam and punch): per run the dofs, interface
points, Newton iterations per load level and solve time; per workflow job the wall time, CPU time
and peak memory (Snakemake's benchmark). Rendering only (no I/O)."""

from __future__ import annotations

from typing import Any, Mapping, Sequence

__all__ = ["run_row", "render_benchmark_markdown"]


def run_row(name: str, attrs: Mapping[str, Any], iterations: Sequence[int]) -> dict:
    """One run's row from its dataset attributes (dofs, interface_points, seconds) and Newton
    iterations per load level."""
    its = [int(i) for i in iterations]
    return {"run": name, "dofs": int(attrs["dofs"]), "interface_points": int(attrs["interface_points"]),
            "iterations": its, "iterations_total": sum(its), "seconds": float(attrs["seconds"])}


def render_benchmark_markdown(examples: Mapping[str, Mapping[str, Any]], jobs: Sequence[Mapping[str, Any]],
                              machine: Mapping[str, Any]) -> str:
    """``examples``: title → {"rows": run rows (:func:`run_row`), "main": names of the runs the
    paper's table needs, "goal": the per-case goal [s], "what": what one job solves}; ``jobs``:
    {job, example, runs, wall_s, cpu_s, max_rss_mb}. The per-run tables, then the job table and
    one summary line per example (the job table comes last: the verification report quotes it)."""
    lines = ["# Section 9: speed and size of the FE runs", "",
             f"Measured by the workflow on {machine.get('cpu', '?')}, {machine.get('cores', '?')} cores, load "
             f"average at the report {machine.get('loadavg', '?')}; jobs run two at a time on two cores. "
             "*solve*: mesh, assembly and every load level of one run (Newton, condensed bulk, one BLAS thread)."]
    for title, ex in examples.items():
        lines += ["", f"## {title}", "", "| run | dofs | interface points | Newton iterations (per load level) | solve [s] |",
                  "|---|---:|---:|---|---:|"]
        for r in sorted(ex["rows"], key=lambda r: r["run"]):
            lines.append(f"| {r['run']} | {r['dofs']} | {r['interface_points']} | {r['iterations_total']} "
                         f"({' '.join(map(str, r['iterations']))}) | {r['seconds']:.2f} |")
    lines += ["", "## Jobs", "", "| job | example | runs | wall [s] | CPU [s] | peak RSS [MB] |", "|---|---|---:|---:|---:|---:|"]
    for j in sorted(jobs, key=lambda j: (j["example"], j["job"])):
        lines.append(f"| {j['job']} | {j['example']} | {j['runs']} | {j['wall_s']:.1f} | {j['cpu_s']:.1f} "
                     f"| {j['max_rss_mb']:.0f} |")
    lines.append("")
    for title, ex in examples.items():
        main = [r for r in ex["rows"] if r["run"] in set(ex["main"])]
        own = [j for j in jobs if j["example"] == title]
        if not main:
            continue
        worst = max(main, key=lambda r: r["seconds"])
        lines.append(f"- {title}: the paper's runs take at most {worst['seconds']:.2f} s of solve per case "
                     f"({worst['run']}, goal ≤ {ex['goal']:g} s); its {len(own)} jobs ({ex['what']}) "
                     f"{sum(j['wall_s'] for j in own):.0f} s of wall time, {sum(j['cpu_s'] for j in own):.0f} s of "
                     f"CPU, at most {max((j['max_rss_mb'] for j in own), default=0):.0f} MB.")
    lines.append(f"- All FE jobs: {sum(j['wall_s'] for j in jobs):.0f} s of wall time, "
                 f"{sum(j['cpu_s'] for j in jobs):.0f} s of CPU.")
    return "\n".join(lines) + "\n"
