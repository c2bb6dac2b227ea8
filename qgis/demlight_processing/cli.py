"""The demlight command-line tool as the provider sees it: where it is, what its commands and
options are (``demlight options --json``), and running one command with its progress and
cancellation. No QGIS import here, so this part is testable without QGIS."""

import json
import os
import queue
import re
import shutil
import signal
import subprocess
import threading
import time

#: Environment variable that names the demlight executable (it wins over every other way).
EXECUTABLE_ENV = "DEMLIGHT_EXECUTABLE"
#: File next to this module that install.sh writes with the executable's path.
EXECUTABLE_FILE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "executable")

# What the CLI prints on stderr per stage when stderr is not a terminal
# (cli/progress_bar.cpp, ProgressBar::writeLine): "STAGE: 40 % after 1.2 s[, ~2.0 s left]".
_PROGRESS_LINE = re.compile(r"^(?P<stage>.+): (?P<percent>\d+) % after ")

#: How the CLI starts an error line (cli/main.cpp, cli/command_line.cpp).
ERROR_PREFIX = "demlight: error: "

# Seconds to wait for the CLI to stop at its next safe point after SIGINT before killing it.
_CANCEL_GRACE_S = 10.0


class DemlightError(Exception):
    """The CLI could not be found or run, or it failed (message: its own error lines)."""


def find_executable(configured=None):
    """The demlight executable: $DEMLIGHT_EXECUTABLE, else `configured` (the provider's
    setting), else the path install.sh recorded, else `demlight` on PATH; None if none exists."""
    candidates = [os.environ.get(EXECUTABLE_ENV), configured]
    if os.path.isfile(EXECUTABLE_FILE):
        with open(EXECUTABLE_FILE, encoding="utf-8") as f:
            candidates.append(f.read().strip())
    candidates.append(shutil.which("demlight"))
    for path in candidates:
        if path and os.path.isfile(path) and os.access(path, os.X_OK):
            return path
    return None


def load_commands(executable):
    """`demlight options --json`: {"version": ..., "commands": [...]} (cli/cmd_options.cpp)."""
    try:
        done = subprocess.run([executable, "options", "--json"], capture_output=True, encoding="utf-8", timeout=60,
                              check=False)
    except (OSError, subprocess.SubprocessError) as e:
        raise DemlightError(f"{executable} options --json: {e}") from e
    if done.returncode != 0:
        raise DemlightError(f"{executable} options --json failed: {done.stderr.strip()}")
    return json.loads(done.stdout)


def parse_progress(line):
    """(stage, percent) of a progress line the CLI prints, or None for any other line."""
    m = _PROGRESS_LINE.match(line)
    return (m.group("stage"), int(m.group("percent"))) if m else None


def run(arguments, on_progress, on_line, is_cancelled, poll_s=0.2, parameter_names=None):
    """Runs demlight with `arguments` (the executable first); with parameter_names="qgis" its
    error messages name parameters by their QGIS labels. Progress lines go to
    on_progress(stage, percent), every other stderr or stdout line to on_line(line). When
    is_cancelled() turns true the CLI is sent SIGINT, as Ctrl-C would (it stops at a safe point
    and leaves no partial output), and killed if it has not stopped after a grace period.
    Returns (exit code, the lines that were not progress)."""
    try:
        env = dict(os.environ, DEMLIGHT_PARAMETER_NAMES=parameter_names) if parameter_names else None
        proc = subprocess.Popen(arguments, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, bufsize=1,
                                encoding="utf-8", errors="replace", env=env)
    except OSError as e:
        raise DemlightError(f"cannot run {arguments[0]}: {e}") from e
    lines = queue.Queue()

    def pump():
        with proc.stdout:
            for line in proc.stdout:
                lines.put(line.rstrip("\n"))
        lines.put(None)

    reader = threading.Thread(target=pump, daemon=True)
    reader.start()
    messages, cancel_sent_at = [], None
    while True:
        if cancel_sent_at is None and is_cancelled():
            proc.send_signal(signal.SIGINT)
            cancel_sent_at = time.monotonic()
        elif cancel_sent_at is not None and time.monotonic() - cancel_sent_at > _CANCEL_GRACE_S:
            proc.kill()
        try:
            line = lines.get(timeout=poll_s)
        except queue.Empty:
            continue
        if line is None:
            break
        progress = parse_progress(line)
        if progress:
            on_progress(*progress)
        elif line.strip():
            messages.append(line)
            on_line(line)
    return proc.wait(), messages
