"""A CalculiX 2.20 with the interface law compiled in, built from Debian's source package and
cached outside the clone (``roughcontact ccx build``, docs/ccx.md).

Why a user element: CalculiX 2.20 has no user hook for contact or friction (surfacebehaviors.f,
frictions.f); its mechanical hooks are user materials and ``*USER ELEMENT`` (e_c3d_u.f,
resultsmech_u.f). The engine's zero-thickness interface element between conforming faces
(:mod:`roughcontact.fe.interface_element`) maps onto a user element one to one, where a user
material would need a thin layer of solid elements, i.e. a change of the geometry.

The build, step by step (each step reported on ``progress``):

1. the tools: gfortran, gcc, make and the libraries Debian links ccx with (SPOOLES, ARPACK,
   LAPACK, BLAS); a missing one is one line naming the Debian packages to install;
2. the source: ``--source`` (a folder holding Debian's unpacked ``calculix-ccx-2.20`` tree, or
   its ``.dsc``) or, by default, ``apt-get source --download-only calculix-ccx`` into the cache
   (a ``deb-src`` entry for bookworm is needed: the one line says which) unpacked with
   ``dpkg-source -x`` (Debian's patches applied); the upstream tarball must have the SHA-256
   below, so every build starts from the same text;
3. the build folder ``ccx-<key>``: ``key`` hashes the source checksums, the Fortran of the law
   and the element, the dispatcher patches and the flags, so a change of any of them builds
   anew and an unchanged one is found again (a second ``ccx build`` returns at once);
4. the dispatchers e_c3d_u.f and resultsmech_u.f gain one branch each (:data:`PATCHES`) calling
   ``rc_ccx_stiffness`` / ``rc_ccx_results`` (ccx/fortran/rc_ccx_element.f90) for user elements
   whose type starts ``URC``; the .frd writer (frd.c) skips them as it skips the U1 beam (it
   stops on an element type it cannot draw); the nonlinear driver (nonlingeo.c) switches on the
   unsymmetric assembly where they exist and mafillsmas.f adds their antisymmetric part (the
   friction tangent is unsymmetric; a degree of freedom under an MPC gets the symmetric part
   only); the Makefile compiles roughcontact_law.f90 and the element;
5. ``make`` with Debian's flags (debian/rules: ``-DARCH="Linux" -DSPOOLES -DARPACK
   -DMATRIXSTORAGE -DUSE_MT=1``, Fortran ``-fallow-argument-mismatch``), a line per 10 % of the
   ~1120 sources; the binary and ``build.json`` (provenance) are moved into place atomically.

Measured on this 2-core machine: ~3–4 min; the cached build is ~14 MB.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import shutil
import subprocess
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

from ..interface.fortran_export import fortran_source

__all__ = ["CCX_VERSION", "BuildError", "Build", "cache_root", "missing_tools", "build_key", "find_build",
           "build_ccx", "PATCHES"]

CCX_VERSION = "2.20"
PACKAGE = "calculix-ccx"
#: Debian bookworm's source package (calculix-ccx_2.20-1): the files and their SHA-256
SOURCE_FILES = {
    "calculix-ccx_2.20.orig.tar.bz2": "b9a6075e181a777bbcfadd3ad21a70749dfdbb439373df3b4895cd2f438343ab",
    "calculix-ccx_2.20-1.debian.tar.xz": "befe7a566836c2527aced457dfcf3bb6cfe69737915b795a99c821694426b5c9",
}
DSC = "calculix-ccx_2.20-1.dsc"
TREE = "calculix-ccx-2.20"
#: debian/rules of calculix-ccx 2.20-1 (without dpkg-buildflags' hardening and debug options)
CFLAGS = '-O2 -I/usr/include/spooles -DARCH="Linux" -DSPOOLES -DARPACK -DMATRIXSTORAGE -DUSE_MT=1'
FFLAGS = "-O2 -fallow-argument-mismatch"
#: our sources, in compilation order (the law's module first)
ELEMENT_SOURCE = "rc_ccx_element.f90"
LAW_SOURCE = "roughcontact_law.f90"
#: what to install, per missing tool or library (Debian package names)
INSTALL = {"gfortran": "gfortran", "gcc": "gcc", "make": "make", "libspooles.so": "libspooles-dev",
           "libarpack.so": "libarpack2-dev", "liblapack.so": "liblapack-dev", "libblas.so": "libblas-dev"}
DEB_SRC_LINE = ("add a deb-src entry for bookworm (e.g. /etc/apt/sources.list.d/src.sources: 'Types: deb-src', "
                "'URIs: http://deb.debian.org/debian', 'Suites: bookworm', 'Components: main', 'Signed-By: "
                "/usr/share/keyrings/debian-archive-keyring.gpg'), run apt-get update, or give --source DIR")

_E_ANCHOR = "      else\n        write(*,*) '*ERROR in e_c3d_u.f: user element'\n"
_R_ANCHOR = "      else\n         write(*,*) '*ERROR in resultsmech_u.f: user element'\n"
_FRD_ANCHOR = 'if(strcmp1(&lakon[8*i],"U1")==0){'
_AS_ANCHOR = "!     only contact friction\n!     \n        do i=neam,nebm\n"
_NASYM_ANCHOR = "  if((*nstate_!=0)&&((*mortar!=1)||(ncont==0))){\n"
#: (file, text, replacement, occurrences): one branch in each user-element dispatcher; the .frd
#: writer skips the URC elements as it skips U1 (its element count and its element list, frd.c)
PATCHES = (
    ("e_c3d_u.f", _E_ANCHOR,
     "      elseif(lakonl(2:3).eq.'RC') then\n"
     "        call rc_ccx_stiffness(co,kon,ipkon,nelem,ielprop,prop,mi,\n"
     "     &       xstiff,s,ff,stiffness)\n" + _E_ANCHOR, 1),
    ("resultsmech_u.f", _R_ANCHOR,
     "      elseif(lakon(nelem)(2:3).eq.'RC') then\n"
     "         call rc_ccx_results(co,kon,ipkon,nelem,ielprop,prop,mi,v,\n"
     "     &        nstate_,xstateini,xstate,xstiff,stx,fn,calcul_fn,\n"
     "     &        calcul_qa,qa,nal)\n" + _R_ANCHOR, 1),
    ("frd.c", _FRD_ANCHOR, 'if((strcmp1(&lakon[8*i],"U1")==0)||(strcmp1(&lakon[8*i],"URC")==0)){', 2),
    # the friction tangent is unsymmetric: the asymmetric assembly on where URC elements exist ...
    ("nonlingeo.c", _NASYM_ANCHOR,
     "  for(k=0;k<*ne;k++){if(strcmp1(&lakon[8*k],\"URC\")==0){nasym=1;break;}}\n" + _NASYM_ANCHOR, 1),
    # ... and their antisymmetric part added to the mirrored symmetric matrix (mafillsmas.f)
    ("mafillsmas.f", _AS_ANCHOR,
     "!     roughcontact: the antisymmetric part of the URC elements\n"
     "        do i=neat,nebt\n"
     "          if(ipkon(i).lt.0) cycle\n"
     "          if(lakon(i)(1:3).ne.'URC') cycle\n"
     "          indexe=ipkon(i)\n"
     "          nope=ichar(lakon(i)(8:8))\n"
     "          call rc_ccx_antisymmetric(co,kon,ipkon,i,ielprop,prop,\n"
     "     &         mi,xstiff,s)\n"
     "          do jj=1,3*nope\n"
     "            j=(jj-1)/3+1\n"
     "            k=jj-3*(j-1)\n"
     "            jdof1=nactdof(k,kon(indexe+j))\n"
     "            if(jdof1.le.0) cycle\n"
     "            do ll=1,3*nope\n"
     "              l=(ll-1)/3+1\n"
     "              m=ll-3*(l-1)\n"
     "              jdof2=nactdof(m,kon(indexe+l))\n"
     "              if((jdof2.le.0).or.(jdof2.eq.jdof1)) cycle\n"
     "              call add_sm_st_as(au,ad,jq,irow,jdof1,jdof2,\n"
     "     &             s(jj,ll),jj,ll,nzs)\n"
     "            enddo\n"
     "          enddo\n"
     "        enddo\n" + _AS_ANCHOR, 1),
)
_MAKEFILE_ANCHOR = "OCCXF = $(SCCXF:.f=.o)\n"
_MAKEFILE_ADDITION = (
    "OCCXF += roughcontact_law.o rc_ccx_element.o\n"
    "%.o: %.f90\n\t$(FC) $(FFLAGS) -frecursive -c $<\n"
    "rc_ccx_element.o: roughcontact_law.o\n"
)


class BuildError(RuntimeError):
    """A build that cannot run or failed: one line saying what to do."""


@dataclass(frozen=True)
class Build:
    """A built ccx: the executable, its folder, its provenance (build.json) and whether it was
    found in the cache (rather than built by this call)."""

    executable: Path
    folder: Path
    info: dict
    cached: bool = True


def cache_root() -> Path:
    """``$ROUGHCONTACT_CCX_CACHE`` or ``$XDG_CACHE_HOME/roughcontact`` (``~/.cache/roughcontact``)."""
    if os.environ.get("ROUGHCONTACT_CCX_CACHE"):
        return Path(os.environ["ROUGHCONTACT_CCX_CACHE"]).expanduser()
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "roughcontact"


def _library(name: str) -> bool:
    gcc = shutil.which("gcc")
    if gcc is None:
        return False
    out = subprocess.run([gcc, f"-print-file-name={name}"], capture_output=True, text=True).stdout.strip()
    return os.path.isabs(out) and os.path.exists(out)


def missing_tools() -> list[str]:
    """The Debian packages to install before a build (empty: everything is there)."""
    missing = [pkg for tool, pkg in INSTALL.items() if not tool.endswith(".so") and shutil.which(tool) is None]
    missing += [pkg for lib, pkg in INSTALL.items() if lib.endswith(".so") and not _library(lib)]
    if not os.path.isdir("/usr/include/spooles") and "libspooles-dev" not in missing:
        missing.append("libspooles-dev")
    return missing


def element_source() -> str:
    return resources.files(__package__).joinpath("fortran", ELEMENT_SOURCE).read_text(encoding="utf-8")


def _compiler_version() -> str:
    exe = shutil.which("gfortran")
    return subprocess.run([exe, "-dumpfullversion"], capture_output=True, text=True).stdout.strip() if exe else ""


def build_key() -> str:
    """16 hex digits of SHA-256 over everything a build depends on (module docstring, step 3)."""
    h = hashlib.sha256()
    for part in (json.dumps(SOURCE_FILES, sort_keys=True), fortran_source(LAW_SOURCE), element_source(),
                 repr(PATCHES), _MAKEFILE_ADDITION, CFLAGS, FFLAGS, _compiler_version()):
        h.update(part.encode())
        h.update(b"\0")
    return h.hexdigest()[:16]


def find_build(root: Path | None = None) -> Build | None:
    """The cached build of the current sources, or None."""
    folder = (root or cache_root()) / f"ccx-{build_key()}"
    exe, info = folder / "ccx", folder / "build.json"
    if exe.is_file() and os.access(exe, os.X_OK) and info.is_file():
        return Build(exe, folder, json.loads(info.read_text()))
    return None


def _sha256(path: Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def _source_tree(source: Path | None, root: Path, progress) -> Path:
    """The unpacked Debian tree (…/calculix-ccx-2.20), fetched into root/ccx-source if needed."""
    if source is not None:
        source = Path(source)
        for tree in (source, source / TREE):
            if (tree / f"ccx_{CCX_VERSION}" / "src" / "e_c3d_u.f").is_file():
                return tree
        if source.suffix == ".dsc" or (source / DSC).is_file():
            folder = source.parent if source.suffix == ".dsc" else source
        else:
            raise BuildError(f"--source {source}: neither Debian's unpacked {TREE} tree nor a folder with {DSC}")
    else:
        folder = root / "ccx-source"
        if (folder / TREE / f"ccx_{CCX_VERSION}" / "src" / "e_c3d_u.f").is_file():
            return folder / TREE
        if shutil.which("apt-get") is None or shutil.which("dpkg-source") is None:
            raise BuildError("the CalculiX source needs apt-get and dpkg-source (apt-get install dpkg-dev), "
                             "or give --source DIR (Debian's calculix-ccx 2.20 source package)")
        folder.mkdir(parents=True, exist_ok=True)
        progress(f"ccx build: fetching Debian's source package ({PACKAGE} {CCX_VERSION}) into {folder}")
        r = subprocess.run(["apt-get", "source", "--download-only", f"{PACKAGE}={CCX_VERSION}-1"], cwd=folder,
                           capture_output=True, text=True)
        if r.returncode != 0:
            why = "no source found" if "source package" in (r.stderr + r.stdout) or "deb-src" in r.stderr \
                else (r.stderr.strip().splitlines() or ["apt-get failed"])[-1]
            raise BuildError(f"apt-get source {PACKAGE}: {why}: {DEB_SRC_LINE}")
    for name, digest in SOURCE_FILES.items():
        path = folder / name
        if not path.is_file():
            raise BuildError(f"{path}: missing ({PACKAGE} {CCX_VERSION}-1's source package has it)")
        if _sha256(path) != digest:
            raise BuildError(f"{path}: SHA-256 differs from Debian bookworm's {PACKAGE} {CCX_VERSION}-1 ({digest[:12]}…)")
    tree = folder / TREE
    if not tree.is_dir():
        progress("ccx build: unpacking with dpkg-source (Debian's patches applied)")
        r = subprocess.run(["dpkg-source", "-x", DSC, TREE], cwd=folder, capture_output=True, text=True)
        if r.returncode != 0:
            raise BuildError(f"dpkg-source -x {folder / DSC}: {(r.stderr.strip().splitlines() or ['failed'])[-1]}")
    return tree


def _patch(src: Path) -> None:
    for name, old, new, count in PATCHES:
        path = src / name
        text = path.read_text()
        if text.count(old) != count:
            raise BuildError(f"{path}: not CalculiX {CCX_VERSION}'s (the text to patch is not found {count} times)")
        path.write_text(text.replace(old, new))
    makefile = src / "Makefile"
    text = makefile.read_text()
    if text.count(_MAKEFILE_ANCHOR) != 1 or "-lspooles" not in text:
        raise BuildError(f"{makefile}: not Debian's Makefile of CalculiX {CCX_VERSION} (apply Debian's patches)")
    makefile.write_text(text.replace(_MAKEFILE_ANCHOR, _MAKEFILE_ANCHOR + _MAKEFILE_ADDITION))
    (src / LAW_SOURCE).write_text(fortran_source(LAW_SOURCE))
    (src / ELEMENT_SOURCE).write_text(element_source())


def _make(src: Path, jobs: int, progress) -> None:
    n_sources = len(re.findall(r"^\S+\.[fc] \\?$", (src / "Makefile.inc").read_text(), flags=re.M)) + 3
    cmd = ["make", f"-j{jobs}", f"ccx_{CCX_VERSION}", f"CFLAGS={CFLAGS}", f"FFLAGS={FFLAGS}"]
    done, shown = 0, 0
    with open(src / "build.log", "w") as log, subprocess.Popen(cmd, cwd=src, stdout=subprocess.PIPE,
                                                                stderr=subprocess.STDOUT, text=True) as p:
        for line in p.stdout:
            log.write(line)
            if line.startswith(("cc ", "gfortran ")) and " -c " in line:
                done += 1
                if 10 * done // n_sources > shown:
                    shown = 10 * done // n_sources
                    progress(f"ccx build: compiled {done} of ~{n_sources} sources")
        p.wait()
    if p.returncode != 0:
        raise BuildError(f"make failed (exit {p.returncode}): see {src / 'build.log'}")


def build_ccx(*, source: Path | None = None, root: Path | None = None, jobs: int | None = None,
              progress=print, force: bool = False) -> Build:
    """Build (or find) the ccx with the interface law (module docstring). Raises BuildError."""
    root = Path(root) if root is not None else cache_root()
    if not force:
        found = find_build(root)
        if found is not None:
            progress(f"ccx build: found {found.executable} (cached)")
            return found
    missing = missing_tools()
    if missing:
        raise BuildError(f"building ccx needs: apt-get install {' '.join(missing)}")
    tree = _source_tree(source, root, progress)
    key = build_key()
    final = root / f"ccx-{key}"
    work = root / f"ccx-{key}.partial"
    shutil.rmtree(work, ignore_errors=True)
    progress(f"ccx build: copying the source into {work}")
    shutil.copytree(tree / f"ccx_{CCX_VERSION}" / "src", work / "src")
    _patch(work / "src")
    _make(work / "src", jobs or os.cpu_count() or 1, progress)
    shutil.move(str(work / "src" / f"ccx_{CCX_VERSION}"), str(work / "ccx"))
    shutil.move(str(work / "src" / "build.log"), str(work / "build.log"))
    shutil.rmtree(work / "src")
    info = {"ccx": CCX_VERSION, "package": f"{PACKAGE} {CCX_VERSION}-1 (Debian bookworm)", "key": key,
            "source_sha256": SOURCE_FILES, "cflags": CFLAGS, "fflags": FFLAGS, "gfortran": _compiler_version(),
            "element": ELEMENT_SOURCE, "law": LAW_SOURCE}
    (work / "build.json").write_text(json.dumps(info, indent=1) + "\n")
    if final.exists():
        shutil.rmtree(final)
    os.replace(work, final)
    progress(f"ccx build: {final / 'ccx'}")
    return Build(final / "ccx", final, info, cached=False)
