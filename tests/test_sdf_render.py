"""``sensorkit render preview`` on SDF: the model is drawn from the URDF subset pybullet
reads (sensorkit.render.sdf_urdf), so a robot written once as URDF and once as SDF
renders the same pixels.

``tests/robots/sdf/render/twin_bot.urdf`` and ``twin_bot.sdf`` are one robot: the SDF
places its mast from a ``<frame>``, its pan link from its joint, and its top camera (on
the pan link) relative to the frame ``mast_top`` of the base link; the URDF holds the
same poses resolved by hand (its comments show the arithmetic). Both are rendered with
the pan joint turned, under one target, with pybullet's TinyRenderer, which is
deterministic: the images must be equal pixel for pixel.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from sensorkit.render import render_preview
from sensorkit.render.png import read_png

HERE = Path(__file__).parent / "robots" / "sdf" / "render"
TWIN_URDF = HERE / "twin_bot.urdf"
TWIN_SDF = HERE / "twin_bot.sdf"
PAIR_WORLD = HERE / "pair_world.sdf"
PLANE_WORLD = HERE / "plane_world.sdf"
IMAGES = ("top_cam/rgb.png", "back_cam/rgb.png", "overview.png")


def _pixels(path: Path) -> np.ndarray:
    return np.asarray(read_png(path.read_bytes()))


@pytest.fixture(scope="module")
def twins(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    out = tmp_path_factory.mktemp("twins")
    for robot, name in ((TWIN_URDF, "urdf"), (TWIN_SDF, "sdf")):
        render_preview(robot, out / name, target="harmonic", joints={"pan": 0.5})
    return out / "urdf", out / "sdf"


@pytest.mark.parametrize("image", IMAGES)
def test_the_sdf_twin_renders_the_same_pixels_as_the_urdf(
    twins: tuple[Path, Path], image: str
) -> None:
    urdf, sdf = (_pixels(folder / image) for folder in twins)
    assert urdf.shape == sdf.shape
    assert np.array_equal(urdf, sdf), (
        f"{image}: {int((urdf != sdf).any(axis=-1).sum())} pixels differ"
    )


def test_the_back_camera_sees_the_robot_it_draws(twins: tuple[Path, Path]) -> None:
    # back_cam looks back at the robot from 1.2 m: the blue body (diffuse 0.2 0.4 0.8,
    # lit: about 30 61 122) fills a block in the middle of its image, so the SDF visuals
    # were drawn, not only the room.
    rgb = _pixels(twins[1] / "back_cam/rgb.png").astype(int)
    block = rgb[60:85, 50:90]
    body = (np.abs(block - np.array([30, 61, 122])) < 25).all(axis=-1)
    assert body.mean() > 0.9


def test_a_camera_placed_relative_to_a_frame_of_another_link_is_where_sdf_says(
    twins: tuple[Path, Path], tmp_path: Path
) -> None:
    # The same SDF with top_cam's relative_to dropped puts the camera 0.5 m lower in the
    # pan link: the view changes, so the equality above holds because the frame is used.
    text = TWIN_SDF.read_text().replace(
        '<pose relative_to="mast_top">0.05 0 0 0 0.3 0</pose>', "<pose>0.05 0 0 0 0.3 0</pose>"
    )
    moved = tmp_path / "twin_bot.sdf"
    moved.write_text(text)
    (tmp_path / "meshes").mkdir()
    shutil.copy(HERE / "meshes" / "cube.obj", tmp_path / "meshes" / "cube.obj")
    render_preview(moved, tmp_path / "moved", target="harmonic", joints={"pan": 0.5})
    before = _pixels(twins[1] / "top_cam/rgb.png")
    after = _pixels(tmp_path / "moved" / "top_cam/rgb.png")
    assert not np.array_equal(before, after)


def _run(*args: str | Path, env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "sensorkit", *(str(a) for a in args)],
        capture_output=True,
        text=True,
        timeout=600,
        env={**os.environ, **(env or {})},
        check=False,
    )


def test_the_command_says_what_it_does_not_draw(tmp_path: Path) -> None:
    out = tmp_path / "out"
    proc = _run("render", "preview", TWIN_SDF, "--out", out, "--target", "harmonic")
    assert proc.returncode == 0, proc.stderr
    said = "not drawn: visual 'footprint' of link 'base_link'"
    line = next(x for x in proc.stderr.splitlines() if said in x)
    assert "<plane> geometry is not drawn" in line
    assert "Traceback" not in proc.stderr
    page = (out / "index.html").read_text()
    assert "footprint" in page and "&lt;plane&gt; geometry is not drawn" in page
    assert (out / "top_cam" / "rgb.png").is_file()


@pytest.mark.parametrize(
    ("world", "note", "drawn"),
    [
        (PAIR_WORLD, "previewing 'scout', the first with sensors (not 'rover')", "front_cam"),
        (
            PLANE_WORLD,
            "previewing 'rig', the first with sensors (not 'ground_plane')",
            "rig_cam",
        ),
    ],
)
def test_a_world_previews_its_first_model_with_sensors_and_says_so(
    tmp_path: Path, world: Path, note: str, drawn: str
) -> None:
    out = tmp_path / "out"
    proc = _run("render", "preview", world, "--out", out)
    assert proc.returncode == 0, proc.stderr
    notes = [x for x in proc.stderr.splitlines() if "world holds" in x]
    assert notes == [f"note: the world holds 2 models: {note}"]
    assert [p.name for p in out.iterdir() if p.is_dir()] == [drawn]


def test_missing_meshes_and_shapes_pybullet_lacks_are_named(tmp_path: Path) -> None:
    model = tmp_path / "m.sdf"
    model.write_text(
        '<sdf version="1.9"><model name="m"><link name="l">'
        '<visual name="hull"><geometry><mesh><uri>meshes/hull.dae</uri></mesh></geometry></visual>'
        '<visual name="pill"><geometry><capsule><radius>0.1</radius><length>0.2</length>'
        "</capsule></geometry></visual>"
        '<visual name="box"><geometry><box><size>0.1 0.1 0.1</size></box></geometry></visual>'
        "</link></model></sdf>"
    )
    proc = _run("render", "preview", model, "--out", tmp_path / "out")
    assert proc.returncode == 0, proc.stderr
    notes = [x for x in proc.stderr.splitlines() if "not drawn" in x]
    assert len(notes) == 2
    assert notes[0].startswith("note: SDF: not drawn: visual 'hull' of link 'l' (")
    assert notes[0].endswith(f"): no file at {tmp_path / 'meshes' / 'hull.dae'}")
    assert notes[1].endswith("): <capsule> geometry is not drawn")


def test_a_stamped_frame_the_sdf_model_lacks_is_not_known_not_a_warning() -> None:
    """As SK501 on SDF: TF may hold a frame the SDF lacks (a URDF kept beside it, as nav2's
    gz_waffle.sdf.xacro and turtlebot3_waffle.urdf are), so the preview does not warn."""
    import numpy as np

    from sensorkit.render.checks import frame_check

    sdf = frame_check(np.eye(4), None, "camera_depth_frame", "<gz_frame_id>", optical=True, sdf=True)
    assert sdf.status == "skipped" and "no frame of this SDF model" in sdf.message
    urdf = frame_check(np.eye(4), None, "camera_depth_frame", "<gz_frame_id>", optical=True)
    assert urdf.status == "warn" and "not a link of the URDF" in urdf.message
