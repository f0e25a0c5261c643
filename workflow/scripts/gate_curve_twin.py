"""The slow twins at the sample points of one curve file (rule curve_twin): JSON with the points
and the twins' values, computed from the configuration alone (roughcontact.paper.gate_anchors)."""

import json
import time

from roughcontact import io
from roughcontact.paper import gate_anchors


def run(source, points, twin_rtol, dps, output, log):
    with io.log_to(log) as logger:
        values = []
        for spec in points:
            point = gate_anchors.TwinPoint(**spec)
            t0 = time.perf_counter()
            values.append(gate_anchors.twin_values(point, rtol=twin_rtol, dps=dps))
            logger.info("%s[%s]: %s in %.1f s", source, point.label, values[-1], time.perf_counter() - t0)
        io.write_text(output, json.dumps({"source": source, "twin_rtol": twin_rtol, "dps": dps, "points": points,
                                          "values": values}, indent=1, sort_keys=True) + "\n")


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.wildcards.source, sm.params.points, sm.params.twin_rtol, sm.params.dps, sm.output[0], sm.log[0])
