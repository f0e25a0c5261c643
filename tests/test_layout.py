"""The package layout is the architecture (docs/architecture.md, "Layout"): imports point one way through the
layers, modules stay small, numba kernels call only kernels of their own file, and the tests
mirror the packages."""

import ast
import importlib
import importlib.util
import pkgutil
from pathlib import Path

import numba.core.registry
import numpy as np
import pytest

import roughcontact

SRC = Path(roughcontact.__file__).resolve().parent
TESTS = Path(__file__).resolve().parent

#: lower layers first; a module may import from its own layer and the layers below it only.
#: (statistics and asperity share the bottom: asperity's plasticity index reads the surface
#: statistics; nothing in statistics reads an asperity.)
LAYERS = [
    {"validation", "files", "limits", "write_errors", "orphan_jobs"},
    {"statistics"},
    {"readers"},
    {"asperity"},
    {"integrals"},
    {"contact"},
    {"interface", "bem"},
    {"fe"},
    {"ccx"},
    {"examples"},
    {"plots"},
    {"paper"},
    {"io", "warmup", "cli", "__main__", "__init__"},
]
RANK = {name: i for i, layer in enumerate(LAYERS) for name in layer}

#: modules allowed above ~600 lines, and why
LONG_MODULES = {
    "integrals/kernels.py": "numba's cache is invalidated per file, so kernels that call each other share one",
}
MAX_LINES = 620


def _modules():
    return sorted(p for p in SRC.rglob("*.py") if "__pycache__" not in p.parts)


def _top(path: Path) -> str:
    """The layer name of a module: its top-level package or module name under roughcontact/."""
    rel = path.relative_to(SRC)
    return rel.parts[0].removesuffix(".py")


def _imported_tops(path: Path):
    """(line, top-level roughcontact name) of every import of the package in ``path``,
    including imports inside functions."""
    tree = ast.parse(path.read_text())
    package = list(path.relative_to(SRC).parent.parts)
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[: len(package) - (node.level - 1)]
                target = base + (node.module.split(".") if node.module else [])
                names = [target[0]] if target else [a.name for a in node.names]
            elif node.module and node.module.split(".")[0] == "roughcontact":
                parts = node.module.split(".")[1:]
                names = [parts[0]] if parts else [a.name for a in node.names]
            else:
                continue
            for n in names:
                yield node.lineno, n
        elif isinstance(node, ast.Import):
            for a in node.names:
                parts = a.name.split(".")
                if parts[0] == "roughcontact" and len(parts) > 1:
                    yield node.lineno, parts[1]


def test_every_module_has_a_layer():
    missing = {_top(p) for p in _modules()} - set(RANK)
    assert not missing, f"modules outside the layer table: {missing}"


@pytest.mark.parametrize("path", _modules(), ids=lambda p: str(p.relative_to(SRC)))
def test_imports_point_down(path):
    """paper → fe → interface → contact → integrals → asperity → statistics → validation."""
    mine = RANK[_top(path)]
    for line, name in _imported_tops(path):
        if name == "__version__":
            continue
        assert name in RANK, f"{path.name}:{line} imports unknown roughcontact.{name}"
        assert RANK[name] <= mine, f"{path.relative_to(SRC)}:{line} imports the higher layer {name!r}"


@pytest.mark.parametrize("path", _modules(), ids=lambda p: str(p.relative_to(SRC)))
def test_modules_are_small(path):
    rel = str(path.relative_to(SRC))
    if rel in LONG_MODULES or path.name.startswith("_") and path.name.endswith("_data.py"):
        return
    n = len(path.read_text().splitlines())
    assert n <= MAX_LINES, f"{rel} has {n} lines: split it by job (or record why in LONG_MODULES)"


def _assert_package_imports_resolve(path: Path, package: list[str]):
    """Every import of roughcontact in ``path`` (``package``: the dotted parts of its own package,
    for relative imports) — also inside functions, where an import error shows only when the
    function runs — names a module (or a name of one) that exists."""
    tree = ast.parse(path.read_text())
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and (node.level or (node.module or "").startswith("roughcontact")):
            base = package[: len(package) - (node.level - 1)] if node.level else []
            module = ".".join(base + (node.module.split(".") if node.module else []))
            mod = importlib.import_module(module)
            for alias in node.names:
                assert alias.name == "*" or hasattr(mod, alias.name) or importlib.util.find_spec(
                    f"{module}.{alias.name}") is not None, f"{path.name}:{node.lineno}: {module}.{alias.name}"


@pytest.mark.parametrize("path", _modules(), ids=lambda p: str(p.relative_to(SRC)))
def test_every_package_import_resolves(path):
    _assert_package_imports_resolve(path, ["roughcontact", *path.relative_to(SRC).parent.parts])


#: scripts outside the package that import it: a workflow script runs only inside its rule (the
#: BEM report's stale import showed only in CI's `snakemake bem`), a benchmark only when run.
SCRIPTS = sorted([*(TESTS.parent / "workflow" / "scripts").glob("*.py"), *(TESTS.parent / "benchmarks").glob("*.py")])


@pytest.mark.parametrize("path", SCRIPTS, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_every_script_import_of_the_package_resolves(path):
    _assert_package_imports_resolve(path, [])


def test_long_modules_are_still_long():
    """An exception that no longer applies is removed from LONG_MODULES."""
    for rel in LONG_MODULES:
        assert len((SRC / rel).read_text().splitlines()) > MAX_LINES, rel


def _kernel_modules():
    out = []
    for info in pkgutil.walk_packages(roughcontact.__path__, "roughcontact."):
        if info.name.endswith("__main__"):
            continue
        mod = importlib.import_module(info.name)
        kernels = {k: v for k, v in vars(mod).items()
                   if isinstance(v, numba.core.registry.CPUDispatcher) and v.py_func.__module__ == mod.__name__}
        if kernels:
            out.append((mod, kernels))
    return out


def test_kernels_call_only_kernels_of_their_own_file():
    """numba invalidates a cached kernel when ITS file changes, not when a callee's file does:
    every jitted function a kernel references is defined in the kernel's own file, and no
    array is frozen into a kernel as a global (tables enter as arguments)."""
    modules = _kernel_modules()
    assert {m.__name__ for m, _ in modules} >= {"roughcontact.integrals.kernels", "roughcontact.interface.kernels"}
    for mod, kernels in modules:
        for name, disp in kernels.items():
            for ref in disp.py_func.__code__.co_names:
                obj = disp.py_func.__globals__.get(ref)
                if hasattr(obj, "py_func"):
                    assert obj.py_func.__module__ == mod.__name__, (mod.__name__, name, ref)
                assert not (isinstance(obj, np.ndarray) and obj.size > 1), (mod.__name__, name, ref)


def test_tests_mirror_the_packages():
    """Each package of src/roughcontact has a test folder of the same name, and back."""
    packages = {p.name for p in SRC.iterdir() if p.is_dir() and (p / "__init__.py").exists()}
    folders = {p.name for p in TESTS.iterdir() if p.is_dir() and any(p.glob("test_*.py"))}
    assert folders == packages
