"""What an analysis script checks of a run directory before it reads the run: a one-line usage
error (argparse, status 2) where the directory holds no complete frame, or a run of a case whose
parameters lack what the script reads, instead of a traceback from deep inside it."""

from mpisph.io.frames import list_frames, read_rows


def run_params(ap, run, needs, reads):
    """The parameters of the run in ``run`` (its first frame's); ``ap.error`` unless it has a complete
    frame and every parameter of ``needs``. ``reads`` says which runs the script reads, for the message."""
    frames = list_frames(run)
    if not frames:
        ap.error(f"{run}: no complete frames (frame_*.hdf)")
    params = read_rows(frames[0], 0, 0)["params"]
    missing = [name for name in needs if name not in params]
    if missing:
        ap.error(f"{run} is a run of {params.get('case')!r}, which has no {', '.join(missing)}: this script "
                 f"reads {reads}")
    return params
