"""One Blender session for the whole run: isolated user directory, the working tree
installed as extension bl_ext.local.sandscape, and an empty file before every test."""

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
    probe = scenes.camera("PERSP")
    try:
        readback.render(scene)
    except RuntimeError as error:  # no OpenGL context: EEVEE cannot draw
        pytest.skip(f"EEVEE cannot render here (no OpenGL context: {error})")
    finally:
        bpy.data.objects.remove(probe)
    return scene


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
    layer. Building takes seconds, opening one."""
    session.reset()
    assert bpy.ops.sandscape.build_demo_scene() == {"FINISHED"}
    folder = tmp_path_factory.mktemp("demo")
    built = folder / "built.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(built), copy=True)
    bpy.context.scene.sandscape_clouds.voxel = 200.0
    assert bpy.ops.sandscape.add_clouds() == {"FINISHED"}
    coarse = folder / "demo.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(coarse), copy=True)
    return {"built": built, "coarse": coarse}


@pytest.fixture
def demo_file(demo_files):
    return demo_files["coarse"]


@pytest.fixture
def demo_scene(demo_file):
    """A fresh copy of the demo (its file opened again), as the current scene."""
    bpy.ops.wm.open_mainfile(filepath=str(demo_file), load_ui=False)
    return bpy.context.scene
