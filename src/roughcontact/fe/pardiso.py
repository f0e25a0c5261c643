"""Intel MKL PARDISO called through ctypes (the optional extra ``[pardiso]``; Schenk & Gärtner,
Future Gener. Comput. Syst. 20, 2004; oneMKL Developer Reference, "pardiso" and "pardiso iparm
Parameter").

pypardiso (the extra) finds MKL's runtime library and wraps it for one-off solves; the
engine's Newton loop solves hundreds of times with one kept factor (:mod:`.linear_solvers`), and
pypardiso's wrapper compares the whole matrix with the factored one, copies both index arrays
and (for every new solver object) searches the site-packages tree for the library before each
of those solves. :class:`PardisoFactor` calls ``pardiso`` itself: MKL's defaults from
``pardisoinit``, zero-based indices (iparm[34] = 1, no copies), the numeric phase once and the
solve phase (33) directly, and optionally

* single precision (iparm[27] = 1): the factor in float32, half the memory and half the
  memory traffic of a triangular solve (the solve is memory-bound). Its solve is then an
  approximate inverse to about 1e-7 of cond(A), used only as the preconditioner of GMRES, which
  recovers the double-precision residual (:class:`.linear_solvers.ReusedFactor`);
* the forward/backward substitution's threading (iparm[24]).

Matrix types: 2 (real symmetric positive definite: Cholesky of the upper triangle; a zero or
negative pivot is an error) and 11 (real unsymmetric: LU with MKL's pivot perturbation, scaling
and weighted matching by default). Errors raise :class:`numpy.linalg.LinAlgError` naming
PARDISO's code. The factor's memory is released (phase −1) when the object is collected.
"""

from __future__ import annotations

import ctypes
import functools
import weakref

import numpy as np
import scipy.sparse as sp

__all__ = ["PardisoFactor", "mkl_library", "ERRORS"]

#: PARDISO's error codes (oneMKL Developer Reference, "pardiso", output parameter ``error``)
ERRORS = {-1: "input inconsistent", -2: "not enough memory", -3: "reordering problem",
          -4: "zero pivot, numerical factorization or iterative refinement problem",
          -5: "unclassified (internal) error", -6: "reordering failed", -7: "diagonal matrix is singular",
          -8: "32-bit integer overflow problem", -9: "not enough memory for OOC",
          -10: "error opening OOC files", -11: "read/write error with OOC files",
          -12: "pardiso_64 called from 32-bit library", -13: "interrupted by the mkl_progress function",
          -15: "reordering failed"}

_INT_P = ctypes.POINTER(ctypes.c_int32)
_PT_P = ctypes.POINTER(ctypes.c_int64)


@functools.cache
def mkl_library() -> ctypes.CDLL:
    """MKL's runtime library, located once per process by pypardiso (ImportError/OSError when
    the extra is not installed), with the argument types of ``pardiso`` and ``pardisoinit``."""
    import pypardiso

    lib = pypardiso.PyPardisoSolver().libmkl
    lib.pardiso.argtypes = [_PT_P, _INT_P, _INT_P, _INT_P, _INT_P, _INT_P, ctypes.c_void_p, _INT_P, _INT_P,
                            _INT_P, _INT_P, _INT_P, _INT_P, ctypes.c_void_p, ctypes.c_void_p, _INT_P]
    lib.pardiso.restype = None
    lib.pardisoinit.argtypes = [_PT_P, _INT_P, _INT_P]
    lib.pardisoinit.restype = None
    return lib


def _int(v: int):
    return ctypes.byref(ctypes.c_int32(v))


class _Handle:
    """PARDISO's internal handle and the arrays every call passes (kept alive together)."""

    def __init__(self, mtype: int, iparm: np.ndarray, n: int, data, ia, ja):
        self.pt = np.zeros(64, dtype=np.int64)
        self.mtype, self.iparm, self.n, self.data, self.ia, self.ja = mtype, iparm, n, data, ia, ja
        self.perm = np.zeros(1, dtype=np.int32)

    def call(self, phase: int, b=None, x=None) -> int:
        error = ctypes.c_int32(0)
        mkl_library().pardiso(
            self.pt.ctypes.data_as(_PT_P), _int(1), _int(1), _int(self.mtype), _int(phase), _int(self.n),
            self.data.ctypes.data, self.ia.ctypes.data_as(_INT_P), self.ja.ctypes.data_as(_INT_P),
            self.perm.ctypes.data_as(_INT_P), _int(1), self.iparm.ctypes.data_as(_INT_P), _int(0),
            None if b is None else b.ctypes.data, None if x is None else x.ctypes.data, ctypes.byref(error))
        return error.value


def _release(handle: _Handle) -> None:
    try:
        handle.call(-1)
    except Exception:  # noqa: BLE001  (interpreter shutdown: MKL may be gone already)
        pass


class PardisoFactor:
    """b ↦ A⁻¹ b from one PARDISO factorisation (module docstring).

    A           scipy sparse matrix, square; for ``symmetric`` only its upper triangle is read.
    symmetric   Cholesky (mtype 2) instead of LU (mtype 11).
    single      factor and solve in single precision (a preconditioner, not a solver).
    solve_threads  iparm[24]: 0 MKL's default, 1 the parallel forward/backward substitution,
                2 the parallel one of a two-level factorisation (oneMKL reference).

    ``perturbed_pivots`` (iparm[13]) and ``factor_bytes`` (iparm[16], the factor's memory in
    kB × 1024) are read after the factorisation."""

    def __init__(self, A, symmetric: bool, single: bool = False, solve_threads: int = 0):
        lib = mkl_library()
        mtype = 2 if symmetric else 11
        iparm = np.zeros(64, dtype=np.int32)
        # MKL's default iparm for this matrix type (pardisoinit also zeroes a handle: a scratch one)
        lib.pardisoinit(np.zeros(64, dtype=np.int64).ctypes.data_as(_PT_P), _int(mtype), iparm.ctypes.data_as(_INT_P))
        iparm[0] = 1            # the values below are supplied
        iparm[34] = 1           # zero-based ia, ja
        iparm[27] = 1 if single else 0
        iparm[24] = solve_threads
        A = sp.triu(A, format="csr") if symmetric else sp.csr_matrix(A)
        A.sort_indices()
        if A.shape[0] != A.shape[1] or A.shape[0] == 0:
            raise ValueError(f"PARDISO: a square non-empty matrix expected, got shape {A.shape}")
        self.dtype = np.float32 if single else np.float64
        self._h = _Handle(mtype, iparm, A.shape[0], A.data.astype(self.dtype),
                          A.indptr.astype(np.int32), A.indices.astype(np.int32))
        weakref.finalize(self, _release, self._h)
        error = self._h.call(12)
        if error:
            raise np.linalg.LinAlgError(f"PARDISO: error {error} ({ERRORS.get(error, 'unknown')}) in the factorisation")
        self.perturbed_pivots = int(iparm[13])
        self.factor_bytes = int(iparm[16]) * 1024

    def __call__(self, b: np.ndarray) -> np.ndarray:
        """A⁻¹ b of a vector b (float64 result)."""
        b = np.ascontiguousarray(b, dtype=self.dtype)
        if b.shape != (self._h.n,):
            raise ValueError(f"PARDISO: a vector of {self._h.n} values expected, got shape {b.shape}")
        x = np.empty_like(b)
        error = self._h.call(33, b, x)
        if error:
            raise np.linalg.LinAlgError(f"PARDISO: error {error} ({ERRORS.get(error, 'unknown')}) in the solve")
        return x.astype(np.float64, copy=False)
