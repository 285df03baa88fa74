"""What the project's Python scripts share: the `verify` binary found as cargo finds it, the
commit and machine a record names, the spread of timed runs, and writing a file through a
temporary name and a rename."""

import json
import os
import platform
import statistics
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))


def verify_binary():
    """Build `verify` (release) and return its path where cargo puts it (CARGO_TARGET_DIR and
    the build configuration honoured). Exits with a message, having written nothing, when it
    cannot."""
    try:
        subprocess.run(["cargo", "build", "--release", "--quiet", "--bin", "verify"], cwd=ROOT,
                       check=True)
        meta = subprocess.run(["cargo", "metadata", "--format-version", "1", "--no-deps"],
                              cwd=ROOT, check=True, capture_output=True, text=True)
    except (OSError, subprocess.CalledProcessError) as e:
        sys.exit(f"cannot build the verify binary with cargo: {e}")
    path = os.path.join(json.loads(meta.stdout)["target_directory"], "release", "verify")
    if not os.access(path, os.X_OK):
        sys.exit(f"cargo built verify, but {path} is not an executable")
    return path


def commit_of(root=ROOT):
    """The checkout's commit, with `+dirty` when it has uncommitted changes to tracked files."""
    try:
        head = subprocess.run(["git", "rev-parse", "--short=12", "HEAD"], cwd=root, check=True,
                              capture_output=True, text=True).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"],
                               cwd=root, check=True, capture_output=True, text=True).stdout.strip()
        return head + ("+dirty" if dirty else "")
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def machine():
    """The machine a measurement ran on: CPU model, cores, memory, kernel."""
    model = "unknown CPU"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    memory_gib = None
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemTotal"):
                    memory_gib = round(int(line.split()[1]) / 2**20, 1)
    except OSError:
        pass
    cores = os.cpu_count()
    return {
        "cpu": model,
        "cores": cores,
        "memory_gib": memory_gib,
        "kernel": platform.release(),
        "description": f"{model}, {cores} cores, {memory_gib} GiB, Linux {platform.release()}",
    }


def write_atomically(path, text):
    """Write `text` to `path` through a temporary file in the same directory and a rename: a
    reader (or a crash) never sees half a file, and an earlier file stays until the new one is
    whole."""
    tmp = f"{path}.{os.getpid()}.partial"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def spread(values):
    """The median, least and largest of timed runs, with the runs themselves."""
    return {"median": statistics.median(values), "min": min(values), "max": max(values),
            "runs": values}
