"""One Blender session for the whole run: isolated user directory, the working tree
installed as extension bl_ext.local.sandscape, and an empty file before every test."""

import contextlib
import fcntl
import pathlib
import sys

REPO_ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO_ROOT))

from devtools import session  # noqa: E402

USER_ROOT = session.isolate()

import bpy  # noqa: E402,F401 (imported after isolate on purpose)
import pytest  # noqa: E402

SANDSCAPE = session.install_dev_extension(USER_ROOT)


@pytest.fixture(autouse=True)
def empty_file():
    session.reset()
    yield


@pytest.fixture(autouse=True)
def no_traceback(capfd):
    """Bad input gets a report, never a traceback: a Python error inside an operator or a
    handler only shows on stderr (Blender catches it), so every test's output is searched. So is
    Cycles' warning that a shader went past its closures: it drops light from the frame."""
    yield
    out, err = capfd.readouterr()
    sys.stdout.write(out)
    sys.stderr.write(err)
    assert "Traceback (most recent call last)" not in out + err, err[-3000:]
    assert "Maximum number of closures exceeded" not in out + err


EEVEE_SIZE = (64, 36)  # pixels: EEVEE renders few and small (software OpenGL here)


@pytest.fixture
def eevee_scene():
    """The empty file set to render in EEVEE at EEVEE_SIZE, 4 samples; the test skips, saying why,
    where no OpenGL context can be made."""
    from devtools import readback, scenes

    scene = bpy.context.scene
    scene.render.engine = "BLENDER_EEVEE"
    scene.render.resolution_x, scene.render.resolution_y = EEVEE_SIZE
    scene.render.resolution_percentage = 100
    scene.eevee.taa_render_samples = 4
    if _EEVEE_PROBE["error"] is None and not _EEVEE_PROBE["rendered"]:
        probe = scenes.camera("PERSP")
        try:
            readback.render(scene)
            _EEVEE_PROBE["rendered"] = True
        except RuntimeError as error:  # no OpenGL context: EEVEE cannot draw
            _EEVEE_PROBE["error"] = str(error)
        finally:
            bpy.data.objects.remove(probe)
    if _EEVEE_PROBE["error"] is not None:
        pytest.skip(f"EEVEE cannot render here (no OpenGL context: {_EEVEE_PROBE['error']})")
    return scene


# Whether this worker's Blender could make an OpenGL context: probed by one render, once (a probe
# per test cost 2-4 s each, about 50 s of the suite).
_EEVEE_PROBE = {"rendered": False, "error": None}


@pytest.fixture
def sandscape():
    """The installed extension's package (bl_ext.local.sandscape)."""
    return SANDSCAPE


@pytest.fixture
def glints_group(sandscape):
    """The procedural glint group (Sandscape Glints), built or reused the way the add-on does."""
    return sandscape.node_groups.helper.ensure_group(sandscape.node_groups.glints)


@pytest.fixture(scope="session")
def demo_files(tmp_path_factory):
    """The demo built once for the run and saved twice: as built (the committed demo.blend's
    counterpart) and with its clouds on 200 m voxels, which most tests open: the demo's 50 m grid
    took 5 s to evaluate at every opening and 6 s of every render after a change to the view
    layer. Building takes 12-25 s, opening one. Under xdist every worker is a session of its own:
    the first to need the demo builds it for all (a lock in the run's shared temporary folder),
    the others wait for it and open its files."""
    with built_once(tmp_path_factory, "demo") as (folder, to_build):
        files = {"built": folder / "built.blend", "coarse": folder / "demo.blend"}
        if to_build:
            session.reset()
            assert bpy.ops.sandscape.build_demo_scene() == {"FINISHED"}
            bpy.ops.wm.save_as_mainfile(filepath=str(files["built"]), copy=True)
            bpy.context.scene.sandscape_clouds.voxel = 200.0
            assert bpy.ops.sandscape.add_clouds() == {"FINISHED"}
            bpy.ops.wm.save_as_mainfile(filepath=str(files["coarse"]), copy=True)
    return files


@contextlib.contextmanager
def built_once(tmp_path_factory, name):
    """(A folder the run's workers share, whether this one is to fill it): the first worker to get
    the lock fills it, the others wait and find it filled. A fill that fails leaves it unfilled."""
    base = tmp_path_factory.getbasetemp()
    shared = base.parent if base.name.startswith("popen-gw") else base  # xdist: one per worker
    folder = shared / f"{name}-shared"
    folder.mkdir(exist_ok=True)
    with open(shared / f"{name}-shared.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        done = folder / "done"
        yield folder, not done.exists()
        done.touch()


@pytest.fixture
def demo_file(demo_files):
    return demo_files["coarse"]


@pytest.fixture
def demo_scene(demo_file):
    """A fresh copy of the demo (its file opened again), as the current scene."""
    bpy.ops.wm.open_mainfile(filepath=str(demo_file), load_ui=False)
    return bpy.context.scene
