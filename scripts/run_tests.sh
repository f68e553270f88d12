#!/usr/bin/env bash
# Run mpisph's test suite in three stages with the .venv Python:
#   (a) serial:  pytest -m "not mpi and not ranks", its test files shared among
#                one pytest-xdist worker per core               (timeout 2400 s)
#   (b) ranks:   pytest -m "ranks and not mpi" in one process: the tests that
#                start runs on several ranks (tests/conftest.py) (timeout 1800 s)
#   (c) MPI:     mpirun -n 2 pytest -m mpi --with-mpi          (timeout 600 s)
# Extra arguments are passed to every pytest run. pytest's exit code 5 ("no
# tests collected") counts as success for a stage, but if no test ran in
# any stage the script fails (set MPISPH_ALLOW_NO_TESTS=1 to allow that).
# The last line printed is "summary: N passed, M failed" (read by CI).
#
# MPISPH_TEST_PATHS overrides the test paths (default "tests/"), e.g. to try
# this script on a scratch directory; MPISPH_SERIAL_TIMEOUT / MPISPH_RANKS_TIMEOUT /
# MPISPH_MPI_TIMEOUT override the stage timeouts (seconds). The timeouts only end a
# hung run.
# MPISPH_TEST_WORKERS sets the serial stage's workers (default: the cores; 0 runs
# it in one process). A worker takes whole files (--dist loadfile), so a file's
# module fixtures run once. Stage (b) runs alone because ranks that wait for each
# other beside a second worker take turns on the cores: on 2 cores (2026-11-27)
# test_rank_agreement's runs took 822 s beside the other worker and 270 s alone.
# Set up .venv first with: bash scripts/bootstrap.sh test
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"

VPY="$ROOT/.venv/bin/python"
[ -x "$VPY" ] || { echo "run_tests: $VPY missing; run 'bash scripts/bootstrap.sh test' first" >&2; exit 1; }

# shellcheck source=scripts/mpi_env.sh
source "$ROOT/scripts/mpi_env.sh"
export VIRTUAL_ENV="$ROOT/.venv"
export PATH="$ROOT/.venv/bin:$PATH"
export PYTHONUNBUFFERED=1

read -r -a TEST_PATHS <<< "${MPISPH_TEST_PATHS:-tests/}"
SERIAL_TIMEOUT="${MPISPH_SERIAL_TIMEOUT:-2400}"
RANKS_TIMEOUT="${MPISPH_RANKS_TIMEOUT:-1800}"
MPI_TIMEOUT="${MPISPH_MPI_TIMEOUT:-600}"
WORKERS="${MPISPH_TEST_WORKERS:-$(nproc)}"

LOGDIR="$(mktemp -d "${TMPDIR:-/tmp}/mpisph-tests.XXXXXX")"
trap 'rm -rf "$LOGDIR"' EXIT

# Counts from the last pytest summary line in a log ("3 passed, 1 failed, 2 errors in 1.2s").
# Prints "<passed> <failed+errors>"; "0 0" when there is no summary line.
pytest_counts() {
    local line p f e
    line="$(grep -aE '([0-9]+ (passed|failed|errors?|skipped|deselected|xfailed|xpassed|warnings?)|no tests ran)[^ ]* in [0-9.]+s' "$1" 2>/dev/null | tail -n 1 || true)"
    p="$(grep -oE '[0-9]+ passed' <<< "$line" | grep -oE '[0-9]+' || true)"
    f="$(grep -oE '[0-9]+ failed' <<< "$line" | grep -oE '[0-9]+' || true)"
    e="$(grep -oE '[0-9]+ errors?' <<< "$line" | grep -oE '[0-9]+' || true)"
    echo "${p:-0} $(( ${f:-0} + ${e:-0} ))"
}

TOTAL_PASSED=0
TOTAL_FAILED=0
STATUS=0
STAGE_NOTES=()

# record_stage NAME RC PASSED FAILED TIMEOUT_MESSAGE
record_stage() {
    local name="$1" rc="$2" passed="$3" failed="$4" tmsg="$5"
    case "$rc" in
        0) STAGE_NOTES+=("$name: ok ($passed passed)") ;;
        5) STAGE_NOTES+=("$name: no tests collected") ;;
        124|137)
            echo "run_tests: $tmsg" >&2
            STAGE_NOTES+=("$name: TIMED OUT")
            STATUS=1 ;;
        *)
            STAGE_NOTES+=("$name: FAILED (exit $rc)")
            STATUS=1 ;;
    esac
    # A stage that failed without a pytest summary (crash, timeout) still counts as a failure.
    if [ "$rc" != 0 ] && [ "$rc" != 5 ] && [ "$failed" -eq 0 ]; then
        failed=1
    fi
    TOTAL_PASSED=$(( TOTAL_PASSED + passed ))
    TOTAL_FAILED=$(( TOTAL_FAILED + failed ))
}

# ---------------------------------------------------------------------------
# (a) serial tests
# ---------------------------------------------------------------------------
echo "== run_tests: serial tests (-m 'not mpi and not ranks', $WORKERS workers) =="
rc=0
timeout -k 30 "$SERIAL_TIMEOUT" "$VPY" -m pytest -q -m "not mpi and not ranks" -n "$WORKERS" --dist loadfile \
    --timeout=900 "${TEST_PATHS[@]}" "$@" \
    2>&1 | tee "$LOGDIR/serial.log" || rc=${PIPESTATUS[0]}
read -r s_passed s_failed < <(pytest_counts "$LOGDIR/serial.log")
record_stage "serial" "$rc" "$s_passed" "$s_failed" "serial tests timed out after $SERIAL_TIMEOUT s"

# ---------------------------------------------------------------------------
# (b) tests that start runs on several ranks, one at a time
# ---------------------------------------------------------------------------
echo "== run_tests: tests of runs on several ranks (-m 'ranks and not mpi', one process) =="
rc=0
timeout -k 30 "$RANKS_TIMEOUT" "$VPY" -m pytest -q -m "ranks and not mpi" --timeout=900 \
    "${TEST_PATHS[@]}" "$@" \
    2>&1 | tee "$LOGDIR/ranks.log" || rc=${PIPESTATUS[0]}
read -r r_passed r_failed < <(pytest_counts "$LOGDIR/ranks.log")
record_stage "ranks" "$rc" "$r_passed" "$r_failed" "tests of runs on several ranks timed out after $RANKS_TIMEOUT s"

# ---------------------------------------------------------------------------
# (c) MPI tests: every rank runs pytest; rank 0 prints live, every rank logs
# to its own file so the summaries can be told apart.
# ---------------------------------------------------------------------------
echo "== run_tests: MPI tests (mpirun -n 2, -m mpi --with-mpi) =="
rc=0
# shellcheck disable=SC2016
timeout -k 30 "$MPI_TIMEOUT" mpirun -n 2 bash -c '
    logdir="$0"
    rank="${OMPI_COMM_WORLD_RANK:-${PMI_RANK:-0}}"
    if [ "$rank" = 0 ]; then
        "$@" 2>&1 | tee "$logdir/mpi-rank$rank.log"
        exit "${PIPESTATUS[0]}"
    else
        exec "$@" > "$logdir/mpi-rank$rank.log" 2>&1
    fi' "$LOGDIR" "$VPY" -m pytest -q -m mpi --with-mpi --timeout=300 --timeout-method=thread "${TEST_PATHS[@]}" "$@" \
    || rc=$?
# A test passed if it passed on every rank, failed if it failed on any:
# take the smallest "passed" and the largest "failed" over the ranks.
m_passed=""
m_failed=0
for f in "$LOGDIR"/mpi-rank*.log; do
    [ -e "$f" ] || continue
    read -r p fl < <(pytest_counts "$f")
    if [ -z "$m_passed" ] || [ "$p" -lt "$m_passed" ]; then m_passed="$p"; fi
    if [ "$fl" -gt "$m_failed" ]; then m_failed="$fl"; fi
done
m_passed="${m_passed:-0}"
if [ "$rc" != 0 ] && [ "$rc" != 5 ]; then
    for f in "$LOGDIR"/mpi-rank*.log; do
        [ -e "$f" ] || continue
        [ "$f" = "$LOGDIR/mpi-rank0.log" ] && continue
        echo "---- $(basename "$f" .log) (last 40 lines) ----"
        tail -n 40 "$f"
    done
fi
# mpirun reports the first non-zero exit code of a rank, so 5 means "no tests" on the ranks.
record_stage "mpi" "$rc" "$m_passed" "$m_failed" "MPI tests timed out (deadlock?)"

# ---------------------------------------------------------------------------
echo "== run_tests: ${STAGE_NOTES[*]} =="
if [ "$STATUS" -eq 0 ] && [ $(( TOTAL_PASSED + TOTAL_FAILED )) -eq 0 ] && [ "${MPISPH_ALLOW_NO_TESTS:-0}" != 1 ]; then
    echo "run_tests: no test ran in any stage" >&2
    STATUS=1
fi
echo "summary: $TOTAL_PASSED passed, $TOTAL_FAILED failed"
exit "$STATUS"
