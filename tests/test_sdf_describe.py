"""``topics``, ``intrinsics``, ``export`` and ``frames`` on SDF models and worlds, through
the command line.

``tests/robots/sdf/render/pair_world.sdf`` is the world ``yard`` of two models, each
with a camera named ``front_cam``: scout's on its link ``base`` with ``<topic>
scout/front/image``, 320x240 and a horizontal FOV of pi/2; rover's on ``cam_link`` of
its nested model ``head``, 640x480, FOV 1.0, without ``<topic>``, beside a
``gpu_lidar`` ``scan`` on ``chassis``. Expected values are worked out here by hand:

- frame_id: gz-sim names a sensor by its scoped name without the world,
  MODEL::...::LINK::SENSOR (gazebosim/gz-sim@gz-sim8_8.14.0:src/Util.cc:138-183 with
  "::"; cameras: src/rendering/RenderUtil.cc:1719-1721, lidars:
  gazebosim/gz-sensors@gz-sensors8:src/Lidar.cc:260-266);
- a sensor without ``<topic>`` publishes on its scoped name with "/" and each entity's
  type, world first: /world/W/model/M/model/NESTED/link/L/sensor/S, then /image or /scan
  (gazebosim/gz-sim@gz-sim8_8.14.0:src/Util.cc:138-183, the suffixes at
  gazebosim/gz-sim@gz-sim8:src/rendering/RenderUtil.cc:1737-1744); a lidar adds
  /points for its cloud;
- camera_info beside the image topic, TOPIC's last part replaced by camera_info
  (gazebosim/gz-sensors@gz-sensors8 c8159af:src/CameraSensor.cc:662-676);
- intrinsics: fx = (width / 2) / tan(hfov / 2), cx = width / 2, cy = height / 2.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
import yaml

HERE = Path(__file__).parent / "robots" / "sdf" / "render"
WORLD = HERE / "pair_world.sdf"
TWIN = HERE / "twin_bot.sdf"


def run(*args: str | Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "sensorkit", *(str(a) for a in args)],
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )


def run_json(*args: str | Path) -> Any:
    proc = run(*args)
    assert proc.returncode == 0, proc.stderr
    assert "Traceback" not in proc.stderr
    return json.loads(proc.stdout)


def test_topics_cover_every_model_of_a_world() -> None:
    doc = run_json("topics", WORLD, "-f", "json")
    assert doc["world"] == "yard"
    assert [m["robot"] for m in doc["models"]] == ["scout", "rover"]
    got = {
        m["robot"]: sorted((t["gz_topic"], t["frame_id"]) for t in m["topics"])
        for m in doc["models"]
    }
    assert got["scout"] == [
        ("/scout/front/camera_info", "scout::base::front_cam"),
        ("/scout/front/image", "scout::base::front_cam"),
    ]
    scoped = "/world/yard/model/rover"
    assert got["rover"] == [
        (f"{scoped}/link/chassis/sensor/scan/scan", "rover::chassis::scan"),
        (f"{scoped}/link/chassis/sensor/scan/scan/points", "rover::chassis::scan"),
        (
            f"{scoped}/model/head/link/cam_link/sensor/front_cam/camera_info",
            "rover::head::cam_link::front_cam",
        ),
        (
            f"{scoped}/model/head/link/cam_link/sensor/front_cam/image",
            "rover::head::cam_link::front_cam",
        ),
    ]


def test_topics_text_has_one_table_per_model() -> None:
    proc = run("topics", WORLD)
    assert proc.returncode == 0, proc.stderr
    heads = [line for line in proc.stdout.splitlines() if line.startswith("model ")]
    assert heads == ["model scout:", "model rover:"]
    summaries = [x for x in proc.stderr.splitlines() if " not bridged from " in x]
    assert len(summaries) == 2
    assert "of scout (" in summaries[0] and "of rover (" in summaries[1]


def test_an_sdf_model_file_keeps_the_one_robot_output() -> None:
    # A model file is spawned under a name sensorkit cannot know: WORLD and MODEL stay.
    doc = run_json("topics", TWIN, "-f", "json", "--target", "harmonic")
    assert doc["robot"] == "twin_bot"
    gz = {t["gz_topic"] for t in doc["topics"]}
    assert "/world/WORLD/model/MODEL/link/pan_link/sensor/top_cam/image" in gz
    assert {t["frame_id"] for t in doc["topics"]} == {
        "twin_bot::pan_link::top_cam",
        "twin_bot::base_link::back_cam",
    }


def test_frames_give_a_tree_per_model() -> None:
    doc = run_json("frames", WORLD, "-f", "json")
    models = {m["robot"]: m for m in doc["models"]}
    assert models["scout"]["roots"] == ["base"]
    assert models["rover"]["roots"] == ["chassis"]
    assert [(f["name"], f["parent"]) for f in models["rover"]["frames"]] == [
        ("chassis", None),
        ("head::cam_link", "chassis"),
    ]
    stamps = {s["name"]: [f["frame"] for f in s["frame_ids"]] for s in models["rover"]["sensors"]}
    assert stamps == {
        "scan": ["rover::chassis::scan"],
        "front_cam": ["rover::head::cam_link::front_cam"],
    }
    text = run("frames", WORLD).stdout
    assert [x for x in text.splitlines() if x.startswith("robot name is")] == [
        "robot name is: scout",
        "robot name is: rover",
    ]


def test_intrinsics_of_every_camera_of_a_world() -> None:
    doc = run_json("intrinsics", WORLD)
    cams = {m["robot"]: m["cameras"] for m in doc["models"]}
    (scout,) = cams["scout"]
    (rover,) = cams["rover"]
    # gz computes in single precision: 1e-6 relative
    assert scout["fx"] == pytest.approx(160.0 / math.tan(math.pi / 4), rel=1e-6)
    assert (scout["cx"], scout["cy"]) == (160.0, 120.0)
    assert rover["fx"] == pytest.approx(320.0 / math.tan(0.5), rel=1e-6)
    assert (rover["cx"], rover["cy"]) == (320.0, 240.0)
    assert scout["frame_id"] == "scout::base::front_cam"
    assert rover["frame_id"] == "rover::head::cam_link::front_cam"


def test_one_camera_format_needs_the_model_named() -> None:
    proc = run("intrinsics", WORLD, "-f", "camera-info")
    assert proc.returncode == 2
    assert proc.stderr.strip().splitlines()[-1] == (
        "sensorkit: cameras in 2 models of the world (scout, rover): -f camera-info holds "
        "one; name it with --sensor MODEL::SENSOR, or use -f json"
    )
    proc = run("intrinsics", WORLD, "-f", "camera-info", "--sensor", "rover::front_cam")
    assert proc.returncode == 0, proc.stderr
    info = yaml.safe_load(proc.stdout)
    assert (info["image_width"], info["image_height"]) == (640, 480)
    proc = run("intrinsics", WORLD, "-f", "camera-info", "--sensor", "nope::front_cam")
    assert proc.returncode == 2
    assert "the world has no model 'nope' (models: scout, rover)" in proc.stderr
    assert "Traceback" not in proc.stderr


def test_export_writes_each_model_into_its_own_folder(tmp_path: Path) -> None:
    out = tmp_path / "out"
    proc = run("export", WORLD, "-o", out)
    # rover's sensors have no <topic>: its bridge and LaserScan consumers are skipped
    assert proc.returncode == 1, proc.stderr
    scout = yaml.safe_load((out / "scout/front_cam/camera_info.yaml").read_text())
    rover = yaml.safe_load((out / "rover/front_cam/camera_info.yaml").read_text())
    assert (scout["image_width"], rover["image_width"]) == (320, 640)
    assert not (out / "front_cam").exists()
    entries = yaml.safe_load((out / "scout/bridge.yaml").read_text())
    # ros_gz_bridge reads a list of maps with these keys (its bridge_config.cpp)
    gz = {(e["gz_topic_name"], e["gz_type_name"], e["direction"]) for e in entries}
    assert gz == {
        ("/clock", "gz.msgs.Clock", "GZ_TO_ROS"),
        ("scout/front/image", "gz.msgs.Image", "GZ_TO_ROS"),
        ("scout/front/camera_info", "gz.msgs.CameraInfo", "GZ_TO_ROS"),
    }
    assert "rover/bridge.yaml: sensor 'scan' is not bridged" in proc.stderr
    assert "for 3 sensors of 2 models (scout, rover)" in proc.stderr


def test_export_of_an_sdf_model_bridges_its_link_sensors(tmp_path: Path) -> None:
    # Sensors of an SDF model sit in its links, not in <gazebo> blocks.
    model = tmp_path / "cam.sdf"
    model.write_text(
        '<sdf version="1.9"><model name="m"><link name="l">'
        '<sensor name="c" type="camera"><topic>m/cam</topic><camera>'
        "<horizontal_fov>1</horizontal_fov><image><width>64</width><height>48</height>"
        "</image></camera></sensor></link></model></sdf>"
    )
    out = tmp_path / "out"
    proc = run("export", model, "-o", out)
    assert proc.returncode == 0, proc.stderr
    entries = yaml.safe_load((out / "bridge.yaml").read_text())
    assert {e["gz_topic_name"] for e in entries} == {"/clock", "m/cam", "m/camera_info"}
