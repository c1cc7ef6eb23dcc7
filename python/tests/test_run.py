"""wavy.run against `wavy run`: the same files, byte for byte, and a bad spec's message."""

from pathlib import Path

import pytest

import wavy
from conftest import REPO, cli, cli_error

SPEC = REPO / "experiments" / "fig2_correction_surfaces.toml"


def test_a_spec_run_writes_what_the_cli_writes(tmp_path):
    written = wavy.run(SPEC, out=tmp_path / "py", cache=tmp_path / "cache")
    cli("run", SPEC, "--out", tmp_path / "cli", "--cache", tmp_path / "cache", check_rc=0)
    names = sorted(Path(p).name for p in written)
    assert names and names == sorted(p.name for p in (tmp_path / "cli").iterdir())
    for p in written:
        assert Path(p).read_bytes() == (tmp_path / "cli" / Path(p).name).read_bytes()


def test_a_bad_spec_is_a_value_error_with_the_cli_message(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(SPEC.read_text().replace("title =", "titel ="))
    message, rc = cli_error("run", bad, "--out", tmp_path / "out")
    assert rc == 2
    with pytest.raises(ValueError) as e:
        wavy.run(bad, out=tmp_path / "out")
    assert str(e.value) == message
