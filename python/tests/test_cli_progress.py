"""`wavy run` shows its progress on a terminal (cases done of total, elapsed time) and stays
quiet when stderr is piped."""

import os
import pty
import subprocess

from conftest import WAVY

SPEC = """title = "progress (test size)"

[fe_vs_model]
aspect_ratios = [0.1, 0.3]
tau_max_mpa = [0.0]
a_over_lambda = { min = 0.0, max = 0.5, count = 11 }

[fe_vs_model.models]
draw = ["westergaard"]
reading = "bracket-sq"
coefficients = "paper-table1"
compare_coefficients = "paper-table1"

[fe_vs_model.fe]
tau_max_mpa = [0.0]
until_a_over_lambda = 0.3
mesh = "16"

[check]
rel_tol = 1e-5
abs_tol = 1e-6
"""


def spec(tmp_path):
    path = tmp_path / "progress.toml"
    path.write_text(SPEC)
    return path


def test_wavy_run_shows_cases_and_elapsed_time_on_a_terminal(tmp_path):
    args = [str(WAVY), "run", str(spec(tmp_path)), "--out", str(tmp_path / "out"),
            "--cache", str(tmp_path / "cache")]
    leader, follower = pty.openpty()
    p = subprocess.Popen(args, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                         stderr=follower, close_fds=True)
    os.close(follower)
    seen = b""
    while True:
        try:
            chunk = os.read(leader, 4096)
        except OSError:  # the terminal closed with the process
            break
        if not chunk:
            break
        seen += chunk
    p.wait(timeout=60)
    os.close(leader)
    text = seen.decode(errors="replace")
    assert p.returncode == 0, text
    assert "/2 cases" in text and "[00:00:0" in text, text


def test_wavy_run_is_quiet_when_piped(tmp_path):
    p = subprocess.run([str(WAVY), "run", str(spec(tmp_path)), "--out", str(tmp_path / "out"),
                        "--cache", str(tmp_path / "cache")], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    assert p.stderr == ""
