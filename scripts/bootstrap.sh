#!/usr/bin/env bash
# Set up everything mpisph needs, then run the demo or the test suite.
#
#   bash scripts/bootstrap.sh demo [extra args for python -m mpisph]
#   bash scripts/bootstrap.sh test [extra args for pytest]
#
# Idempotent: every step checks first and skips what is already done.
#   1. Debian packages openmpi-bin libopenmpi-dev libhdf5-openmpi-dev
#      (installed with apt-get only when missing and we are root; when they are
#      all present apt-get is never called, so this works without root).
#   2. .venv/ in the repo root (python3 -m venv).
#   3. Python packages in .venv: mpi4py built from source against Debian's
#      Open MPI, h5py built from source against Debian's parallel HDF5, the
#      rest from PyPI, and this project in editable mode. A stamp file keyed on
#      a hash of the requirement list + pyproject.toml + the venv's Python
#      records a finished install; a quick import check confirms it.
#   4. For the tests only: the readers the frames must open in (tests/test_paraview.py):
#      Debian's ParaView with pvpython (paraview python3-paraview, without their
#      recommends; apt-get only when missing) and the oldest VTK mpisph supports,
#      vtk==9.2.6 with numpy<2, in its own venv .venv/oldest-vtk.
#
# The demo runs the granular column collapse (column_collapse_2d with
# --set dp=0.005, about a minute on 2 ranks) and ends with `python -m mpisph plot`,
# which prints the path of a PNG of the deposit.
#
# Environment knobs: MPISPH_DEMO_CASE (default column_collapse_2d; dp=0.005 is
# set only for that case), MPISPH_DEMO_OUT (default runs/CASE), MPISPH_PYTHON
# (python used to create the venv, default python3).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"

log() { printf '[bootstrap] %s\n' "$*"; }
die() { printf '[bootstrap] ERROR: %s\n' "$*" >&2; exit 1; }

usage() {
    echo "usage: bash scripts/bootstrap.sh demo|test [extra args]" >&2
    exit 2
}

[ $# -ge 1 ] || usage
MODE="$1"
shift
case "$MODE" in
    demo|test) ;;
    *) usage ;;
esac

T_START=$(date +%s)
VENV="$ROOT/.venv"
VPY="$VENV/bin/python"
BASE_PY="${MPISPH_PYTHON:-python3}"

# Python packages besides mpi4py and h5py (those two are built from source below).
PY_DEPS=(numpy numba meshio pytest pytest-timeout pytest-mpi pytest-xdist matplotlib vtk psutil)
# Import names checked to decide whether the venv is complete.
PY_MODULES=(numpy numba meshio pytest pytest_timeout pytest_mpi xdist matplotlib vtk psutil mpisph)

# ---------------------------------------------------------------------------
# 1. Debian packages
# ---------------------------------------------------------------------------
DEB_PKGS=(openmpi-bin libopenmpi-dev libhdf5-openmpi-dev)

deb_installed() {
    dpkg -s "$1" 2>/dev/null | grep -q '^Status: install ok installed'
}

missing=()
for p in "${DEB_PKGS[@]}"; do
    deb_installed "$p" || missing+=("$p")
done
venv_python_ok() {
    [ -x "$VPY" ] && "$VPY" -c 'import sys; sys.exit(sys.version_info < (3, 11))' >/dev/null 2>&1
}
# What creating the venv and the two source builds need, checked only when the
# venv is not finished yet, and added only when absent (pyenv's Python on the
# project machines already has venv and headers; gcc is there too).
if ! { venv_python_ok && [ -f "$VENV/.mpisph-bootstrap.sha256" ]; }; then
    if ! venv_python_ok; then
        if ! command -v "$BASE_PY" >/dev/null 2>&1; then
            missing+=(python3 python3-venv)
        else
            "$BASE_PY" -c 'import venv, ensurepip' >/dev/null 2>&1 || missing+=(python3-venv)
        fi
    fi
    PY_FOR_HEADERS="$BASE_PY"
    venv_python_ok && PY_FOR_HEADERS="$VPY"
    if command -v "$PY_FOR_HEADERS" >/dev/null 2>&1; then
        "$PY_FOR_HEADERS" -c 'import os, sys, sysconfig; sys.exit(not os.path.exists(os.path.join(sysconfig.get_paths()["include"], "Python.h")))' \
            >/dev/null 2>&1 || missing+=(python3-dev)
    else
        missing+=(python3-dev)
    fi
    command -v gcc >/dev/null 2>&1 || missing+=(gcc)
fi

if [ ${#missing[@]} -gt 0 ]; then
    if [ "$(id -u)" -ne 0 ]; then
        die "missing Debian packages: ${missing[*]} (not root: run 'sudo apt-get install -y ${missing[*]}' first)"
    fi
    log "installing Debian packages: ${missing[*]}"
    apt-get update
    DEBIAN_FRONTEND=noninteractive apt-get install -y "${missing[@]}"
else
    log "Debian packages present (${DEB_PKGS[*]})"
fi

command -v mpicc >/dev/null 2>&1 || die "mpicc not found on PATH although libopenmpi-dev is installed"
command -v mpirun >/dev/null 2>&1 || die "mpirun not found on PATH although openmpi-bin is installed"
MPICC_BIN="$(command -v mpicc)"
[ -x /usr/bin/mpicc ] && MPICC_BIN=/usr/bin/mpicc

# Debian's parallel HDF5 (include/ and lib/ under one prefix).
HDF5_MPI_DIR=""
for d in "/usr/lib/$(gcc -print-multiarch 2>/dev/null || echo x86_64-linux-gnu)/hdf5/openmpi" /usr/lib/*/hdf5/openmpi; do
    if [ -d "$d/include" ] && [ -d "$d/lib" ]; then HDF5_MPI_DIR="$d"; break; fi
done
[ -n "$HDF5_MPI_DIR" ] || die "Debian's parallel HDF5 not found under /usr/lib/*/hdf5/openmpi"

# shellcheck source=scripts/mpi_env.sh
source "$ROOT/scripts/mpi_env.sh"

# ---------------------------------------------------------------------------
# 2. The virtual environment
# ---------------------------------------------------------------------------
if venv_python_ok; then
    log ".venv present ($("$VPY" -V 2>&1))"
else
    if [ -e "$VENV" ]; then
        die ".venv exists but .venv/bin/python does not run or is older than 3.11 (was its Python removed?); delete it with 'rm -rf .venv' and rerun"
    fi
    "$BASE_PY" -c 'import sys; sys.exit(sys.version_info < (3, 11))' \
        || die "$BASE_PY is $("$BASE_PY" -V 2>&1); mpisph needs Python >= 3.11"
    log "creating .venv with $("$BASE_PY" -V 2>&1)"
    "$BASE_PY" -m venv "$VENV"
fi

# ---------------------------------------------------------------------------
# 3. Python packages
# ---------------------------------------------------------------------------
PIP=("$VPY" -m pip --disable-pip-version-check)
STAMP="$VENV/.mpisph-bootstrap.sha256"
want_hash="$({
    printf '%s\n' "${PY_DEPS[@]}" mpi4py h5py "$MPICC_BIN" "$HDF5_MPI_DIR"
    cat pyproject.toml
    "$VPY" -VV
} | sha256sum | cut -d' ' -f1)"

# Prints one word per problem: missing:<module>, mpi4py-not-openmpi, h5py-not-mpi, ...
# Runs isolated (-I) so the repo's own directory does not count as installed.
venv_problems() {
    "$VPY" -I - "$ROOT" "${PY_MODULES[@]}" <<'PY' 2>/dev/null || echo "check-crashed"
import importlib.util, os, sys
root, mods = sys.argv[1], sys.argv[2:]
for m in mods:
    try:
        spec = importlib.util.find_spec(m)
    except Exception:
        spec = None
    if spec is None:
        print("missing:" + m)
    elif m == "mpisph":
        locs = [os.path.realpath(p) for p in (spec.submodule_search_locations or [])]
        if os.path.realpath(os.path.join(root, "mpisph")) not in locs:
            print("mpisph-not-this-checkout")
try:
    import mpi4py
    mpi4py.rc.initialize = False
    mpi4py.rc.finalize = False
    from mpi4py import MPI
    if "Open MPI" not in MPI.Get_library_version():
        print("mpi4py-not-openmpi")
except Exception:
    print("mpi4py-broken")
try:
    import h5py
    if not h5py.get_config().mpi:
        print("h5py-not-mpi")
except Exception:
    print("h5py-broken")
PY
}

mpi4py_ok() {
    "$VPY" -I -c '
import sys, mpi4py
mpi4py.rc.initialize = False
mpi4py.rc.finalize = False
from mpi4py import MPI
sys.exit(0 if "Open MPI" in MPI.Get_library_version() else 1)' >/dev/null 2>&1
}

h5py_ok() {
    "$VPY" -I -c 'import h5py, sys; sys.exit(0 if h5py.get_config().mpi else 1)' >/dev/null 2>&1
}

have_dist() {
    "$VPY" -I -c 'import importlib.metadata as m, sys; m.distribution(sys.argv[1])' "$1" >/dev/null 2>&1
}

problems="$(venv_problems)"
if [ -f "$STAMP" ] && [ "$(cat "$STAMP")" = "$want_hash" ] && [ -z "$problems" ]; then
    log "Python packages already installed (stamp matches)"
else
    [ -n "$problems" ] && log "venv needs work: ${problems//$'\n'/ }"
    rm -f "$STAMP"

    # mpi4py, from source, against Debian's Open MPI (never a wheel bundling its own MPI).
    if mpi4py_ok; then
        log "mpi4py (Open MPI) present"
    else
        if have_dist mpi4py; then
            log "removing mpi4py that is not built against Open MPI"
            "${PIP[@]}" uninstall -y -q mpi4py
        fi
        log "building mpi4py from source with $MPICC_BIN"
        MPICC="$MPICC_BIN" "${PIP[@]}" install -q --no-binary=mpi4py mpi4py
        if ! mpi4py_ok; then
            log "mpi4py from pip's wheel cache is not Open MPI; rebuilding without cache"
            "${PIP[@]}" uninstall -y -q mpi4py
            MPICC="$MPICC_BIN" "${PIP[@]}" install -q --no-cache-dir --no-binary=mpi4py mpi4py
        fi
        mpi4py_ok || die "mpi4py does not report Open MPI after building it"
    fi

    log "installing ${PY_DEPS[*]}"
    "${PIP[@]}" install -q --no-binary=mpi4py "${PY_DEPS[@]}"

    # h5py, from source, against Debian's parallel HDF5 (~2 min).
    if h5py_ok; then
        log "h5py (parallel HDF5) present"
    else
        if have_dist h5py; then
            log "removing h5py that is not built with MPI"
            "${PIP[@]}" uninstall -y -q h5py
        fi
        # Built without build isolation, against the venv's own mpi4py: in an
        # isolated build h5py pins an old mpi4py (4.0.0 on Python 3.11) for its
        # build env and pip then compiles that from source too, which took gcc
        # >13 min and >20 GB of RAM here. H5PY_SETUP_REQUIRES=0 stops
        # setuptools from fetching that pin itself.
        log "installing h5py's build requirements (Cython, pkgconfig, setuptools)"
        "${PIP[@]}" install -q "Cython>=3.0.0,<4" "pkgconfig>=1.5.5" "setuptools>=77.0.1" wheel
        build_h5py() {
            HDF5_MPI=ON CC="$MPICC_BIN" HDF5_DIR="$HDF5_MPI_DIR" MPICC="$MPICC_BIN" H5PY_SETUP_REQUIRES=0 \
                "${PIP[@]}" install -q --no-build-isolation --no-binary=h5py,mpi4py "$@" h5py
        }
        log "building h5py from source against $HDF5_MPI_DIR (takes ~2 min)"
        build_h5py
        if ! h5py_ok; then
            log "h5py from pip's wheel cache is not MPI-enabled; rebuilding without cache"
            "${PIP[@]}" uninstall -y -q h5py
            build_h5py --no-cache-dir
        fi
        h5py_ok || die "h5py.get_config().mpi is False after building h5py"
    fi

    log "installing mpisph in editable mode"
    "${PIP[@]}" install -q --no-binary=mpi4py,h5py -e ".[test]"

    problems="$(venv_problems)"
    [ -z "$problems" ] || die "venv still incomplete after install: ${problems//$'\n'/ }"
    echo "$want_hash" > "$STAMP"
    log "Python packages installed"
fi

export VIRTUAL_ENV="$VENV"
export PATH="$VENV/bin:$PATH"

# ---------------------------------------------------------------------------
# 4. The frame readers the tests open frames with
# ---------------------------------------------------------------------------
VIEWER_PKGS=(paraview python3-paraview)
OLDEST_VTK=(vtk==9.2.6 "numpy<2")
OLD_VENV="$VENV/oldest-vtk"
if [ "$MODE" = test ]; then
    viewers_missing=()
    for p in "${VIEWER_PKGS[@]}"; do
        deb_installed "$p" || viewers_missing+=("$p")
    done
    if [ ${#viewers_missing[@]} -gt 0 ]; then
        [ "$(id -u)" -eq 0 ] || die "missing Debian packages: ${viewers_missing[*]} (not root: run 'sudo apt-get install -y --no-install-recommends ${viewers_missing[*]}' first)"
        log "installing Debian's ParaView for the frame tests: ${viewers_missing[*]}"
        apt-get update
        DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${viewers_missing[@]}"
    else
        log "Debian's ParaView present ($(pvpython --version 2>/dev/null | head -n 1))"
    fi
    if "$OLD_VENV/bin/python" -I -c 'import vtk, sys; sys.exit(vtk.vtkVersion.GetVTKVersion() != "9.2.6")' >/dev/null 2>&1; then
        log "oldest VTK reader present ($OLD_VENV)"
    else
        log "installing the oldest VTK reader into $OLD_VENV: ${OLDEST_VTK[*]}"
        rm -rf "$OLD_VENV"
        "$VPY" -m venv "$OLD_VENV"
        "$OLD_VENV/bin/python" -m pip --disable-pip-version-check install -q "${OLDEST_VTK[@]}"
    fi
fi

log "set-up done in $(( $(date +%s) - T_START )) s"

# ---------------------------------------------------------------------------
# 5. Run
# ---------------------------------------------------------------------------
case "$MODE" in
    demo)
        case_name="${MPISPH_DEMO_CASE:-column_collapse_2d}"
        out_dir="${MPISPH_DEMO_OUT:-runs/$case_name}"
        case_args=()
        # coarser than the case's default 0.002: 800 particles, about a minute on 2 ranks, unless
        # the extra arguments set dp themselves (`demo --set dp=0.002`: a dp given twice is refused)
        user_dp=0
        for arg in "$@"; do
            case "$arg" in dp=*) user_dp=1 ;; esac
        done
        if [ "$case_name" = column_collapse_2d ] && [ "$user_dp" = 0 ]; then
            case_args=(--set dp=0.005)
        fi
        log "running demo: mpirun -n 2 .venv/bin/python -m mpisph $case_name ${case_args[*]} --out $out_dir $*"
        mpirun -n 2 "$VPY" -m mpisph "$case_name" "${case_args[@]}" --out "$out_dir" "$@"
        log "plotting: .venv/bin/python -m mpisph plot $out_dir"
        exec "$VPY" -m mpisph plot "$out_dir"
        ;;
    test)
        log "running tests: scripts/run_tests.sh $*"
        exec bash "$ROOT/scripts/run_tests.sh" "$@"
        ;;
esac
