#!/usr/bin/env bash
# PySPH side by side with mpisph on the same cases, 1 core and 2 MPI ranks.
#
# What it does:
#   1. Installs PySPH from PyPI (default 1.0b2) into its own virtual environment in a
#      scratch directory, never into the project's .venv: Cython, mako, numpy, cyarray,
#      compyle, pytools, Beaker, then (for MPI) mpi4py and pyzoltan built against Debian's
#      libtrilinos-zoltan-dev (apt-get installed when missing and running as root), then
#      PySPH itself with `pip install --no-build-isolation`. Each step is skipped when
#      already done. No PySPH code lives in this repository.
#   2. Runs PySPH's elliptical_drop and dam_break_2d examples and the mpisph cases of the
#      same names with the same particle spacing, h = 1.3 dx, Wendland C2 kernel (PySPH's
#      WendlandQuintic is Wendland C2, support 2h) and end time, each on 1 core (PySPH
#      serial, no OpenMP) and on 2 MPI ranks, after one warm-up run of each code so that
#      numba compilation (mpisph) and Cython code generation (PySPH) are excluded.
#      PySPH's dam_break_2d sets h and the mass from its module default dx=0.03 whatever
#      --dx says: the script copies the example into the scratch directory and patches
#      the copy with sed so that h = hdx*dx and m = rho0*dx^2 (and drops its matplotlib
#      post-processing). mpisph's elliptical drop is run with c0=1400, PySPH's value.
#   3. Prints, one figure per line with the command that produced it: particles, steps,
#      solver-loop and whole-process wall times, particle-steps/s/core, and the ratios
#      PySPH time / mpisph time on 1 core and on 2 ranks (see benchmarks/peers/compare.py).
#   A failed or timed-out run stops the script with a message and a non-zero exit.
#
# Run:    bash benchmarks/peers/pysph.sh
# Takes:  about 9 minutes on the 2-core machine when PySPH is installed and the machine is
#         idle (the longest single run, PySPH's dam break on 2 ranks, ~2 min); the first
#         time about 5 more (apt zoltan, pyzoltan and the PySPH Cython build, ~3 min of it,
#         and PySPH's code generation in the warm-ups). Don't run other heavy work
#         meanwhile: the figures assume 2 idle cores.
# Env:
#   MPISPH_BENCH_SCRATCH   scratch directory (default ${TMPDIR:-/tmp}/mpisph-bench): the
#                          venv (pysph-venv/), the patched example, run outputs and logs
#   PYSPH_VERSION          PySPH version from PyPI (default 1.0b2)
#   PYSPH_BENCH_PYTHON     interpreter the venv is made from (default python3; 3.11 tested)
#   MPISPH_BENCH_TIMEOUT   seconds after which one run is killed and the script fails (600)
#   MPISPH_BENCH_IDLE_WAIT seconds to wait, before each timed run, for the cores to be >= 90%
#                          idle (300); then it runs anyway. Each run's CPU time is checked
#                          against its solver-loop time x ranks; a run that shared its
#                          cores with other work is made again (MPISPH_BENCH_RETRIES
#                          times, default 2), then kept with a WARNING line in the summary.
#   MPISPH_BENCH_NO_MPI=1  skip PySPH's MPI part, as if it could not be built
#   MPISPH_BENCH_QUICK=1   tiny sizes and end times, to check the script (figures meaningless)
# PySPH also keeps its generated, compiled code in ~/.pysph/source (its own fixed place).

set -euo pipefail

case "${1:-}" in
    -h|--help) sed -n '2,/^$/{/^$/q;s/^# \{0,1\}//;p}' "$0"; exit 0 ;;  # the comment above
    "") ;;
    *) echo "pysph.sh: takes no arguments (settings are environment variables: bash $0 --help)" >&2; exit 2 ;;
esac

REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
HERE="$REPO/benchmarks/peers"
SCRATCH="${MPISPH_BENCH_SCRATCH:-${TMPDIR:-/tmp}/mpisph-bench}"
VENV="$SCRATCH/pysph-venv"
PYSPH_VERSION="${PYSPH_VERSION:-1.0b2}"
BASE_PYTHON="${PYSPH_BENCH_PYTHON:-python3}"
TIMEOUT="${MPISPH_BENCH_TIMEOUT:-600}"
IDLE_WAIT="${MPISPH_BENCH_IDLE_WAIT:-300}"
RETRIES="${MPISPH_BENCH_RETRIES:-2}"
MPISPH_PY="$REPO/.venv/bin/python"
INSTALL_LOG="$SCRATCH/install.log"
RUNS="$SCRATCH/runs"
TSV="$RUNS/runs.tsv"

# Debian's libtrilinos-zoltan-dev: what pyzoltan's and PySPH's setup.py read.
ZOLTAN_INC=/usr/include/trilinos
ZOLTAN_LIB=/usr/lib/x86_64-linux-gnu
[ -d "$ZOLTAN_LIB" ] || ZOLTAN_LIB="/usr/lib/$(gcc -print-multiarch 2>/dev/null || echo .)"

# The cases. Elliptical drop: PySPH takes --nx (dx = 1/nx); mpisph gets the same dp.
# Dam break: ~25k fluid particles (PySPH 24976, mpisph 24642).
ED_NX=60; ED_T=0.0076
DB_DX=0.009; DB_T=0.2
if [ "${MPISPH_BENCH_QUICK:-0}" = 1 ]; then
    ED_NX=25; ED_T=0.001
    DB_DX=0.04; DB_T=0.01
fi

die() { echo "pysph.sh: $*" >&2; exit 1; }
say() { echo "pysph.sh: $*"; }

mkdir -p "$SCRATCH" "$RUNS"
[ -x "$MPISPH_PY" ] || die "no $MPISPH_PY: run scripts/bootstrap.sh first"
ED_DP="$("$MPISPH_PY" -c "print(1 / $ED_NX)")"  # PySPH's dx = 1.0/nx, the same float
CORES="$(getconf _NPROCESSORS_ONLN)"
# shellcheck source=scripts/mpi_env.sh source-path=SCRIPTDIR/../..
source "$REPO/scripts/mpi_env.sh"
export OMP_NUM_THREADS=1

# ---------------------------------------------------------------- install
: >"$INSTALL_LOG"
pip_install() {  # pip_install ARGS...: into the PySPH venv, output to the install log
    echo "+ pip install $*" >>"$INSTALL_LOG"
    timeout 1800 "$VENV/bin/python" -m pip install --no-input "$@" >>"$INSTALL_LOG" 2>&1
}
install_failed() {
    echo "--- last lines of $INSTALL_LOG ---" >&2
    grep -v "^WARNING: Location" "$INSTALL_LOG" | tail -n 25 >&2
    die "$*"
}
vpy() { "$VENV/bin/python" -c "$1" >/dev/null 2>&1; }

if [ ! -x "$VENV/bin/python" ]; then
    say "creating the PySPH venv $VENV"
    "$BASE_PYTHON" -m venv "$VENV" || die "could not create a venv with $BASE_PYTHON"
    pip_install --upgrade pip setuptools wheel || install_failed "could not upgrade pip in $VENV"
fi

if ! vpy "import Cython, mako, numpy, cyarray, compyle, pytools, beaker, setuptools, wheel"; then
    say "installing PySPH's build dependencies into $VENV"
    pip_install "cython>=3,<4" mako "numpy>=2,<3" pytools Beaker setuptools wheel ||
        install_failed "could not install PySPH's build dependencies"
    pip_install --no-build-isolation cyarray compyle || install_failed "could not install cyarray, compyle"
fi

MPI_MISSING=""
if [ "${MPISPH_BENCH_NO_MPI:-0}" = 1 ]; then
    MPI_MISSING="MPISPH_BENCH_NO_MPI=1 was set"
elif ! command -v mpicc >/dev/null || ! command -v mpirun >/dev/null; then
    MPI_MISSING="no mpicc/mpirun on PATH (Debian: libopenmpi-dev openmpi-bin)"
fi
if [ -z "$MPI_MISSING" ] && [ ! -f "$ZOLTAN_INC/zoltan.h" ]; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
        say "installing libtrilinos-zoltan-dev with apt-get (for pyzoltan)"
        { apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q libtrilinos-zoltan-dev; } \
            >>"$INSTALL_LOG" 2>&1 || MPI_MISSING="apt-get install libtrilinos-zoltan-dev failed (see $INSTALL_LOG)"
    else
        MPI_MISSING="Zoltan is missing ($ZOLTAN_INC/zoltan.h) and this is not root with apt-get: apt-get install libtrilinos-zoltan-dev"
    fi
fi
if [ -z "$MPI_MISSING" ] && ! vpy "import mpi4py"; then
    say "installing mpi4py into $VENV"
    pip_install --no-build-isolation mpi4py || MPI_MISSING="pip install mpi4py failed (see $INSTALL_LOG)"
fi
export ZOLTAN_INCLUDE="$ZOLTAN_INC" ZOLTAN_LIBRARY="$ZOLTAN_LIB" USE_TRILINOS=1
if [ -z "$MPI_MISSING" ] && ! vpy "import pyzoltan.core.zoltan"; then
    say "building pyzoltan against Debian's Zoltan (ZOLTAN_INCLUDE=$ZOLTAN_INC ZOLTAN_LIBRARY=$ZOLTAN_LIB USE_TRILINOS=1)"
    pip_install --no-build-isolation --no-cache-dir pyzoltan ||
        MPI_MISSING="pyzoltan did not build against $ZOLTAN_INC, $ZOLTAN_LIB (see $INSTALL_LOG)"
fi

have_pysph() { vpy "import pysph, sys; sys.exit(pysph.__version__ != '$PYSPH_VERSION')"; }
have_parallel() { vpy "import pysph.parallel.parallel_manager"; }
if ! have_pysph || { [ -z "$MPI_MISSING" ] && ! have_parallel; }; then
    say "building PySPH $PYSPH_VERSION into $VENV (about 3 minutes)"
    if [ -n "$MPI_MISSING" ]; then  # serial build: keep setup.py from looking for Zoltan
        unset ZOLTAN_INCLUDE ZOLTAN_LIBRARY USE_TRILINOS
    fi
    # --no-cache-dir: a cached wheel may have been built without the parallel module
    pip_install --no-build-isolation --no-cache-dir --force-reinstall --no-deps "pysph==$PYSPH_VERSION" ||
        install_failed "could not build PySPH $PYSPH_VERSION"
    have_pysph || install_failed "PySPH $PYSPH_VERSION installed but does not import"
fi
if [ -z "$MPI_MISSING" ] && ! have_parallel; then
    MPI_MISSING="PySPH was built without pysph.parallel.parallel_manager (see $INSTALL_LOG)"
fi
say "PySPH venv: $("$VENV/bin/python" -c "
import importlib.metadata as m
print(', '.join(f'{p} {m.version(p)}' for p in ('pysph', 'cython', 'numpy', 'compyle', 'cyarray', 'mpi4py', 'pyzoltan')
                if any(d.metadata['Name'].lower() == p for d in m.distributions())))")"
[ -z "$MPI_MISSING" ] || say "PySPH MPI comparison will be missing: $MPI_MISSING"

# The dam break example, patched so that h and the mass follow --dx.
DB_PY="$SCRATCH/cases/dam_break_2d_dx.py"
mkdir -p "$SCRATCH/cases"
DB_ORIG="$("$VENV/bin/python" -c "import pysph.examples.dam_break_2d as m; print(m.__file__)")"
sed -e 's/h=h, m=m/h=self.h, m=self.dx**2*ro/g' \
    -e '/^    app\.post_process(app\.info_filename)$/d' "$DB_ORIG" >"$DB_PY"
if [ "$(grep -c 'h=self.h, m=self.dx\*\*2\*ro' "$DB_PY")" != 2 ] || grep -q 'app.post_process' "$DB_PY"; then
    die "patching $DB_ORIG did not work (PySPH $PYSPH_VERSION's example differs): see $DB_PY"
fi

# ---------------------------------------------------------------- runs
: >"$TSV"
# run LABEL CASE CODE RANKS OUT_DIR -- COMMAND...: time it, fail loudly, record it (not
# warm-ups). A timed run that shared its cores with other work is made again, up to RETRIES times.
run() {
    local label=$1 case=$2 code=$3 ranks=$4 out=$5 shown rc why proc cpu row busy try=0
    shift 6
    shown="$(printf '%q ' "$@")"; shown="${shown% }"
    while :; do
        rm -rf "$out"
        case $label in warm*) ;; *) wait_idle ;; esac
        echo "[$label] $shown"
        rc=0
        # bash's time: wall time of the whole command, and the CPU time of it and all its
        # children (mpirun's ranks included), to tell whether it had its cores to itself.
        local TIMEFORMAT='%R %U %S'
        { time { (cd "$REPO" && exec timeout --kill-after=20 "$TIMEOUT" "$@") \
            >"$RUNS/$label.out" 2>&1 </dev/null; }; } 2>"$RUNS/$label.time" || rc=$?
        if [ "$rc" != 0 ]; then
            case $rc in 124 | 137) why="timed out after $TIMEOUT s" ;; *) why="exit code $rc" ;; esac
            echo "--- last lines of $RUNS/$label.out ---" >&2
            tail -n 25 "$RUNS/$label.out" >&2
            die "run $label FAILED ($why): $shown"
        fi
        read -r proc cpu < <(awk '{ printf "%s %.3f\n", $1, $2 + $3 }' "$RUNS/$label.time")
        echo "    ok, ${proc} s wall, ${cpu} s CPU"
        case $label in warm*) return ;; esac
        row="$(printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s' "$case" "$code" "$ranks" \
            "$RUNS/$label.out" "$out" "$proc" "$cpu" "$shown")"
        rc=0
        busy="$("$MPISPH_PY" "$HERE/compare.py" --busy-check <(echo "$row"))" || rc=$?
        [ "$rc" = 0 ] || [ "$rc" = 3 ] || die "compare.py could not read the log of $label: $busy"
        if [ "$rc" = 3 ] && [ "$try" -lt "$RETRIES" ]; then
            try=$((try + 1))
            say "$label shared its cores with other work ($busy): making it again ($try of $RETRIES)"
            continue
        fi
        echo "$row" >>"$TSV"
        return
    done
}

# Idle share of all cores over 2 s, in percent, from /proc/stat.
idle_percent() {
    local a b
    a=$(head -n 1 /proc/stat); sleep 2; b=$(head -n 1 /proc/stat)
    awk -v a="$a" -v b="$b" 'BEGIN { split(a, x); split(b, y); t = 0
        for (i = 2; i <= 9; i++) t += y[i] - x[i]
        printf "%d\n", (t > 0 ? 100 * (y[5] - x[5] + y[6] - x[6]) / t : 100) }'
}
# Before a timed run: wait (up to IDLE_WAIT s) until the cores are >= 90% idle.
wait_idle() {
    local waited=0 idle
    while idle=$(idle_percent); [ "$idle" -lt 90 ]; do
        [ "$waited" != 0 ] || say "machine busy ($idle% idle): waiting up to $IDLE_WAIT s before the next run"
        if [ "$waited" -ge "$IDLE_WAIT" ]; then
            say "still busy after $IDLE_WAIT s ($idle% idle): running anyway (see the CPU-time check at the end)"
            return
        fi
        sleep 8; waited=$((waited + 10))
    done
}

PYSPH_PY="$VENV/bin/python"
pysph_cmd() {  # pysph_cmd RANKS ARGS...: serial python, or mpirun -n RANKS
    if [ "$1" = 1 ]; then shift; CMD=("$PYSPH_PY" "$@"); else local n=$1; shift; CMD=(mpirun -n "$n" "$PYSPH_PY" "$@"); fi
}

say "mpisph tree: $(git -C "$REPO" describe --always --dirty 2>/dev/null || echo '?'); load average: $(cut -d' ' -f1-3 /proc/loadavg); $CORES cores"
say "all runs: OMP_NUM_THREADS=1 and the Open MPI settings of scripts/mpi_env.sh; run logs in $RUNS"

RANKS_PYSPH=(1 2)
[ -z "$MPI_MISSING" ] || RANKS_PYSPH=(1)

for case in elliptical_drop dam_break_2d; do
    if [ "$case" = elliptical_drop ]; then
        T=$ED_T
        PYSPH_ARGS=(-m pysph.examples.elliptical_drop --nx "$ED_NX" --kernel WendlandQuintic --tf "$T" --pfreq 1000000)
        MPISPH_SET=(--set "dp=$ED_DP" c0=1400)
    else
        T=$DB_T
        PYSPH_ARGS=("$DB_PY" --dx "$DB_DX" --hdx 1.3 --kernel WendlandQuintic --tf "$T" --pfreq 1000000)
        MPISPH_SET=(--set "dp=$DB_DX")
    fi
    T_WARM="$(awk -v t="$T" 'BEGIN { printf "%g", t / 50 }')"
    say "--- $case: end time $T s ---"
    # warm-ups: numba compiles mpisph's kernels, PySPH generates and compiles its code
    # (serial and parallel code differ), then the timed runs.
    for n in 1 2; do
        run "warm_${case}_mpisph_$n" "$case" mpisph "$n" "$RUNS/warm_${case}_mpisph_$n" -- \
            mpirun -n "$n" "$MPISPH_PY" -m mpisph "$case" "${MPISPH_SET[@]}" --t-end "$T_WARM" \
            --output-interval "$T_WARM" --out "$RUNS/warm_${case}_mpisph_$n"
    done
    for n in "${RANKS_PYSPH[@]}"; do
        pysph_cmd "$n" "${PYSPH_ARGS[@]}" --max-steps 5 -d "$RUNS/warm_${case}_pysph_$n"
        run "warm_${case}_pysph_$n" "$case" pysph "$n" "$RUNS/warm_${case}_pysph_$n" -- "${CMD[@]}"
    done
    for n in "${RANKS_PYSPH[@]}"; do
        pysph_cmd "$n" "${PYSPH_ARGS[@]}" -d "$RUNS/${case}_pysph_$n"
        run "${case}_pysph_$n" "$case" pysph "$n" "$RUNS/${case}_pysph_$n" -- "${CMD[@]}"
    done
    for n in 1 2; do
        run "${case}_mpisph_$n" "$case" mpisph "$n" "$RUNS/${case}_mpisph_$n" -- \
            mpirun -n "$n" "$MPISPH_PY" -m mpisph "$case" "${MPISPH_SET[@]}" --t-end "$T" \
            --output-interval "$T" --out "$RUNS/${case}_mpisph_$n"
    done
done

say "load average after the runs: $(cut -d' ' -f1-3 /proc/loadavg)"
echo
"$MPISPH_PY" "$HERE/compare.py" "$TSV" --mpi-missing "$MPI_MISSING"
echo "notes:"
echo "  PySPH $PYSPH_VERSION from PyPI, built in $VENV; mpisph from the work tree $REPO."
echo "  kernel: Wendland C2 with h = 1.3 dx, support 2h, in both codes (PySPH: --kernel WendlandQuintic)."
echo "  elliptical_drop: PySPH keeps the particles with r <= 1 of a lattice offset from the origin, mpisph its own"
echo "    lattice, so the counts differ slightly; mpisph is run with c0=1400 m/s, PySPH's value (mpisph's default: 1000)."
echo "  dam_break_2d: PySPH's example copied to $DB_PY with h = hdx*dx and m = rho0*dx^2 (the original keeps"
echo "    dx = 0.03 for both); PySPH has 4 layers of wall particles, mpisph 3; mpisph counts only moving particles."
echo "  steps differ: PySPH WCSPH with EPEC (elliptical drop) / PEC (dam break) and its adaptive CFL time step;"
echo "    mpisph dual-criteria time stepping. Time to solution (same end time) is the figure to compare."
echo "  mpisph is run without --quiet because --quiet also hides its closing timing/throughput lines."
echo "  issue's reference: PySPH 1.0b2, 2D dam break, 25k particles: 1.24e6 particle-steps/s on one core."
