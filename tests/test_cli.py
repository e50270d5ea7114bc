"""./sandscape: every subcommand has --help, bad input exits 2 with one clear line, and a
demo built on the command line renders."""

import pathlib
import subprocess
import sys

import pytest
from conftest import built_once

REPO = pathlib.Path(__file__).resolve().parent.parent
CLI = [sys.executable, str(REPO / "devtools" / "cli.py")]


def run(*args):
    return subprocess.run([*CLI, *args], capture_output=True, text=True, timeout=600)


@pytest.mark.parametrize("command", [[], ["build-demo"], ["render"], ["bench"]])
def test_help(command):
    result = run(*command, "--help")
    assert result.returncode == 0 and "usage: sandscape" in result.stdout


@pytest.fixture(scope="module")
def blend(tmp_path_factory):
    """A demo saved by the command line, built once for the run's workers."""
    with built_once(tmp_path_factory, "cli-demo") as (folder, to_build):
        path = folder / "demo.blend"
        if to_build:
            built = run("build-demo", "--output", str(path))
            assert built.returncode == 0 and path.is_file(), built.stderr
            assert "sandscape: saved" in built.stdout
    return path


@pytest.fixture(scope="module")
def not_a_blend(tmp_path_factory):
    path = tmp_path_factory.mktemp("cli") / "notes.blend"
    path.write_text("not a blend file")
    return path


BAD_INPUT = [
    (["render", "/no/such.blend"], "no such .blend"),
    (["render", "{not_a_blend}"], "is not a .blend"),
    (["render", "{blend}", "--output", "/proc/sandscape/frame.png"], "cannot write"),
    (["render", "{blend}", "--width", "64"], "--width and --height together"),
    (["render", "{blend}", "--width", "-10", "--height", "36"], "must lie in 1..65536"),
    (["render", "{blend}", "--output", "frame.gif"], "extension picks the format"),
    (["render", "{blend}", "--samples", "0"], "samples must be at least 1"),
    (["render", "{blend}", "--frame", "2000000"], "frames must lie in -1048574..1048574"),
    (["build-demo", "--output", "demo.txt"], "must be a .blend"),
    (["build-demo", "--output", "/proc/sandscape/demo.blend"], "cannot write"),
    (["bench", "nope"], "no benchmark 'nope'"),
]


@pytest.mark.parametrize("args, message", BAD_INPUT)
def test_bad_input_exits_2_with_one_line(blend, not_a_blend, args, message):
    result = run(*[a.format(blend=blend, not_a_blend=not_a_blend) for a in args])
    assert result.returncode == 2, result.stderr
    assert message in result.stderr and result.stderr.count("\n") == 1, result.stderr
    assert "Traceback" not in result.stderr + result.stdout


def test_build_then_render_with_the_format_the_extension_picks(blend, tmp_path):
    rendered = run("render", str(blend), "--output", str(tmp_path / "frame.jpg"), "--frame", "5",
                   "--frame", "-3", "--width", "64", "--height", "36", "--samples", "1")
    assert rendered.returncode == 0, rendered.stderr
    assert rendered.stdout.count("sandscape: frame") == 2
    for frame in (5, -3):  # JPEGs, named as asked; a negative frame is a frame, as in Blender
        assert (tmp_path / f"frame_{frame:04d}.jpg").read_bytes()[:3] == b"\xff\xd8\xff"
    assert not list(tmp_path.glob("*.png"))


def test_a_bench_runs_quick_from_the_command_line():
    result = run("bench", "footprint_dicing", "--quick", "--no-append")
    assert result.returncode == 0, result.stderr[-2000:]
    assert "adaptive patch over the prints" in result.stdout
