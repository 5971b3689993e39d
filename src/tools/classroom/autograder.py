"""Classroom 50 autograder for the opengl3d AO lesson (written by `opengl3d lesson start
--classroom classroom50`). The runner starts it in the student's checkout; it fetches the opengl3d
grader pinned below, grades the five lesson shaders on Mesa's software OpenGL, and leaves
result.json (schema classroom50/result/v1) and the grade-report/ pictures for release_assets.

Exit status: 0 when result.json was written (pass or fail is inside it); anything else is an
infrastructure error, which the runner reports as such.
"""

import hashlib
import os
import shutil
import subprocess
import sys
import tarfile
import tempfile
import urllib.request
from pathlib import Path

# The grader, pinned: every submission of the assignment is graded by this version. To move a
# class to a newer grader on purpose, change all three (see docs/grade/classroom.md).
GRADER_VERSION = "{{VERSION}}"
GRADER_TAG = "{{TAG}}"
# Where a prebuilt grader comes from: the Release of this tag in the class's copy of opengl3d
# (its workflow grader-release.yml builds it once). Empty: built from source instead.
GRADER_RELEASE = "{{RELEASE_URL}}"
GRADER_ASSET = "{{ASSET}}"
# Built from source when there is no prebuilt grader (needs "rust" in the assignment's runtime).
GRADER_GIT = "{{GIT_URL}}"
# The class's language and the points of each step.
LANG = "{{LANG}}"
POINTS = "{{POINTS}}"

HERE = Path(__file__).resolve().parent


def log(message):
    print(f"autograder: {message}", file=sys.stderr, flush=True)


def runs(exe):
    """Whether `exe` is an opengl3d grader of the pinned version."""
    try:
        out = subprocess.run([str(exe), "--version"], capture_output=True, text=True, timeout=60)
    except (OSError, subprocess.TimeoutExpired):
        return False
    return out.returncode == 0 and out.stdout.split()[-1:] == [GRADER_VERSION]


def beside():
    """A grader the teacher put in the autograder bundle itself."""
    exe = HERE / "opengl3d"
    if exe.is_file():
        exe.chmod(0o755)
        if runs(exe):
            return exe
        log(f"{exe} is not opengl3d {GRADER_VERSION}; not used")
    return None


def download(work):
    """The prebuilt grader from the class's Release, checked against its .sha256 file."""
    if not GRADER_RELEASE:
        return None
    url = f"{GRADER_RELEASE}/{GRADER_ASSET}"
    archive = work / GRADER_ASSET
    try:
        with urllib.request.urlopen(url, timeout=120) as r, open(archive, "wb") as f:
            shutil.copyfileobj(r, f)
        with urllib.request.urlopen(url + ".sha256", timeout=60) as r:
            expected = r.read().decode("ascii", "replace").split()[0].lower()
    except OSError as e:
        log(f"cannot download {url}: {e}")
        return None
    actual = hashlib.sha256(archive.read_bytes()).hexdigest()
    if actual != expected:
        log(f"{url}: sha256 {actual} does not match its .sha256 file ({expected}); not used")
        return None
    with tarfile.open(archive) as tar:
        member = tar.getmember("opengl3d")
        if not member.isfile():
            log(f"{url}: 'opengl3d' in the archive is not a file; not used")
            return None
        if hasattr(tarfile, "data_filter"):
            tar.extract(member, work, filter="data")
        else:
            tar.extract(member, work)
    exe = work / "opengl3d"
    exe.chmod(0o755)
    return exe if runs(exe) else None


def build(work):
    """The grader built from the pinned tag: slow (minutes), for classes without a Release."""
    if not GRADER_GIT or not shutil.which("cargo"):
        return None
    log(f"building opengl3d {GRADER_TAG} from {GRADER_GIT} (no prebuilt grader)")
    root = work / "cargo"
    cmd = ["cargo", "install", "--locked", "--profile", "grader", "--no-default-features", "--features", "grade",
           "--git", GRADER_GIT, "--tag", GRADER_TAG, "--root", str(root), "opengl3d"]
    if subprocess.run(cmd).returncode != 0:
        return None
    exe = root / "bin" / "opengl3d"
    return exe if runs(exe) else None


def main():
    # A result.json left in the checkout must never stand in for this run's.
    result = Path("result.json")
    if result.exists():
        result.unlink()
    # The downloaded or built grader (tens of MB) lives only as long as this run.
    with tempfile.TemporaryDirectory(prefix="opengl3d-grader-") as tmp:
        work = Path(tmp)
        exe = beside() or download(work) or build(work)
        if exe is None:
            log("no opengl3d grader could be found, downloaded or built (see the lines above)")
            return 1
        cmd = [str(exe), "--lang", LANG, "--res", ".", "grade", "--format", "classroom50",
               "--points", POINTS, "--out", "grade-report"]
        log(" ".join(cmd))
        code = subprocess.run(cmd).returncode
    if code != 0 or not result.is_file():
        log(f"the grader stopped (exit status {code}) without writing result.json")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
