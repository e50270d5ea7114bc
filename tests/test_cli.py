"""./sandscape: every subcommand has --help, bad input exits 2 with one clear line, and a
demo built on the command line renders."""

import pathlib
import subprocess
import sys

import pytest

REPO = pathlib.Path(__file__).resolve().parent.parent
CLI = [sys.executable, str(REPO / "devtools" / "cli.py")]


def run(*args):
    return subprocess.run([*CLI, *args], capture_output=True, text=True, timeout=600)


@pytest.mark.parametrize("command", [[], ["build-demo"], ["render"], ["bench"]])
def test_help(command):
    result = run(*command, "--help")
    assert result.returncode == 0 and "usage: sandscape" in result.stdout


@pytest.mark.parametrize("args, message", [
    (["render", "/no/such.blend"], "no such .blend"),
    (["build-demo", "--output", "demo.txt"], "must be a .blend"),
    (["bench", "nope"], "no benchmark 'nope'"),
])
def test_bad_input_exits_2_with_a_message(args, message):
    result = run(*args)
    assert result.returncode == 2
    assert message in result.stderr and result.stderr.count("\n") == 1


def test_build_then_render(tmp_path):
    blend = tmp_path / "demo.blend"
    built = run("build-demo", "--output", str(blend))
    assert built.returncode == 0 and blend.is_file(), built.stderr
    assert "sandscape: saved" in built.stdout
    rendered = run("render", str(blend), "--output", str(tmp_path / "frame.png"), "--frame", "5",
                   "--frame", "9", "--width", "64", "--height", "36", "--samples", "1")
    assert rendered.returncode == 0, rendered.stderr
    assert (tmp_path / "frame_0005.png").is_file() and (tmp_path / "frame_0009.png").is_file()
    assert rendered.stdout.count("sandscape: frame") == 2
