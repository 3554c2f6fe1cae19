"""The course graded while the student works, end to end, in a scratch copy.

Run after `cargo build --release` (`.ci/run` does both):

    python3 tests/e2e/learn_watch.py            # the end-to-end check
    python3 tests/e2e/learn_watch.py --bench 5  # save-to-verdict latency, 5 rounds

The check:

1. `spintop course export` writes a student's copy of the course to a
   temporary folder (the repository's own lessons are never touched);
2. `spintop learn --chapter section-2 --course COPY` runs in a private tmux server
   (`tmux -L`, its own socket) and must show "course 0 of 22";
3. the instructor's solution of one assignment (larmor_rate, Eq. (2.1)) is
   written into the copy's src/ch2.rs, as a student saving the file would,
   and the header must turn to "course 1 of 22" without a restart; the
   course panel (`a`) must mark larmor_rate passing; `q` must exit 0;
4. `spintop course watch --course COPY` (a plain process) must print
   "1 of 22 passing", then, after a second solution is saved (torque_rate,
   Eq. (2.2)), "2 of 22 passing".

The time from the write to the verdict on screen is printed for each save. It
is measured, never asserted (a test must not fail because the machine is busy);
`--bench N` saves a solution and the stub in turn N times and prints the
median, the fastest and the slowest (the figures in the README come from it).

The copy's cargo shares the repository's target folder (CARGO_TARGET_DIR), so
that spintop itself is not built twice: that is the warm case the latency goal
is about.
"""

from __future__ import annotations

import argparse
import json
import os
import pathlib
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

REPO = pathlib.Path(__file__).resolve().parents[2]
SOLUTIONS = REPO / "lessons" / "src" / "solutions"
SOCKET = f"spintop-e2e-learn-{os.getpid()}"


def binary() -> pathlib.Path:
    path = pathlib.Path(os.environ.get("SPINTOP", REPO / "target" / "release" / "spintop"))
    if not path.is_file():
        sys.exit(f"learn_watch: {path} is missing; run `cargo build --release` first")
    return path


def function_source(text: str, name: str) -> str:
    """The text of `pub fn NAME ... }` (to the closing brace at column 0)."""
    match = re.search(rf"^pub fn {name}\b.*?^\}}\n", text, re.S | re.M)
    if not match:
        raise SystemExit(f"learn_watch: no `pub fn {name}` found")
    return match.group(0)


def write_function(file: pathlib.Path, name: str, replacement: str) -> None:
    """Replace `pub fn NAME` in FILE, as an editor saving the file would."""
    text = file.read_text()
    old = function_source(text, name)
    file.write_text(text.replace(old, replacement))


def solution(chapter: str, name: str) -> str:
    return function_source((SOLUTIONS / f"{chapter}.rs").read_text(), name)


class Tmux:
    def __init__(self, width: int = 160, height: int = 48) -> None:
        self.run("-f", "/dev/null", "new-session", "-d", "-s", "e2e", "-x", str(width),
                 "-y", str(height), "sleep 600")
        self.run("set-option", "-t", "e2e", "remain-on-exit", "on")

    def run(self, *args: str) -> str:
        out = subprocess.run(["tmux", "-L", SOCKET, *args], capture_output=True, text=True)
        if out.returncode != 0:
            raise SystemExit(f"tmux {' '.join(args)}: {out.stderr.strip()}")
        return out.stdout

    def start(self, command: str) -> None:
        self.run("respawn-pane", "-k", "-t", "e2e", command)

    def screen(self) -> str:
        return self.run("capture-pane", "-p", "-t", "e2e")

    def keys(self, *keys: str) -> None:
        self.run("send-keys", "-t", "e2e", *keys)

    def wait(self, what: str, ready, limit: float) -> str:
        start = time.monotonic()
        while True:
            screen = self.screen()
            if ready(screen):
                return screen
            if time.monotonic() - start > limit:
                raise SystemExit(f"learn_watch: timed out waiting for {what}; the screen:\n{screen}")
            time.sleep(0.05)

    def close(self) -> None:
        subprocess.run(["tmux", "-L", SOCKET, "kill-server"], capture_output=True)


def check(copy: pathlib.Path, env: dict[str, str]) -> list[float]:
    latencies = []
    ch2 = copy / "src" / "ch2.rs"
    status = copy / "learn.status"
    tmux = Tmux()
    try:
        envs = " ".join(f"{k}='{v}'" for k, v in env.items() if k in ("CARGO_TARGET_DIR", "SPINTOP_LEARN_PROGRESS"))
        tmux.start(f"env {envs} '{binary()}' learn --chapter section-2 --course '{copy}'; echo $? > '{status}'")
        screen = tmux.wait("the chapter and course 0 of 22", lambda s: "course 0 of 22" in s, 300)
        assert "Section 2" in screen, screen
        write_function(ch2, "larmor_rate", solution("ch2", "larmor_rate"))
        saved = time.monotonic()
        tmux.wait("course 1 of 22 after saving larmor_rate", lambda s: "course 1 of 22" in s, 120)
        latencies.append(time.monotonic() - saved)
        print(f"learn: saved larmor_rate; 'course 1 of 22' on screen {latencies[-1]:.2f} s later")
        tmux.keys("a")
        panel = tmux.wait("the course panel", lambda s: "larmor_rate" in s and "passing" in s, 10)
        line = next(l for l in panel.splitlines() if "larmor_rate" in l)
        assert "✓" in line, panel
        assert "▰" in panel, panel  # the progress bar, 1 of 22
        # h: the hint ladder of the chapter's next assignment, one rung per press;
        # the rungs are kept in the copy's own target/spintop-course.json.
        tmux.keys("h")
        tmux.wait("hint 1 of 3", lambda s: "hint 1 of 3 (where to look) for schott_angular_momentum" in s, 10)
        tmux.keys("h")
        tmux.wait("hint 2 of 3", lambda s: "hint 2 of 3 (the idea)" in s, 10)
        kept = json.loads((copy / "target" / "spintop-course.json").read_text())
        assert kept["hints"] == {"schott_angular_momentum": 2}, kept
        assert "larmor_rate" in kept["first_passed"], kept
        tmux.keys("Escape")
        tmux.keys("q")
        start = time.monotonic()
        while not status.exists() and time.monotonic() - start < 10:
            time.sleep(0.05)
        code = status.read_text().strip() if status.exists() else "none"
        assert code == "0", f"spintop learn exited with {code}"
        assert tmux.run("display-message", "-p", "-t", "e2e", "#{alternate_on}").strip() == "0"
    finally:
        tmux.close()

    watch = subprocess.Popen(
        [str(binary()), "course", "watch", "--course", str(copy)],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env,
    )
    try:
        seen = []

        def wait_line(pattern: str, limit: float) -> None:
            start = time.monotonic()
            while time.monotonic() - start < limit:
                line = watch.stdout.readline()
                if not line:
                    break
                seen.append(line.rstrip())
                if pattern in line:
                    return
            raise SystemExit(f"learn_watch: course watch never said {pattern!r}; it said:\n" + "\n".join(seen))

        wait_line("1 of 22 passing", 300)
        write_function(ch2, "torque_rate", solution("ch2", "torque_rate"))
        saved = time.monotonic()
        wait_line("2 of 22 passing", 120)
        latencies.append(time.monotonic() - saved)
        assert any("✓ (2.2) torque_rate passing" in l for l in seen), seen
        print(f"course watch: saved torque_rate; '2 of 22 passing' printed {latencies[-1]:.2f} s later")
    finally:
        watch.kill()
        watch.wait()
    return latencies


def bench(copy: pathlib.Path, env: dict[str, str], rounds: int) -> None:
    """Save a solution and the stub in turn; time each save to its verdict."""
    ch2 = copy / "src" / "ch2.rs"
    stub = function_source(ch2.read_text(), "larmor_rate")
    answer = solution("ch2", "larmor_rate")
    watch = subprocess.Popen(
        [str(binary()), "course", "watch", "--course", str(copy)],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env,
    )
    times = []
    try:
        def until(pattern: str) -> None:
            while True:
                line = watch.stdout.readline()
                if not line:
                    raise SystemExit("learn_watch: course watch ended")
                if pattern in line:
                    return

        until("0 of 22 passing")
        for k in range(rounds):
            for text, verdict in ((answer, "1 of 22 passing"), (stub, "0 of 22 passing")):
                time.sleep(1.0)  # a distinct modification time, and the student's pause
                write_function(ch2, "larmor_rate", text)
                saved = time.monotonic()
                until(verdict)
                times.append(time.monotonic() - saved)
    finally:
        watch.kill()
        watch.wait()
    print(
        f"save → verdict (course watch, warm, {len(times)} saves): "
        f"median {statistics.median(times):.2f} s, fastest {min(times):.2f} s, slowest {max(times):.2f} s"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bench", type=int, metavar="N", help="time N rounds of saves instead")
    args = parser.parse_args()
    if shutil.which("tmux") is None and not args.bench:
        sys.exit("learn_watch: tmux is missing (apt-get install tmux)")
    with tempfile.TemporaryDirectory(prefix="spintop-course-") as tmp:
        copy = pathlib.Path(tmp) / "course"
        subprocess.run([str(binary()), "course", "export", "--out", str(copy)], check=True,
                       stdout=subprocess.DEVNULL)
        env = dict(os.environ)
        env["CARGO_TARGET_DIR"] = str(REPO / "target")
        env["SPINTOP_LEARN_PROGRESS"] = str(pathlib.Path(tmp) / "progress.json")
        if args.bench:
            bench(copy, env, args.bench)
        else:
            latencies = check(copy, env)
            print(f"learn_watch: ok (save → verdict: {', '.join(f'{t:.2f} s' for t in latencies)})")
        # The repository's own lessons were never touched.
        assert "todo!(" in function_source((REPO / "lessons/src/ch2.rs").read_text(), "larmor_rate")


if __name__ == "__main__":
    main()
