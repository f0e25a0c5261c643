"""Machine information and numba compile-versus-run timings for the benchmark reports."""

from __future__ import annotations

import json
import os
import platform
import subprocess
import sys
import tempfile
import textwrap
from importlib.metadata import version


def cpu_model() -> str:
    try:
        with open("/proc/cpuinfo") as fh:
            for line in fh:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def info() -> dict:
    """CPU, cores, load average, numba threading, library versions."""
    import numba

    try:
        layer = numba.threading_layer()
    except ValueError:  # no parallel region has run yet
        layer = "not initialised"
    return {
        "cpu": cpu_model(),
        "cores": os.cpu_count(),
        "loadavg": [round(x, 2) for x in os.getloadavg()],
        "numba_threads": numba.config.NUMBA_NUM_THREADS,
        "numba_threading_layer": layer,
        "platform": platform.platform(),
        "python": sys.version.split()[0],
        **{lib: version(lib) for lib in ("roughcontact", "numpy", "scipy", "numba", "mpmath", "xarray")},
    }


_COMPILE_PROBE = textwrap.dedent(
    """
    import json, time
    t0 = time.perf_counter()
    from roughcontact import SpectralMoments
    from roughcontact.contact import elastic_contact
    from roughcontact.contact import elastoplastic_contact
    from roughcontact.asperity import AsperityMaterial, yield_strength_for_plasticity_index
    t_import = time.perf_counter() - t0
    surf = SpectralMoments(0.0625, 8e-5, 8e-4, 1.04e-6, 1.04e-4)
    mat = AsperityMaterial(1.14e5, yield_strength_for_plasticity_index(1.0, surf, 1.14e5))
    out = {"import": t_import}
    for name, call in (("elastic", lambda s: elastic_contact(surf, s, 1.14e5)),
                       ("elastoplastic", lambda s: elastoplastic_contact(surf, s, mat, accuracy="plot"))):
        for run, s in (("first", [1.0]), ("second", [1.01]), ("first_batch", [1.0] * 16), ("second_batch", [1.02] * 16)):
            t0 = time.perf_counter(); call(s); out[f"{name}_{run}"] = time.perf_counter() - t0
    print(json.dumps(out))
    """
)


def _probe(cache_dir: str) -> dict:
    env = dict(os.environ, NUMBA_CACHE_DIR=cache_dir)
    res = subprocess.run([sys.executable, "-c", _COMPILE_PROBE], env=env, capture_output=True, text=True,
                         check=True, timeout=1800)
    return json.loads(res.stdout.strip().splitlines()[-1])


def compile_times() -> dict:
    """Two fresh processes sharing an empty numba cache directory: the first compiles every
    kernel (serial and threaded variants) and writes the cache, the second loads it. First call
    minus second call is the compile (or load) time; separations differ so nothing is reused
    across calls except the θ-node set-up of the surface (one-off, in the first call too)."""
    with tempfile.TemporaryDirectory(prefix="numba-cache-") as d:
        cold = _probe(d)
        warm = _probe(d)
    return {"cold_cache": cold, "warm_cache": warm}
