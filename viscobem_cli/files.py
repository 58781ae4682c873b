"""Files a user can trust after a crash: every output is written whole or not at all.

A file is written to a temporary file in the same folder, then renamed over its name (an atomic
step on POSIX file systems), with the permissions of a plain new file; a process killed while
writing leaves only a hidden ``.NAME.*.tmp`` that the next run removes.
"""

import os
import tempfile
from pathlib import Path

__all__ = ["remove_stale_temporaries", "write_atomic"]


def _file_mode():
    """0o666 minus the process's umask: what ``open()`` would give a new file."""
    mask = os.umask(0o022)
    os.umask(mask)
    return 0o666 & ~mask


def write_atomic(path, data, mode="w"):
    """Write ``data`` to ``path`` through a temporary file in the same folder + rename.

    The file gets the permissions of a plain new file (``0o666`` minus the umask), so a
    group that shares the results folder can read it.
    """
    path = Path(path)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        os.fchmod(fd, _file_mode())
        with os.fdopen(fd, mode) as f:
            f.write(data)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def remove_stale_temporaries(folder):
    """Delete temporary files left by a process killed while writing (``kill -9``)."""
    for tmp in Path(folder).glob(".*.tmp"):
        tmp.unlink(missing_ok=True)
