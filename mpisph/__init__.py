"""mpisph: MPI-parallel SPH for fluids and geomaterials.

numba's on-disk cache recompiles a kernel when its own file changes, but not when a kernel it calls
from another file does (numba/numba#1833): the caller keeps the callee's old code, compiled into it.
So the kernels are cached in a folder named for the content of every source file of the package,
under NUMBA_CACHE_DIR if set, else in the package's __pycache__: any change of the sources (a pull,
an edit) starts a new folder and recompiles everything once; old folders can be deleted.
"""

import hashlib
import os
from pathlib import Path

import numba

__version__ = "0.1.0"


def kernel_cache_dir():
    """The folder of the compiled kernels for the sources as they are (module docstring)."""
    package = Path(__file__).resolve().parent
    digest = hashlib.sha256()
    for path in sorted(package.rglob("*.py")):
        digest.update(path.relative_to(package).as_posix().encode() + b"\0" + path.read_bytes() + b"\0")
    base = os.environ.get("NUMBA_CACHE_DIR") or str(package / "__pycache__")
    return os.path.join(base, "kernels-" + digest.hexdigest()[:16])


numba.config.CACHE_DIR = kernel_cache_dir()  # before any module of the package defines a kernel
