"""The user's paths checked before a command runs: an output directory or file that cannot be
written, or a serial port that is not there, is a UsageError (exit 2) naming the option, not an
OSError after minutes of simulation."""

import errno
import os
import tempfile

from hexapod.units import shown
from hexapod_host.commands.cli import UsageError


def _probe(option, folder, what):
    """Create and remove a file in folder: the only sure test of 'can we write there'."""
    try:
        probe = tempfile.NamedTemporaryFile(dir=folder, prefix=".hexapod-probe-")  # noqa: SIM115
        probe.close()
    except OSError as err:
        raise UsageError("%s: cannot write %s: %s" % (option, what, err.strerror or err)) from None


def out_dir(option, path, *, empty=False):
    """A directory the command writes into (and creates when missing), refused when it is a file, when
    it or the folder it would be made in cannot be written, or (empty=True) when it holds anything."""
    if not path:
        raise UsageError("%s: empty; give a directory" % option)
    if os.path.exists(path) and not os.path.isdir(path):
        raise UsageError("%s: %s exists and is not a directory" % (option, shown(path, 200)))
    if empty and os.path.isdir(path) and os.listdir(path):
        raise UsageError("%s: %s is not empty (give a new or empty directory)" % (option, shown(path, 200)))
    # A refused command leaves nothing behind: the nearest existing folder is probed, the command
    # itself creates the rest.
    base = path
    while not os.path.exists(base):
        base = os.path.dirname(base) or "."
    if not os.path.isdir(base):
        raise UsageError("%s: cannot write into %s: %s" % (option, shown(path, 200), os.strerror(errno.ENOTDIR)))
    _probe(option, base, "into " + shown(path, 200))
    return path


def out_file(option, path, *, suffix=None):
    """A file the command writes (replacing one already there): its folder must exist and take a new
    file, the path must not be a directory, and it must end in suffix when one is given."""
    if not path:
        raise UsageError("%s: empty; give a file name" % option)
    if suffix and not path.endswith(suffix):
        raise UsageError("%s: %s, allowed a file name ending in %s" % (option, shown(path, 200), suffix))
    if os.path.isdir(path):
        raise UsageError("%s: %s is a directory; give a file name" % (option, shown(path, 200)))
    folder = os.path.dirname(path) or "."
    if not os.path.isdir(folder):
        raise UsageError("%s: no such directory %s (for %s)" % (option, shown(folder, 200), shown(path, 200)))
    _probe(option, folder, shown(path, 200))
    return path


def port(path):
    """A serial port named by a path must exist (COM3 and the like are left to the serial layer)."""
    if os.sep in path and not os.path.exists(path):
        raise UsageError("no such port %r (hexapod ports lists them)" % path)
    return path
