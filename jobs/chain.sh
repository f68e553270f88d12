# What the Slurm and PBS job scripts share (sourced by both): a node-local numba cache warmed by
# one rank per node, the run, and a follow-up job from the run's last frame when a signal stopped
# it before t_end (a chain of jobs). With MPISPH_DRY_RUN=1 every command is printed, not run (the
# check that the case exists still reads it).
#
# The batch script sets, before sourcing:
#   LAUNCH=(...)             the launcher of all ranks (srun, mpirun)
#   LAUNCH_PER_NODE=(...)    the launcher of one rank per node (the warm-up)
#   submit_after ARGS...     a function that submits the batch script again, to start after this
#                            job, with the mpisph arguments ARGS (CASE --restart FRAME), through run
# sets JOB_ID (the batch system's job id) and, where the batch system sends no signal before the
# walltime, SIGNAL_AFTER (seconds after the job's start, bash's SECONDS, when this shell sends itself
# SIGUSR1: the check and the warm-up count); and may set (environment, or the submission's -v/--export):
#   OUT               output directory (default runs/CASE-JOB_ID, CASE a case file's name without .py;
#                     a follow-up job keeps it)
#   NUMBA_CACHE_DIR   compiled kernels (default node-local: $TMPDIR or /tmp, per user)
#   WARMUP_ARGS       arguments of the warm-up run (default --t-end 1e-9: one step of the case at
#                     its default, workstation size, compiling the kernels of its default options;
#                     add the run's scheme options, e.g. "--set stabiliser=tvf --t-end 1e-9")
#   CHAIN_MAX         the most jobs in a chain (default 20); CHAIN_INDEX counts them (1 first)

set -euo pipefail

PY="${PY:-.venv/bin/python}"
CASE="${1:?usage: the job script takes the CASE (a name, or a case file) first}"; shift
case_name="$(basename "$CASE" .py)"  # a case file runs into runs/ its name, as python -m mpisph does
OUT="${OUT:-runs/${case_name}-${JOB_ID}}"
CHAIN_INDEX="${CHAIN_INDEX:-1}"
CHAIN_MAX="${CHAIN_MAX:-20}"
export NUMBA_CACHE_DIR="${NUMBA_CACHE_DIR:-${TMPDIR:-/tmp}/mpisph-numba-${USER:-$(id -un)}}"
export NUMBA_NUM_THREADS=1 OMP_NUM_THREADS=1
export OMPI_MCA_odls_base_sigkill_timeout="${OMPI_MCA_odls_base_sigkill_timeout:-120}"  # mpirun's grace after SIGTERM

say() { echo "mpisph job: $*"; }
# A case that does not exist stops the job here, in one line, before the warm-up and the run take
# their nodes (a dry run checks it too: it reads the case, it runs nothing)
"$PY" -m mpisph info "$CASE" > /dev/null || exit 2
say "job ${CHAIN_INDEX} of at most ${CHAIN_MAX}; output in ${OUT}; numba cache in ${NUMBA_CACHE_DIR}"
if [ -n "${SIGNAL_AFTER:-}" ]; then
    say "SIGUSR1 to this job in ${SIGNAL_AFTER} s"
fi

# run CMD...: run it, or print it in a dry run
run() {
    if [ "${MPISPH_DRY_RUN:-0}" = 1 ]; then
        echo "+ $*"
    else
        "$@"
    fi
}

# The warm-up: one rank per node compiles into the node-local cache, so that the ranks of the
# run load the kernels instead of each compiling them.
# shellcheck disable=SC2086
run "${LAUNCH_PER_NODE[@]}" "$PY" -m mpisph "$CASE" ${WARMUP_ARGS:---t-end 1e-9} --out "$OUT/warm-up" --quiet

# The run, in the background with its output in $OUT, so that the batch shell can pass a walltime
# signal on to the launcher (srun and mpirun forward SIGUSR1 to the ranks).
LOG="$OUT/job-${JOB_ID}.log"
run mkdir -p "$OUT"
if [ "${MPISPH_DRY_RUN:-0}" = 1 ]; then
    run "${LAUNCH[@]}" "$PY" -m mpisph "$CASE" "$@" --out "$OUT"
    STOPPED_LINE="${MPISPH_DRY_RUN_LAST_LINE:-}"  # what the run would have printed last
else
    say "run output in $LOG"
    "${LAUNCH[@]}" "$PY" -m mpisph "$CASE" "$@" --out "$OUT" > "$LOG" 2>&1 &
    RUN_PID=$!
    TIMER_PID=""
    if [ -n "${SIGNAL_AFTER:-}" ]; then
        (sleep "$(( SIGNAL_AFTER > SECONDS ? SIGNAL_AFTER - SECONDS : 0 ))" && kill -USR1 $$) &
        TIMER_PID=$!
    fi
    trap 'say "signal received: asking the run to stop"; kill -USR1 "$RUN_PID" 2>/dev/null || true' USR1 TERM
    STATUS=0
    while true; do  # wait returns early (status > 128) when a trapped signal arrives
        wait "$RUN_PID" && STATUS=0 || STATUS=$?
        kill -0 "$RUN_PID" 2>/dev/null || break
    done
    [ -z "$TIMER_PID" ] || kill "$TIMER_PID" 2>/dev/null || true
    tail -n 5 "$LOG"
    [ "$STATUS" = 0 ] || { say "the run failed (status $STATUS)"; exit "$STATUS"; }
    STOPPED_LINE="$(grep -a '^mpisph: stopped by' "$LOG" | tail -n 1 || true)"
fi

# A run stopped by a signal said where to go on from: submit the next job of the chain.
if [ -n "$STOPPED_LINE" ]; then
    FRAME="$(sed -E 's/.* --restart ([^ ]+) .*/\1/' <<< "$STOPPED_LINE")"
    if [ "$CHAIN_INDEX" -ge "$CHAIN_MAX" ]; then
        say "stopped at $FRAME; the chain has reached CHAIN_MAX=$CHAIN_MAX jobs, not resubmitting"
        exit 0
    fi
    say "stopped at $FRAME; submitting job $((CHAIN_INDEX + 1)) of the chain"
    export OUT CHAIN_INDEX=$((CHAIN_INDEX + 1)) CHAIN_MAX
    submit_after "$CASE" --restart "$FRAME"
fi
