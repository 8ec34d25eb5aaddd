"""A partial ``<lens><intrinsics>`` or ``<lens><projection>``: what it leaves out takes
sdformat's defaults fx=fy=277, cx=160, cy=120 (SK412; issue 23, wrong fact 1).

Sources (read in the repositories themselves):

- sdformat loads each value with ``Get<double>(tag, current)`` once the block is written
  (gazebosim/sdformat@sdf14 8512585:src/Camera.cc:421-435 intrinsics, :437-452 projection;
  @sdf12 b9417e5 (Fortress) and @sdf13 31bbc9b: :419-433, :435-450), and Element::Get takes
  the element description's default for a child not written (@sdf14:include/sdf/Element.hh:
  1075-1077). The defaults: sdf/1.9/camera.sdf:181-193 (fx 277, fy 277, cx 160, cy 120, s 0)
  and :200-215 (p_fx 277, p_fy 277, p_cx 160, p_cy 120, tx 0, ty 0) on sdf12, sdf13, sdf14.
- gz-sensors publishes camera_info K from the intrinsics and P from the projection
  (gazebosim/gz-sensors@gz-sensors8 c8159af:src/CameraSensor.cc:729-735 K, :744-752 P) and
  renders with the intrinsics (:858-873), then with the projection (:898-914); K without
  <intrinsics> is read back from the horizontal_fov projection (:844-857), before the
  projection block replaces the render matrix. The same on @ign-sensors6 7cfaddf (Fortress:
  :257-271, :309-325; K :740-746, P :755-763).
- Gazebo Classic renders with the intrinsics, defaults included (sdformat@sdf9:
  sdf/1.7/camera.sdf:146-158 gives the same 277/277/160/120;
  elysia-best/gazebo-classic@debian/11.10.2+dfsg-1:gazebo/rendering/Camera.cc:194-210,
  Camera::LoadCameraIntrinsics, ``sdfIntrinsics->Get<double>("fx")``), and never reads
  <lens><projection> (nothing under gazebo/ reads "projection" or "p_fx").
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest
import yaml
from typer.testing import CliRunner

from sensorkit.base.findings import Severity
from sensorkit.cli import app
from sensorkit.describe.sensorinfo import describe, load
from sensorkit.knowledge.gazebo_sim import (
    SDF_LENS_INTRINSICS_DEFAULTS,
    SDF_LENS_PROJECTION_DEFAULTS,
    lens_block_values,
)

HFOV = 1.047
FX_640 = 320 / math.tan(HFOV / 2)  # 554.38: what a 640 px eye at horizontal_fov 1.047 has


def _camera(name: str, y: float, lens: str, *, width: int = 640, height: int = 480) -> str:
    return (
        f'<sensor name="{name}" type="camera"><update_rate>30</update_rate>'
        f"<topic>{name}/image</topic><gz_frame_id>base_link</gz_frame_id><pose>0 {y} 0 0 0 0</pose>"
        f"<camera><horizontal_fov>{HFOV}</horizontal_fov><image><width>{width}</width>"
        f"<height>{height}</height></image><clip><near>0.1</near><far>100</far></clip>{lens}"
        "</camera></sensor>"
    )


def _robot(*sensors: str) -> str:
    return (
        '<?xml version="1.0"?><robot name="pair"><link name="base_footprint"/>'
        '<link name="base_link"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" '
        'ixy="0" ixz="0" iyz="0"/></inertial></link><joint name="j" type="fixed">'
        '<parent link="base_footprint"/><child link="base_link"/></joint>'
        f'<gazebo reference="base_link">{"".join(sensors)}</gazebo></robot>'
    )


RIGHT_TX_ONLY = _robot(
    _camera("left", 0.05, ""),
    _camera("right", -0.05, "<lens><projection><tx>-27.7</tx></projection></lens>"),
)


def _write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "robot.urdf"
    path.write_text(text)
    return path


def _sk412(check, text: str, target: str) -> list:  # type: ignore[no-untyped-def]
    return [f for f in check(text, target=target).findings if f.rule == "SK412"]


def test_defaults_are_sdformats() -> None:
    # sdformat@sdf14:sdf/1.9/camera.sdf:181-193 and :200-215 (same on sdf12, sdf13)
    assert SDF_LENS_INTRINSICS_DEFAULTS == {"fx": 277, "fy": 277, "cx": 160, "cy": 120, "s": 0}
    assert SDF_LENS_PROJECTION_DEFAULTS == {
        "p_fx": 277, "p_fy": 277, "p_cx": 160, "p_cy": 120, "tx": 0, "ty": 0,
    }  # fmt: skip
    assert lens_block_values("projection", {"tx": -5.0}) == {
        "p_fx": 277, "p_fy": 277, "p_cx": 160, "p_cy": 120, "tx": -5.0, "ty": 0,
    }  # fmt: skip


@pytest.mark.parametrize("target", ["fortress", "harmonic", "jetty"])
def test_sk412_right_eye_with_only_tx(check, target: str) -> None:
    # gz-sensors@gz-sensors8:src/CameraSensor.cc:744-752 (P), :898-914 (render); ign-sensors6
    # :755-763, :309-325
    (f,) = _sk412(check, RIGHT_TX_ONLY, target)
    assert f.severity == Severity.WARNING and f.sensor == "right"
    assert "leaves out p_fx, p_fy, p_cx, p_cy" in f.message
    assert "P = [277, 0, 160, -27.7; 0, 277, 120, 0; 0, 0, 1, 0]" in f.message
    assert "renders the image with it" in f.message
    assert "<p_fx>554.383</p_fx>" in (f.fix or "") and "<p_cx>320</p_cx>" in (f.fix or "")


def test_sk412_partial_intrinsics_on_gz(check) -> None:
    # sdformat@sdf14:src/Camera.cc:421-435; gz-sensors@gz-sensors8:src/CameraSensor.cc:729-735 (K)
    lens = "<lens><intrinsics><fx>554.4</fx><fy>554.4</fy></intrinsics></lens>"
    (f,) = _sk412(check, _robot(_camera("cam", 0.0, lens)), "harmonic")
    assert "<lens><intrinsics> leaves out cx, cy" in f.message
    assert "K = [554.4, 0, 160; 0, 554.4, 120; 0, 0, 1] (and P from it)" in f.message


def test_sk412_near_misses(check) -> None:
    full_proj = (
        f"<lens><projection><p_fx>{FX_640}</p_fx><p_fy>{FX_640}</p_fy><p_cx>320</p_cx>"
        "<p_cy>240</p_cy><tx>-27.7</tx></projection></lens>"
    )
    full_intr = (
        f"<lens><intrinsics><fx>{FX_640}</fx><fy>{FX_640}</fy><cx>320</cx><cy>240</cy>"
        "</intrinsics></lens>"
    )
    # complete blocks (tx, ty and s left out are 0: a left eye, a mono camera)
    for lens in (full_proj, full_intr):
        assert _sk412(check, _robot(_camera("cam", 0.0, lens)), "harmonic") == []
    # the defaults are what a 320 x 240 image at horizontal_fov 1.047 gives anyway
    tx_only = "<lens><projection><tx>-13.85</tx></projection></lens>"
    small = _robot(_camera("cam", 0.0, tx_only, width=320, height=240))
    assert _sk412(check, small, "harmonic") == []
    # Gazebo Classic never reads <lens><projection>
    # (gazebo-classic@11.10.2:gazebo/rendering/Camera.cc:194-210 reads <intrinsics> only)
    assert _sk412(check, RIGHT_TX_ONLY, "classic") == []


def test_sk412_partial_intrinsics_on_classic(check) -> None:
    # gazebo-classic@11.10.2:gazebo/rendering/Camera.cc:199-207 renders with
    # Get<double>("cx"), whose default is 160 (sdformat@sdf9:sdf/1.7/camera.sdf:152)
    lens = f"<lens><intrinsics><fx>{FX_640}</fx><fy>{FX_640}</fy></intrinsics></lens>"
    (f,) = _sk412(check, _robot(_camera("cam", 0.0, lens)), "classic")
    assert "Gazebo Classic renders the image with" in f.message and "cx 160, cy 120" in f.message


def test_intrinsics_output_for_the_right_eye_with_only_tx(tmp_path: Path) -> None:
    # gz-sensors@gz-sensors8:src/CameraSensor.cc:744-752: P from LensProjection*, the defaults
    # for what <projection> leaves out; K from horizontal_fov (:844-857), as before.
    info = describe(load(_write(tmp_path, RIGHT_TX_ONLY)), "harmonic")
    right = next(c for s in info.sensors for c in s.cameras if c.id == "right")
    assert right.intrinsics is not None
    assert right.intrinsics.P.tolist() == [[277, 0, 160, -27.7], [0, 277, 120, 0], [0, 0, 1, 0]]
    assert right.intrinsics.fx == pytest.approx(FX_640, rel=1e-6)
    assert right.intrinsics.cx == 320 and right.intrinsics.cy == 240
    assert any("leaves out p_fx=277" in n for n in right.notes)
    result = CliRunner().invoke(
        app, ["intrinsics", "--target", "harmonic", str(tmp_path / "robot.urdf")]
    )
    assert result.exit_code == 0, result.output
    doc = yaml.safe_load(result.stdout)
    cam = next(c for c in doc["cameras"] if c["camera"] == "right")
    assert cam["P"] == [[277, 0, 160, -27.7], [0, 277, 120, 0], [0, 0, 1, 0]]


def test_intrinsics_of_a_partial_intrinsics_block(tmp_path: Path) -> None:
    # sdformat@sdf14:src/Camera.cc:421-435 fills cx, cy with 160, 120; gz-sensors publishes K
    # from them (@gz-sensors8:src/CameraSensor.cc:729-735) and, with no <projection>, P read
    # back from the matrix built from them (:858-873, :880-896)
    lens = "<lens><intrinsics><fx>500</fx><fy>500</fy></intrinsics></lens>"
    info = describe(load(_write(tmp_path, _robot(_camera("cam", 0.0, lens)))), "harmonic")
    (cam,) = info.sensors[0].cameras
    assert cam.intrinsics is not None
    assert (cam.intrinsics.fx, cam.intrinsics.cx, cam.intrinsics.cy) == (500, 160, 120)


def test_export_camera_info_says_what_gz_publishes(tmp_path: Path) -> None:
    # gz-sensors@gz-sensors8:src/CameraSensor.cc:744-752
    path = _write(tmp_path, RIGHT_TX_ONLY)
    out = tmp_path / "out"
    result = CliRunner().invoke(app, ["export", "--target", "harmonic", "-o", str(out), str(path)])
    assert result.exit_code == 0, result.output
    info = yaml.safe_load((out / "right" / "camera_info.yaml").read_text())
    assert info["projection_matrix"]["data"] == [277, 0, 160, -27.7, 0, 277, 120, 0, 0, 0, 1, 0]
    assert info["camera_matrix"]["data"][0] == pytest.approx(FX_640, rel=1e-6)
