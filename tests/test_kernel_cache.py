"""The compiled kernels are cached per content of the package's sources (mpisph/__init__.py), so a
kernel never keeps the old code of a kernel it calls from another file (numba/numba#1833); old
cache folders are pruned."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import mpisph
from mpisph import prune_kernel_caches

PACKAGE = Path(mpisph.__file__).resolve().parent


def cache_dir(root, **env):
    """numba's cache folder as a fresh interpreter importing the package copied under ``root`` sets it."""
    environ = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CACHE_DIR", "PYTHONPATH")}
    r = subprocess.run([sys.executable, "-c", "import mpisph, numba; print(numba.config.CACHE_DIR)"], cwd=root,
                       env={**environ, **env}, capture_output=True, text=True, check=True, timeout=120)
    return Path(r.stdout.strip())


def test_a_change_to_any_source_file_starts_a_new_kernel_cache(tmp_path):
    shutil.copytree(PACKAGE, tmp_path / "mpisph", ignore=shutil.ignore_patterns("__pycache__"))
    first = cache_dir(tmp_path)
    assert first.parent == tmp_path / "mpisph" / "__pycache__" and first.name.startswith("kernels-")
    assert cache_dir(tmp_path) == first
    callee = tmp_path / "mpisph" / "physics" / "walls.py"  # called by the kernels of other files
    callee.write_text(callee.read_text() + "\n# an edit\n")
    edited = cache_dir(tmp_path)
    assert edited != first and edited.parent == first.parent
    assert cache_dir(tmp_path, NUMBA_CACHE_DIR=str(tmp_path / "node")) == tmp_path / "node" / edited.name


def test_prune_keeps_the_current_and_the_most_recently_used(tmp_path):
    folders = [tmp_path / f"kernels-{i:016x}" for i in range(6)]
    for age, folder in enumerate(folders):
        folder.mkdir()
        (folder / "index.nbi").write_bytes(b"")
        os.utime(folder, (1e9 - 100 * age, 1e9 - 100 * age))  # folders[0] the newest
    (tmp_path / "other").mkdir()
    current = folders[5]  # the oldest, but in use
    prune_kernel_caches(current, kept=2)
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(["other", folders[0].name, folders[1].name, current.name])
    assert current.stat().st_mtime > folders[0].stat().st_mtime  # marked as used
    prune_kernel_caches(current, kept=2)  # nothing more to delete
    assert folders[0].exists() and folders[1].exists()
    prune_kernel_caches(tmp_path / "kernels-not-compiled-yet", kept=0)  # a folder not made yet is no error
    assert sorted(p.name for p in tmp_path.iterdir()) == ["other"]
