"""Large meshes are safe: the memory a mesh needs is estimated before solving, and a solve above
the caller's max_memory, the memory available or the address space the process may take is
refused (MemoryError; the CLI exits 1), naming the estimate; nothing aborts."""

import resource
import subprocess
import sys

import pytest

import wavy
from conftest import WAVY, cli, python_words


def test_a_solve_above_max_memory_is_refused_naming_the_estimate():
    with pytest.raises(MemoryError) as e:
        wavy.solve(ar=0.1, mesh=512, max_memory=1e8)
    message = str(e.value)
    assert message.startswith("mesh 512×256 needs about 593 MB of memory and ")
    assert "above max_memory = 100000000 bytes (100 MB)" in message
    rc, out, err = cli("solve", "--ar", 0.1, "--mesh", 512, "--max-memory", 100000000)
    assert rc == 1 and out == ""
    assert python_words(err) == f"error: {message}\n"
    # at or above the estimate it runs
    assert wavy.solve(ar=0.3, mesh=8, until_a_over_lambda=0.2, max_memory=10**9).load_steps > 0


def test_more_than_the_machine_has_is_refused():
    # mesh 2048 needs about 10 GB: refused when it is not available, else a cap below it
    with pytest.raises(MemoryError, match=r"^mesh 2048×1024 needs about 10\.2 GB of memory"):
        wavy.solve(ar=0.1, mesh=2048, max_memory=9e9)


def limit_address_space():
    resource.setrlimit(resource.RLIMIT_AS, (3 * 10**9, 3 * 10**9))


def test_an_address_space_limit_is_a_memory_error_not_an_abort():
    # mesh 1024 needs about 2.5 GB resident and 3.1 GB of address space: above a 3 GB ulimit -v
    code = (
        "import wavy\n"
        "try:\n"
        "    wavy.solve(ar=0.1, mesh=1024)\n"
        "except MemoryError as e:\n"
        "    print(e)\n"
    )
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       preexec_fn=limit_address_space, timeout=60)
    assert p.returncode == 0, p.stderr
    assert p.stdout.startswith("mesh 1024×512 needs about 2.5 GB of memory")
    assert "cannot reserve the 3.1 GB of address space" in p.stdout
    # the command line: exit 1 with the message, no abort (134)
    p = subprocess.run([str(WAVY), "solve", "--ar", "0.1", "--mesh", "1024"], capture_output=True,
                       text=True, preexec_fn=limit_address_space, timeout=60)
    assert p.returncode == 1 and "cannot reserve the 3.1 GB of address space" in p.stderr
