"""`roughcontact ccx build` (roughcontact.ccx.build): the absent paths (no tools, no source, no
build) say in one line what to do; the build's key follows its inputs; the dispatcher patches
fit CalculiX 2.20's source where that source is at hand."""

from __future__ import annotations

import pytest

from roughcontact.ccx import build as ccx_build
from roughcontact.cli import main


def test_missing_tools_are_one_line_naming_the_packages(monkeypatch, tmp_path, capsys):
    monkeypatch.setenv("ROUGHCONTACT_CCX_CACHE", str(tmp_path))
    monkeypatch.setattr(ccx_build.shutil, "which", lambda name: None)
    assert set(ccx_build.missing_tools()) >= {"gfortran", "gcc", "make"}
    code = main(["ccx", "build", "--quiet"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1
    assert err[0].startswith("roughcontact: error: building ccx needs: apt-get install gfortran")


def test_no_source_is_one_line(monkeypatch, tmp_path, capsys):
    monkeypatch.setenv("ROUGHCONTACT_CCX_CACHE", str(tmp_path))
    monkeypatch.setattr(ccx_build, "missing_tools", lambda: [])
    real = ccx_build.shutil.which
    monkeypatch.setattr(ccx_build.shutil, "which", lambda name: None if name in ("apt-get", "dpkg-source") else real(name))
    code = main(["ccx", "build", "--quiet"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and "--source DIR" in err[0] and "dpkg-dev" in err[0]
    code = main(["ccx", "build", "--quiet", "--source", str(tmp_path)])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and "calculix-ccx-2.20" in err[0]


def test_a_source_with_another_checksum_is_refused(monkeypatch, tmp_path):
    monkeypatch.setattr(ccx_build, "missing_tools", lambda: [])
    (tmp_path / ccx_build.DSC).write_text("x")
    for name in ccx_build.SOURCE_FILES:
        (tmp_path / name).write_bytes(b"not the tarball")
    with pytest.raises(ccx_build.BuildError, match="SHA-256 differs"):
        ccx_build.build_ccx(source=tmp_path, root=tmp_path / "cache", progress=lambda m: None)


def test_run_without_a_build_is_one_line(monkeypatch, tmp_path, capsys):
    monkeypatch.setenv("ROUGHCONTACT_CCX_CACHE", str(tmp_path))
    code = main(["ccx", "run", "model.inp", "--interface", "law.yaml"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and err == ["roughcontact: error: no ccx with the interface law: run `roughcontact ccx build` "
                                 "first (docs/ccx.md)"]


def test_the_key_follows_the_element_source(monkeypatch):
    key = ccx_build.build_key()
    assert key == ccx_build.build_key() and len(key) == 16
    monkeypatch.setattr(ccx_build, "element_source", lambda: "changed")
    assert ccx_build.build_key() != key


def test_the_patches_fit_calculix_2_20(tmp_path):
    """The patched texts occur as often as the patches expect (the cached source, or skip)."""
    tree = ccx_build.cache_root() / "ccx-source" / ccx_build.TREE / "ccx_2.20" / "src"
    if not (tree / "e_c3d_u.f").is_file():
        pytest.skip("CalculiX's source is not in the cache (roughcontact ccx build fetches it)")
    for name, old, new, count in ccx_build.PATCHES:
        text = (tree / name).read_text()
        assert text.count(old) == count
        if name.endswith(".f"):
            assert all(len(line) <= 72 for line in new.splitlines())  # fixed form
