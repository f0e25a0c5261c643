"""Verification against the paper: computed values vs printed ones under configured tolerances.

Pure functions, no file I/O: the workflow scripts read the inputs and write what these return.

A *check* is one row of ``paper_figures/VERIFICATION.md``: a printed table cell compared with
our value (kind ``cell``), production vs mpmath reference agreement at a table cell
(``numerics``), or a prose claim tested on a figure's data (``claim``). Its verdict is
``"reproduced"``, ``"within a documented residual"`` (a cell that passes only under the wider
``residual`` tolerance its config documents, e.g. Table 2's loads) or ``"not reproduced"``;
comparing the verdict with the expected one kept in ``config/expected_verdicts.yaml`` gives its
status:

=========== =================== ================= =============================================
expected    verdict             status            CI
=========== =================== ================= =============================================
reproduced  reproduced          ``ok``            green
reproduced  other               ``regression``    **red**
residual    residual            ``residual``      green (documented residual)
residual    reproduced          ``improved``      **red** until expected_verdicts.yaml says why
residual    not reproduced      ``regression``    **red**
not repr.   not repr., in band  ``known``         green (documented discrepancy)
not repr.   not repr., off band ``regression``    **red** (the discrepancy changed)
not repr.   other               ``improved``      **red** until expected_verdicts.yaml says why
=========== =================== ================= =============================================

A check better than its documented expectation is a change nobody has explained (a fix, or an
error that happens to move a number towards the paper): like a regression it fails the gate
until its expectation in ``config/expected_verdicts.yaml`` is updated, with the reason.

Every documented discrepancy carries its expected ``band`` [lo, hi] of the check's error (sign
and size, with a margin) or is declared ``qualitative`` (its checks carry no number). The gate
also counts the checks of every scene against ``expected_checks``: a scene with fewer checks
than declared (or none) is a regression, unless it is declared optional (``requires`` a tool
that is not installed: reported as skipped).
"""

from __future__ import annotations

import csv
import fnmatch
import io as _io
import math
from dataclasses import asdict, dataclass, fields, replace
from decimal import Decimal, InvalidOperation
from typing import Any, Iterable, Mapping, Sequence

import numpy as np

__all__ = [
    "REPRODUCED",
    "WITHIN_RESIDUAL",
    "NOT_REPRODUCED",
    "Check",
    "Expectation",
    "relative_error",
    "half_unit_of_last_digit",
    "effective_tolerance",
    "table_cell_checks",
    "numerics_checks",
    "claim_check",
    "load_expectations",
    "expected_for",
    "apply_expectations",
    "regressions",
    "improvements",
    "check_coverage",
    "required_tools",
    "skipped_text",
    "summarize",
    "checks_to_csv",
    "checks_from_csv",
    "format_number",
    "format_percent",
    "format_tolerance",
]

REPRODUCED = "reproduced"
WITHIN_RESIDUAL = "within a documented residual"
NOT_REPRODUCED = "not reproduced"
VERDICTS = (REPRODUCED, WITHIN_RESIDUAL, NOT_REPRODUCED)
STATUS_OK, STATUS_REGRESSION, STATUS_KNOWN, STATUS_IMPROVED = "ok", "regression", "known", "improved"
STATUS_RESIDUAL = "residual"


@dataclass(frozen=True)
class Check:
    """One verification row. ``target`` is the printed value (cell), the reference value
    (numerics) or the claimed limit (claim); ``value`` is ours; ``error`` is the relative
    error (cell, numerics) or the absolute deviation (claim) that ``tolerance`` bounds."""

    id: str
    kind: str
    scene: str
    verdict: str
    detail: str
    description: str = ""
    model: str = ""
    quantity: str = ""
    s: str = ""
    unit: str = ""
    printed: str = ""
    target: float = math.nan
    value: float = math.nan
    error: float = math.nan
    tolerance: float = math.nan
    tolerance_why: str = ""
    residual_tolerance: float = math.nan
    expected: str = ""
    status: str = ""
    reason: str = ""


_FLOAT_FIELDS = {f.name for f in fields(Check) if f.type in ("float", float)}


# ---------------------------------------------------------------------------------------
# numbers
# ---------------------------------------------------------------------------------------
def relative_error(value: float, target: float) -> float:
    """(value − target)/|target|; ±inf for a non-zero value against a zero target, nan if
    either is not finite."""
    value, target = float(value), float(target)
    if not (math.isfinite(value) and math.isfinite(target)):
        return math.nan
    if target == 0.0:
        return 0.0 if value == 0.0 else math.copysign(math.inf, value)
    return (value - target) / abs(target)


def half_unit_of_last_digit(printed: str) -> float:
    """Half a unit of the last printed digit: "0.0097" → 5e-5, "2105.97" → 5e-3, "1.04e-6" → 5e-9."""
    try:
        d = Decimal(str(printed).strip())
    except InvalidOperation:
        raise ValueError(f"not a printed decimal number: {printed!r}") from None
    exponent = d.as_tuple().exponent
    if not isinstance(exponent, int):
        raise ValueError(f"not a finite number: {printed!r}")
    return 0.5 * 10.0**exponent


def effective_tolerance(rtol: float, printed: str | None = None, printed_rounding: bool = False) -> float:
    """The relative tolerance a cell is judged with: ``rtol``, widened when ``printed_rounding``
    to half a unit of the printed value's last digit relative to that value (a paper value
    printed as 0.0097 cannot be held to better than 0.52 %)."""
    tol = float(rtol)
    if printed_rounding and printed is not None:
        p = abs(float(printed))
        if p > 0.0:
            tol = max(tol, half_unit_of_last_digit(printed) / p)
    return tol


def _judge(error: float, tolerance: float, residual: float = math.nan) -> str:
    """Reproduced within ``tolerance``; within a documented residual within ``residual`` (nan:
    none documented); else not reproduced."""
    if not math.isfinite(error):
        return NOT_REPRODUCED
    if abs(error) <= tolerance:
        return REPRODUCED
    return WITHIN_RESIDUAL if abs(error) <= residual else NOT_REPRODUCED


def format_number(x: float, digits: int = 6) -> str:
    """Compact significant-digit formatting for reports (nan → "–")."""
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "–"
    x = float(x)
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    if x == 0.0:
        return "0"
    if 1e-4 <= abs(x) < 1e6:
        decimals = max(0, digits - 1 - int(math.floor(math.log10(abs(x)))))
        text = f"{x:.{decimals}f}"
        return text.rstrip("0").rstrip(".") if "." in text else text
    return f"{x:.{digits - 1}e}"


def format_percent(x: float, digits: int = 3) -> str:
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "–"
    if math.isinf(x):
        return "inf"
    pct = 100.0 * x
    return f"{pct:+.{digits}g} %" if abs(pct) >= 1e-3 or pct == 0.0 else f"{pct:+.1e} %"


def format_tolerance(x: float) -> str:
    if math.isnan(x):
        return "–"
    return f"{100.0 * x:.3g} %" if x >= 1e-6 else f"{x:.0e}"


# ---------------------------------------------------------------------------------------
# building checks
# ---------------------------------------------------------------------------------------
def cell_id(scene: str, model: str, quantity: str, row: str, row_key: str = "s") -> str:
    return f"cell:{scene}/{model}/{quantity}/{row_key}={row}"


def numerics_id(scene: str, model: str, quantity: str, row: str, row_key: str = "s") -> str:
    return f"numerics:{scene}/{model}/{quantity}/{row_key}={row}"


def claim_id(scene: str, claim: str) -> str:
    return f"claim:{scene}/{claim}"


def table_cell_checks(
    scene: str,
    paper_table: Mapping[str, Any],
    results: Mapping[str, Mapping[str, Sequence[float]]],
    models: Mapping[str, Mapping[str, Any]],
    tolerances: Mapping[str, Any],
    quantities: Sequence[str] | None = None,
) -> list[Check]:
    """One check per (model, quantity, printed row).

    paper_table  an entry of config/paper_values.yaml: ``rows`` (printed row labels),
                 ``row_key`` (their name in the check ids), ``quantities`` (unit, factor
                 library → printed unit), ``columns`` (printed strings).
    results      {model name: {quantity: values at the printed rows, in library units}}.
    models       {model name: config entry with ``paper_column`` and ``label``}.
    tolerances   the scene's tolerances: {model: {quantity: {rtol, why, residual}}, printed_rounding};
                 the optional ``residual: {rtol, why}`` is a documented residual: cells beyond
                 ``rtol`` but within it get the verdict "within a documented residual".
    """
    s_printed = [str(x) for x in paper_table["rows"]]
    row_key = paper_table.get("row_key", "s")
    rounding = bool(tolerances.get("printed_rounding", False))
    out: list[Check] = []
    for model, per_quantity in results.items():
        mcfg = models[model]
        column = paper_table["columns"][mcfg["paper_column"]]
        for quantity in quantities or list(per_quantity):
            qinfo = paper_table["quantities"][quantity]
            printed = [str(x) for x in column[quantity]]
            values = np.asarray(per_quantity[quantity], dtype=float) * float(qinfo.get("factor", 1.0))
            if len(values) != len(s_printed) or len(printed) != len(s_printed):
                raise ValueError(
                    f"{scene}/{model}/{quantity}: {len(values)} values for {len(s_printed)} printed rows"
                )
            try:
                tol_cfg = tolerances[model][quantity]
            except KeyError:
                raise KeyError(f"no tolerance configured for {scene}/{model}/{quantity}") from None
            residual_cfg = tol_cfg.get("residual") or {}
            residual = float(residual_cfg.get("rtol", math.nan))
            why = str(tol_cfg.get("why", "")) + (f" Residual: {residual_cfg['why']}" if residual_cfg.get("why") else "")
            for s, p, v in zip(s_printed, printed, values):
                tol = effective_tolerance(tol_cfg["rtol"], p, rounding)
                err = relative_error(v, float(p))
                verdict = _judge(err, tol, residual)
                widened = " (printed rounding)" if tol > float(tol_cfg["rtol"]) else ""
                detail = (
                    f"ours {format_number(v)} vs printed {p} {qinfo['unit']}: "
                    f"{format_percent(err)} {'≤' if verdict == REPRODUCED else '>'} {format_tolerance(tol)}{widened}"
                )
                if verdict == WITHIN_RESIDUAL:
                    detail += f", ≤ {format_tolerance(residual)} (documented residual)"
                out.append(
                    Check(
                        id=cell_id(scene, model, quantity, s, row_key),
                        kind="cell",
                        scene=scene,
                        verdict=verdict,
                        detail=detail,
                        description=f"{mcfg['paper_column']} column, {mcfg['label']}",
                        model=model,
                        quantity=quantity,
                        s=s,
                        unit=qinfo["unit"],
                        printed=p,
                        target=float(p),
                        value=float(v),
                        error=err,
                        tolerance=tol,
                        tolerance_why=" ".join(why.split()),
                        residual_tolerance=residual,
                    )
                )
    return out


def numerics_checks(
    scene: str,
    s_printed: Sequence[str],
    production: Mapping[str, Mapping[str, Sequence[float]]],
    reference: Mapping[str, Mapping[str, Sequence[float]]],
    rtol: float,
    quantities: Sequence[str] | None = None,
    reference_dps: int | None = None,
    row_key: str = "s",
) -> list[Check]:
    """Production (numba) vs reference (mpmath) at every table cell: |rel. diff| ≤ rtol."""
    out: list[Check] = []
    dps = f" (mpmath {reference_dps} digits)" if reference_dps else ""
    for model, per_quantity in production.items():
        if model not in reference:
            continue
        for quantity in quantities or list(per_quantity):
            prod = np.asarray(per_quantity[quantity], dtype=float)
            ref = np.asarray(reference[model][quantity], dtype=float)
            for s, p, r in zip(s_printed, prod, ref):
                err = relative_error(p, r)
                verdict = _judge(err, rtol)
                out.append(
                    Check(
                        id=numerics_id(scene, model, quantity, str(s), row_key),
                        kind="numerics",
                        scene=scene,
                        verdict=verdict,
                        detail=(
                            f"production {p:.12g} vs reference {r:.12g}{dps}: |rel. diff| "
                            f"{abs(err):.1e} {'≤' if verdict == REPRODUCED else '>'} {rtol:.0e}"
                        ),
                        description="production vs reference quadrature",
                        model=model,
                        quantity=quantity,
                        s=str(s),
                        target=float(r),
                        value=float(p),
                        error=err,
                        tolerance=float(rtol),
                        tolerance_why="issue #2: production must agree with the reference to 1e-8",
                    )
                )
    return out


def claim_check(
    scene: str,
    claim: Mapping[str, Any],
    x: Sequence[float],
    curves: Mapping[str, Sequence[float]],
    x_name: str = "x",
) -> Check:
    """Test a prose claim on figure data (``x_name`` names the abscissa in the report).

    ``check: approaches`` — every curve's |y − target| shrinks monotonically for
    x ≥ ``tail_from`` and is ≤ ``atol`` at the last x (a numerical "tends to").
    ``check: value_at_start`` — every curve's |y(x[0]) − target| ≤ ``atol``.
    The check's value is the worst deviation over the curves.
    """
    x = np.asarray(x, dtype=float)
    target = float(claim["target"])
    atol = float(claim["atol"])
    kind = claim["check"]
    worst = 0.0
    ok = True
    parts = []
    for label, y in curves.items():
        y = np.asarray(y, dtype=float)
        if kind == "approaches":
            tail = x >= float(claim.get("tail_from", x[0]))
            dev = np.abs(y[tail] - target)
            # allow round-off-sized wiggles in a monotone decrease
            monotone = bool(np.all(np.diff(dev) <= 1e-9 * np.maximum(dev[:-1], 1e-300) + 1e-15))
            end = float(dev[-1]) if dev.size else math.nan
            good = monotone and math.isfinite(end) and end <= atol
            parts.append(
                f"{label}: |y − {target:g}| = {end:.3g} at {x_name} = {x[tail][-1]:g}"
                + ("" if monotone else f", not shrinking monotonically for {x_name} ≥ {claim.get('tail_from')}")
            )
        elif kind == "value_at_start":
            end = float(abs(y[0] - target))
            good = math.isfinite(end) and end <= atol
            parts.append(f"{label}: |y({x_name} = {x[0]:g}) − {target:g}| = {end:.2g}")
        else:
            raise ValueError(f"unknown claim check {kind!r}")
        ok = ok and good
        worst = max(worst, end) if math.isfinite(end) else math.inf
    verdict = REPRODUCED if ok else NOT_REPRODUCED
    return Check(
        id=claim_id(scene, claim["id"]),
        kind="claim",
        scene=scene,
        verdict=verdict,
        detail="; ".join(parts) + f" (tolerance {atol:g})",
        description=str(claim["text"]),
        target=target,
        value=math.nan,
        error=worst,
        tolerance=atol,
        tolerance_why=str(claim.get("why", "")),
    )


# ---------------------------------------------------------------------------------------
# expectations
# ---------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Expectation:
    """One entry of config/expected_verdicts.yaml. ``band`` (lo, hi) bounds the check's
    ``band_on`` field ("error" or "value") of a documented discrepancy; None for a qualitative
    one (its checks carry no number) and for the other verdicts."""

    match: str
    expected: str
    reason: str
    band: tuple[float, float] | None = None
    band_on: str = "error"


QUALITATIVE = "qualitative"


def _band(i: int, entry: Mapping[str, Any], expected: str) -> tuple[tuple[float, float] | None, str]:
    where = f"expectation #{i + 1} ({entry.get('match')})"
    band, band_on = entry.get("band"), entry.get("band_on", "error")
    if band_on not in ("error", "value"):
        raise ValueError(f"{where}: band_on must be 'error' or 'value', got {band_on!r}")
    if expected != NOT_REPRODUCED:
        if band is not None:
            raise ValueError(f"{where}: only a documented discrepancy ('{NOT_REPRODUCED}') takes a band")
        return None, band_on
    if band == QUALITATIVE:
        return None, band_on
    try:
        lo, hi = (float(x) for x in band)
    except (TypeError, ValueError):
        raise ValueError(f"{where}: a documented discrepancy needs band: [lo, hi] of its {band_on} "
                         f"(sign and size, with a margin), or band: {QUALITATIVE}; got {band!r}") from None
    if not (math.isfinite(lo) and math.isfinite(hi) and lo <= hi):
        raise ValueError(f"{where}: band must be two finite numbers lo <= hi, got {band!r}")
    return (lo, hi), band_on


def load_expectations(data: Mapping[str, Any]) -> tuple[str, list[Expectation]]:
    """(default verdict, ordered expectations) from config/expected_verdicts.yaml's content."""
    default = data.get("default", REPRODUCED)
    if default not in (REPRODUCED, WITHIN_RESIDUAL):
        raise ValueError(f"default must be {REPRODUCED!r} (or {WITHIN_RESIDUAL!r}), got {default!r}")
    out = []
    for i, entry in enumerate(data.get("expectations") or []):
        try:
            match, expected = str(entry["match"]), entry["expected"]
        except (KeyError, TypeError):
            raise ValueError(f"expectation #{i + 1} needs 'match' and 'expected': {entry!r}") from None
        if expected not in VERDICTS:
            raise ValueError(f"expectation #{i + 1} ({match}): expected must be one of {VERDICTS}")
        reason = " ".join(str(entry.get("reason", "")).split())
        out.append(Expectation(match, expected, reason, *_band(i, entry, expected)))
    return default, out


def expected_for(check_id: str, expectations: Sequence[Expectation], default: str = REPRODUCED) -> Expectation:
    """The last expectation whose glob matches ``check_id`` (or the default)."""
    found = Expectation("(default)", default, "")
    for e in expectations:
        if fnmatch.fnmatchcase(check_id, e.match):
            found = e
    return found


def _status(e: Expectation, c: Check) -> tuple[str, str]:
    """(status, reason) of check ``c`` under expectation ``e``."""
    if e.expected == REPRODUCED:
        return (STATUS_OK if c.verdict == REPRODUCED else STATUS_REGRESSION), e.reason
    if e.expected == WITHIN_RESIDUAL:
        status = {REPRODUCED: STATUS_IMPROVED, WITHIN_RESIDUAL: STATUS_RESIDUAL}.get(c.verdict, STATUS_REGRESSION)
        return status, e.reason
    if c.verdict != NOT_REPRODUCED:
        return STATUS_IMPROVED, e.reason
    x = float(getattr(c, e.band_on))
    if e.band is None:
        if math.isfinite(c.error):
            return STATUS_REGRESSION, f"a qualitative expectation, but the check has an error {c.error:.4g}: give it a band. {e.reason}"
        return STATUS_KNOWN, e.reason
    lo, hi = e.band
    if math.isfinite(x) and lo <= x <= hi:
        return STATUS_KNOWN, e.reason
    return STATUS_REGRESSION, (f"LEFT ITS DOCUMENTED BAND: {e.band_on} {x:.4g} not in [{lo:.4g}, {hi:.4g}]. "
                               f"Documented: {e.reason}")


def apply_expectations(checks: Iterable[Check], data: Mapping[str, Any]) -> list[Check]:
    """Attach expected verdict, status and documented reason to each check."""
    default, expectations = load_expectations(data)
    out = []
    for c in checks:
        e = expected_for(c.id, expectations, default)
        status, reason = _status(e, c)
        out.append(replace(c, expected=e.expected, status=status, reason=reason))
    return out


def regressions(checks: Iterable[Check]) -> list[Check]:
    """Checks expected to reproduce that did not, and documented discrepancies that left their
    band: these turn CI red."""
    return [c for c in checks if c.status == STATUS_REGRESSION]


def improvements(checks: Iterable[Check]) -> list[Check]:
    """Documented discrepancies (or residuals) that now reproduce: unexplained changes that fail
    the gate until config/expected_verdicts.yaml is updated with the reason."""
    return [c for c in checks if c.status == STATUS_IMPROVED]


def _declared_specs(data: Mapping[str, Any]) -> dict[str, tuple[int, str | None, str | None, str]]:
    """{scene: (expected number of checks, required tool or None, own target or None, how to
    install the tool)}: a scene with ``target`` is computed only by that workflow target (e.g.
    ``bem``, not part of ``all``)."""
    out = {}
    for scene, spec in (data.get("expected_checks") or {}).items():
        spec = dict(spec) if isinstance(spec, Mapping) else {"checks": spec}
        count, tool, target = spec.get("checks"), spec.get("requires"), spec.get("target")
        if not isinstance(count, int) or isinstance(count, bool) or count < 1:
            raise ValueError(f"expected_checks.{scene}: a positive number of checks, got {count!r}")
        out[str(scene)] = (count, None if tool is None else str(tool), None if target is None else str(target),
                           str(spec.get("install") or ""))
    return out


def required_tools(data: Mapping[str, Any]) -> list[str]:
    """The external tools optional scenes of ``expected_checks`` require (e.g. ``ccx``)."""
    return sorted({tool for _, tool, _, _ in _declared_specs(data).values() if tool})


def skipped_text(tool: str, install: str = "") -> str:
    """The one line every report (VERIFICATION.md, the gate, the gallery, the scene's own page)
    gives for an optional scene whose tool is absent: "skipped: ccx not installed — `apt-get
    install calculix-ccx`"."""
    missing = "not run" if tool.startswith("target ") else "not installed"  # a target of its own (bem)
    return f"skipped: {tool} {missing}" + (f" — `{install}`" if install else "")


def check_coverage(checks: Sequence[Check], data: Mapping[str, Any], tools: Iterable[str] = ()) -> dict[str, Any]:
    """Compare the checks per scene with ``expected_checks`` of ``data``.

    missing     [{scene, expected, found}] scenes with fewer checks than declared (regressions);
    skipped     [{scene, requires, checks, install}] optional scenes absent because their tool is
                not in ``tools`` (``checks``: the declared number, counted as skipped), or, for a
                scene with its own ``target``, because that target was not run (requires =
                "target <name>", install = the command that runs it);
    unexpected  [{scene, expected, found}] scenes with more checks than declared, or undeclared
                (not a regression: update expected_checks). A scene with its own target declares
                the least number of checks (its count grows with the target's scale).
    """
    specs, tools = _declared_specs(data), set(tools)
    found = {scene: 0 for scene in specs}
    for c in checks:
        found[c.scene] = found.get(c.scene, 0) + 1
    out: dict[str, list] = {"missing": [], "skipped": [], "unexpected": []}
    for scene, n in found.items():
        expected, tool, target, install = specs.get(scene, (0, None, None, ""))
        if n == 0 and tool and tool not in tools:
            out["skipped"].append({"scene": scene, "requires": tool, "checks": expected, "install": install})
        elif n == 0 and target:
            out["skipped"].append({"scene": scene, "requires": f"target {target}", "checks": expected,
                                   "install": f"snakemake {target}"})
        elif n < expected:
            out["missing"].append({"scene": scene, "expected": expected, "found": n})
        elif n > expected and not target:
            out["unexpected"].append({"scene": scene, "expected": expected, "found": n})
    return out


def summarize(checks: Sequence[Check], coverage: Mapping[str, Any] | None = None) -> dict[str, Any]:
    """Counts overall, per scene and per kind; ``passed`` is False if there is a regression, a
    check improved beyond its documented expectation (unexplained until the expectation is
    updated), a scene misses checks (``coverage`` of :func:`check_coverage`), or there are no
    checks."""

    def counts(cs):
        return {
            "checks": len(cs),
            "reproduced": sum(c.verdict == REPRODUCED for c in cs),
            "within_residual": sum(c.verdict == WITHIN_RESIDUAL for c in cs),
            "not_reproduced": sum(c.verdict == NOT_REPRODUCED for c in cs),
            "ok": sum(c.status == STATUS_OK for c in cs),
            "residual": sum(c.status == STATUS_RESIDUAL for c in cs),
            "known": sum(c.status == STATUS_KNOWN for c in cs),
            "improved": sum(c.status == STATUS_IMPROVED for c in cs),
            "regressions": sum(c.status == STATUS_REGRESSION for c in cs),
        }

    coverage = dict(coverage or {"missing": [], "skipped": [], "unexpected": []})
    scenes = list(dict.fromkeys(c.scene for c in checks))
    kinds = list(dict.fromkeys(c.kind for c in checks))
    total = counts(checks)
    return {
        **total,
        "passed": (total["regressions"] == 0 and total["improved"] == 0 and not coverage["missing"]
                   and len(checks) > 0),
        "by_scene": {s: counts([c for c in checks if c.scene == s]) for s in scenes},
        "by_kind": {k: counts([c for c in checks if c.kind == k]) for k in kinds},
        "regression_ids": [c.id for c in checks if c.status == STATUS_REGRESSION],
        "improved_ids": [c.id for c in checks if c.status == STATUS_IMPROVED],
        # the declared checks of optional scenes whose tool is absent: neither run nor failed
        "skipped": sum(int(m.get("checks", 0)) for m in coverage["skipped"]),
        "coverage": coverage,
    }


# ---------------------------------------------------------------------------------------
# CSV round trip
# ---------------------------------------------------------------------------------------
_FIELDS = [f.name for f in fields(Check)]


def checks_to_csv(checks: Iterable[Check]) -> str:
    buf = _io.StringIO()
    w = csv.DictWriter(buf, fieldnames=_FIELDS, lineterminator="\n")
    w.writeheader()
    for c in checks:
        row = asdict(c)
        for k in _FLOAT_FIELDS:
            row[k] = repr(float(row[k]))
        w.writerow(row)
    return buf.getvalue()


def checks_from_csv(text: str) -> list[Check]:
    out = []
    for row in csv.DictReader(_io.StringIO(text)):
        kw = {k: (float(v) if k in _FLOAT_FIELDS else v) for k, v in row.items() if k in _FIELDS}
        out.append(Check(**kw))
    return out
