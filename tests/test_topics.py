"""``sensorkit topics``: every topic a robot's sensors publish, with type, frame_id, encoding
and rate; Gazebo Sim topics with the ROS name their bridge entry gives, or "not bridged"."""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

import pytest
import yaml
from typer.testing import CliRunner

from sensorkit.cli import app
from sensorkit.describe.topics import classic_encoding, gz_encoding

OPTICAL_RPY = "-1.5707963267948966 0 -1.5707963267948966"
# One line of `ros2 topic list -t`: '{topic_name} [{types}]'
# (ros2/ros2cli@humble 28d73d25:ros2topic/ros2topic/verb/list.py:74-79).
ROS2_LIST_LINE = re.compile(r"^/\S+ \[[A-Za-z0-9_]+/(msg/)?[A-Za-z0-9_]+(, [^\]]+)?\]$")


def robot(sensor: str, *, name: str = "rover", extra: str = "") -> str:
    """base_link -> camera_link (the sensor's link) -> camera_link_optical."""
    return (
        f'<?xml version="1.0"?>\n<robot name="{name}">\n'
        '<link name="base_link"><inertial><mass value="5"/>'
        '<inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>\n'
        '<link name="camera_link"><inertial><mass value="0.1"/>'
        '<inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial></link>\n'
        '<joint name="camera_joint" type="fixed"><parent link="base_link"/>'
        '<child link="camera_link"/><origin xyz="0.2 0 0.3" rpy="0 0 0"/></joint>\n'
        '<link name="camera_link_optical"/>\n'
        '<joint name="camera_optical_joint" type="fixed"><parent link="camera_link"/>'
        f'<child link="camera_link_optical"/><origin xyz="0 0 0" rpy="{OPTICAL_RPY}"/></joint>\n'
        f'<gazebo reference="camera_link">{sensor}</gazebo>\n{extra}\n</robot>\n'
    )


def camera_block(fmt: str | None = "B8G8R8", name: str = "") -> str:
    tag = f"<format>{fmt}</format>" if fmt is not None else ""
    named = f' name="{name}"' if name else ""
    return (
        f"<camera{named}><horizontal_fov>1.047</horizontal_fov>"
        f"<image><width>640</width><height>480</height>{tag}</image>"
        "<clip><near>0.05</near><far>8</far></clip></camera>"
    )


def classic_depth_camera(plugin_params: str = "") -> str:
    return (
        '<sensor name="camera" type="depth"><update_rate>15</update_rate>'
        f"{camera_block()}"
        '<plugin name="camera_controller" filename="libgazebo_ros_camera.so">'
        f"<frame_name>camera_link_optical</frame_name>{plugin_params}</plugin></sensor>"
    )


GZ_SENSORS_SYSTEM = (
    '<gazebo><plugin filename="gz-sim-sensors-system" name="gz::sim::systems::Sensors">'
    "<render_engine>ogre2</render_engine></plugin></gazebo>"
)


def gz_camera(topic: str | None = "front/image", fmt: str | None = "R8G8B8") -> str:
    tag = f"<topic>{topic}</topic>" if topic is not None else ""
    return (
        f'<sensor name="front" type="camera"><update_rate>30</update_rate>{tag}'
        f"<gz_frame_id>camera_link_optical</gz_frame_id>{camera_block(fmt)}</sensor>"
    )


def run(*args: Any) -> Any:
    result = CliRunner().invoke(app, [str(a) for a in args])
    assert result.exception is None or isinstance(result.exception, SystemExit), result.exception
    return result


def topics_of(path: Path, *args: Any) -> dict[str, Any]:
    result = run("topics", path, "--format", "json", *args)
    assert result.exit_code == 0, result.stderr
    doc: dict[str, Any] = json.loads(result.stdout)
    return doc


def write(tmp_path: Path, text: str, name: str = "robot.urdf") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


# --------------------------------------------------------------------------- Gazebo Classic


def test_classic_depth_camera_publishes_exactly_five_topics(tmp_path: Path) -> None:
    # gazebo_ros_camera on a depth sensor: <camera_name>/image_raw, camera_info,
    # depth/image_raw, depth/camera_info, points; camera_name defaults to the sensor's name
    # (ros-simulation/gazebo_ros_pkgs@ros2 d52f7c4:gazebo_plugins/src/gazebo_ros_camera.cpp:179,
    # :187, :200, :241, :250, :260). Types: image_transport (Image) :189/:243, CameraInfo
    # :202/:253, PointCloud2 :262. Encodings: B8G8R8 -> bgr8 (:306-308), depth TYPE_32FC1 (:660).
    doc = topics_of(write(tmp_path, robot(classic_depth_camera())))
    assert doc["target"] == "classic"
    got = {t["topic"]: t for t in doc["topics"]}
    assert list(got) == sorted(got)  # sorted by name, as ros2 topic list prints them
    assert set(got) == {
        "/camera/image_raw",
        "/camera/camera_info",
        "/camera/depth/image_raw",
        "/camera/depth/camera_info",
        "/camera/points",
    }
    types = {name: t["type"] for name, t in got.items()}
    assert types == {
        "/camera/image_raw": "sensor_msgs/msg/Image",
        "/camera/camera_info": "sensor_msgs/msg/CameraInfo",
        "/camera/depth/image_raw": "sensor_msgs/msg/Image",
        "/camera/depth/camera_info": "sensor_msgs/msg/CameraInfo",
        "/camera/points": "sensor_msgs/msg/PointCloud2",
    }
    assert {t["frame_id"] for t in got.values()} == {"camera_link_optical"}
    assert got["/camera/image_raw"]["encoding"] == "bgr8"
    assert got["/camera/depth/image_raw"]["encoding"] == "32FC1"
    assert all(got[n]["encoding"] is None for n in got if not n.endswith("image_raw"))
    assert {t["rate"] for t in got.values()} == {15.0}
    assert {t["sensor"] for t in got.values()} == {"camera"}
    assert all(t["gz_topic"] is None and t["bridged"] is None for t in got.values())


def test_list_format_is_ros2_topic_list_and_text_prints_each_row_once(tmp_path: Path) -> None:
    # issue 38: the text output printed the `ros2 topic list -t` lines and then the same
    # topics again as rows; the lines moved to --format list, the rows gained the type
    path = write(tmp_path, robot(classic_depth_camera()))
    listing = run("topics", path, "--format", "list").stdout.splitlines()
    assert listing == [
        "/camera/camera_info [sensor_msgs/msg/CameraInfo]",
        "/camera/depth/camera_info [sensor_msgs/msg/CameraInfo]",
        "/camera/depth/image_raw [sensor_msgs/msg/Image]",
        "/camera/image_raw [sensor_msgs/msg/Image]",
        "/camera/points [sensor_msgs/msg/PointCloud2]",
    ]
    assert all(ROS2_LIST_LINE.match(line) for line in listing)
    result = run("topics", path)
    assert result.exit_code == 0, result.stderr
    header, *rows = result.stdout.splitlines()
    assert header.split() == ["topic", "type", "frame_id", "encoding", "rate", "sensor"]
    row = next(r for r in rows if r.startswith("/camera/image_raw "))
    assert row.split()[:6] == ["/camera/image_raw", "sensor_msgs/msg/Image", "camera_link_optical", "bgr8", "15", "Hz"]
    for name in (line.split()[0] for line in listing):  # each topic once
        assert result.stdout.count(name + " ") == 1, name
    assert "5 ROS topics from 1 sensor of rover (target classic" in result.stderr


def test_namespace_camera_name_and_remapping_are_resolved(tmp_path: Path) -> None:
    # Topics are relative to the node's <ros><namespace> under <camera_name>, and
    # <ros><remapping> renames them (gazebo_plugins/include/gazebo_plugins/gazebo_ros_camera.hpp:41-55
    # @ros2 d52f7c4, the plugin's documented example).
    sensor = (
        '<sensor name="camera" type="camera"><update_rate>30</update_rate>'
        f"{camera_block('L8')}"
        '<plugin name="cam_ctl" filename="libgazebo_ros_camera.so"><ros>'
        "<namespace>/robot1</namespace><remapping>front/image_raw:=front/rgb</remapping></ros>"
        "<camera_name>front</camera_name><frame_name>camera_link_optical</frame_name></plugin>"
        "</sensor>"
    )
    doc = topics_of(write(tmp_path, robot(sensor)))
    got = {t["topic"]: t for t in doc["topics"]}
    assert set(got) == {"/robot1/front/rgb", "/robot1/front/camera_info"}
    assert got["/robot1/front/rgb"]["encoding"] == "mono8"  # L8 (gazebo_ros_camera.cpp:297-299)


def test_multicamera_lists_each_camera_with_its_own_encoding(tmp_path: Path) -> None:
    # A multicamera publishes <camera_name>/<camera>/image_raw and .../camera_info per camera
    # (gazebo_ros_camera.cpp:210-238) with each camera's own format (:293, MultiCameraPlugin::format_).
    sensor = (
        '<sensor name="stereo" type="multicamera"><update_rate>20</update_rate>'
        f"{camera_block('L8', 'left')}{camera_block(None, 'right')}"
        '<plugin name="stereo_ctl" filename="libgazebo_ros_camera.so">'
        "<frame_name>camera_link_optical</frame_name></plugin></sensor>"
    )
    doc = topics_of(write(tmp_path, robot(sensor)))
    got = {t["topic"]: t for t in doc["topics"]}
    assert set(got) == {
        "/stereo/left/image_raw",
        "/stereo/left/camera_info",
        "/stereo/right/image_raw",
        "/stereo/right/camera_info",
    }
    assert got["/stereo/left/image_raw"]["encoding"] == "mono8"
    # no <format>: sdformat's default R8G8B8 (gazebosim/sdformat@sdf10:sdf/1.7/camera.sdf:20) -> rgb8
    assert got["/stereo/right/image_raw"]["encoding"] == "rgb8"
    assert got["/stereo/right/image_raw"]["camera"] == "stereo/right"


def test_ray_sensor_type_follows_output_type(tmp_path: Path) -> None:
    # gazebo_ros_ray_sensor publishes on ~/out what <output_type> names
    # (gazebo_plugins/src/gazebo_ros_ray_sensor.cpp:122-134 @ros2 d52f7c4); an invalid value
    # publishes nothing (:135-138).
    def lidar(output: str) -> str:
        return (
            '<sensor name="laser" type="ray"><update_rate>10</update_rate><ray><scan><horizontal>'
            "<samples>360</samples><resolution>1</resolution><min_angle>-3.14</min_angle>"
            "<max_angle>3.14</max_angle></horizontal></scan><range><min>0.1</min><max>12</max>"
            '</range></ray><plugin name="laser_ctl" filename="libgazebo_ros_ray_sensor.so">'
            "<ros><remapping>~/out:=scan</remapping></ros>"
            f"<output_type>{output}</output_type><frame_name>camera_link</frame_name></plugin></sensor>"
        )

    doc = topics_of(write(tmp_path, robot(lidar("sensor_msgs/LaserScan"))))
    assert [(t["topic"], t["type"], t["frame_id"]) for t in doc["topics"]] == [
        ("/scan", "sensor_msgs/msg/LaserScan", "camera_link")
    ]
    doc = topics_of(write(tmp_path, robot(lidar("sensor_msgs/Range")), "range.urdf"))
    assert [t["type"] for t in doc["topics"]] == ["sensor_msgs/msg/Range"]
    result = run("topics", write(tmp_path, robot(lidar("sensor_msgs/msg/LaserScan")), "bad.urdf"))
    assert result.exit_code == 0
    assert result.stdout.strip() == ""
    assert "is invalid: it publishes nothing" in result.stderr


@pytest.mark.parametrize(
    ("fmt", "encoding"),
    [
        # gazebo_ros_camera.cpp:296-335 @ros2 d52f7c4 (ROS 1: gazebo_ros_camera_utils.cpp:447-494
        # @noetic-devel f9e1a46)
        ("L8", "mono8"),
        ("L_INT8", "mono8"),
        ("L16", "mono16"),
        ("R8G8B8", "rgb8"),
        ("B8G8R8", "bgr8"),
        ("BGR_INT8", "bgr8"),
        ("R16G16B16", "rgb16"),
        ("BAYER_RGGB8", "bayer_rggb8"),
        ("BAYER_GRBG8", "bayer_grbg8"),
        (None, "rgb8"),  # sdformat's default R8G8B8 (sdformat@sdf10:sdf/1.7/camera.sdf:20)
    ],
)
def test_classic_encoding_table(fmt: str | None, encoding: str) -> None:
    assert classic_encoding("image", fmt) == (encoding, None)
    assert classic_encoding("image", fmt, ros1=True) == (encoding, None)


def test_classic_unknown_format_falls_back_to_bgr8() -> None:
    # "Unsupported Gazebo ImageFormat, using BGR8" (gazebo_ros_camera.cpp:336-340 @ros2 d52f7c4)
    encoding, note = classic_encoding("image", "R_FLOAT32")
    assert encoding == "bgr8"
    assert note is not None and "R_FLOAT32" in note
    assert classic_encoding("depth_image", "L8") == ("32FC1", None)  # :660
    assert classic_encoding("camera_info", "L8") == (None, None)


def test_ros1_kinect_types_and_16uc1_depth(tmp_path: Path) -> None:
    # ROS 1: topics under /<robotNamespace>/<cameraName> (gazebo_ros_camera_utils.cpp:288
    # @noetic-devel f9e1a46), ROS 1 type names; openni_kinect publishes 16UC1 depth with
    # <useDepth16UC1Format> (gazebo_ros_openni_kinect.cpp:111-114, :431-438) and PointCloud2
    # points (:123).
    sensor = (
        '<sensor name="kinect" type="depth"><update_rate>20</update_rate>'
        f"{camera_block('B8G8R8')}"
        '<plugin name="kinect_ctl" filename="libgazebo_ros_openni_kinect.so">'
        "<robotNamespace>/bot</robotNamespace><cameraName>kinect</cameraName>"
        "<frameName>camera_link_optical</frameName>{flag}</plugin></sensor>"
    )
    path = write(
        tmp_path, robot(sensor.format(flag="<useDepth16UC1Format>true</useDepth16UC1Format>"))
    )
    doc = topics_of(path)
    assert doc["target"] == "ros1"
    got = {t["topic"]: t for t in doc["topics"]}
    assert {n: t["type"] for n, t in got.items()} == {
        "/bot/kinect/image_raw": "sensor_msgs/Image",
        "/bot/kinect/camera_info": "sensor_msgs/CameraInfo",
        "/bot/kinect/depth/image_raw": "sensor_msgs/Image",
        "/bot/kinect/depth/camera_info": "sensor_msgs/CameraInfo",
        "/bot/kinect/points": "sensor_msgs/PointCloud2",
    }
    assert got["/bot/kinect/depth/image_raw"]["encoding"] == "16UC1"
    assert got["/bot/kinect/image_raw"]["encoding"] == "bgr8"
    doc = topics_of(write(tmp_path, robot(sensor.format(flag="")), "float.urdf"))
    depth = next(t for t in doc["topics"] if t["role"] == "depth_image")
    assert depth["encoding"] == "32FC1"  # gazebo_ros_openni_kinect.cpp:431


def test_sensor_without_plugin_publishes_nothing(tmp_path: Path) -> None:
    sensor = f'<sensor name="camera" type="camera"><update_rate>30</update_rate>{camera_block()}</sensor>'
    path = write(
        tmp_path,
        robot(
            sensor,
            extra='<gazebo><plugin name="d" filename="libgazebo_ros_diff_drive.so"/></gazebo>',
        ),
    )
    result = run("topics", path, "--format", "json")
    assert result.exit_code == 0
    assert json.loads(result.stdout)["topics"] == []
    assert "no ROS plugin" in result.stderr


# --------------------------------------------------------------------------- Gazebo Sim


@pytest.mark.parametrize(
    ("fmt", "target", "encoding", "noted"),
    [
        # sdformat reads the old names into pixel formats (gazebosim/sdformat@sdf14:src/Camera.cc:
        # 1157-1186); gz-sensors renders RGB_INT8, L_INT8, L_INT16 and, from Harmonic, Bayer
        # (gazebosim/gz-sensors@gz-sensors8:src/CameraSensor.cc:288-316; @ign-sensors6:
        # src/CameraSensor.cc:222-238); any other keeps the render camera's PF_R8G8B8
        # (gazebosim/gz-rendering@gz-rendering8:include/gz/rendering/base/BaseCamera.hh:496).
        # ros_gz_bridge: pixel format -> encoding
        # (gazebosim/ros_gz@humble:ros_gz_bridge/src/convert/sensor_msgs.cpp:126-160).
        ("R8G8B8", "harmonic", "rgb8", False),
        ("L8", "harmonic", "mono8", False),
        ("L16", "fortress", "mono16", False),
        ("L_INT16", "jetty", "mono16", False),
        ("B8G8R8", "harmonic", "rgb8", True),
        ("BAYER_RGGB8", "fortress", "rgb8", True),
        (None, "harmonic", "rgb8", False),
    ],
)
def test_gz_camera_encoding(fmt: str | None, target: str, encoding: str, noted: bool) -> None:
    got, note = gz_encoding("image", "camera", fmt, target)
    assert got == encoding
    assert (note is not None) == noted


def test_gz_bayer_has_no_ros_encoding() -> None:
    # gz-sensors8 publishes BAYER_RGGB8 (src/CameraSensor.cc:541-543); ros_gz_bridge has no
    # case for it: "Unsupported pixel format" and return before encoding and data are set
    # (ros_gz@humble:ros_gz_bridge/src/convert/sensor_msgs.cpp:161-165).
    encoding, note = gz_encoding("image", "camera", "BAYER_RGGB8", "harmonic")
    assert encoding is None
    assert note is not None and "empty encoding" in note


def test_gz_depth_and_rgbd_encodings() -> None:
    # Depth images are R_FLOAT32 (gz-sensors8:src/DepthCameraSensor.cc:585,
    # src/RgbdCameraSensor.cc:525) -> 32FC1 (ros_gz@humble:.../sensor_msgs.cpp:158-160);
    # an rgbd_camera's colour image is RGB_INT8 whatever <format> says (RgbdCameraSensor.cc:636).
    assert gz_encoding("depth_image", "depth_camera", None, "harmonic") == ("32FC1", None)
    assert gz_encoding("depth_image", "rgbd_camera", "L8", "fortress") == ("32FC1", None)
    assert gz_encoding("image", "rgbd_camera", "R8G8B8", "jetty") == ("rgb8", None)
    encoding, note = gz_encoding("image", "rgbd_camera", "L8", "harmonic")
    assert encoding == "rgb8" and note is not None


def test_gz_robot_without_bridge_is_not_bridged(tmp_path: Path) -> None:
    path = write(tmp_path, robot(gz_camera(), extra=GZ_SENSORS_SYSTEM))
    result = run("topics", path, "--format", "json")
    assert result.exit_code == 0, result.stderr
    doc = json.loads(result.stdout)
    assert doc["target"] == "harmonic" and doc["bridge_files"] == []
    # camera: <topic> and a sibling camera_info (gazebosim/gz-sensors@gz-sensors8:
    # src/CameraSensor.cc:662-674)
    assert [(t["gz_topic"], t["topic"], t["bridged"]) for t in doc["topics"]] == [
        ("/front/camera_info", None, False),
        ("/front/image", None, False),
    ]
    image = doc["topics"][1]
    assert (image["type"], image["gz_type"], image["encoding"]) == (
        "sensor_msgs/msg/Image",
        "gz.msgs.Image",
        "rgb8",
    )
    assert image["frame_id"] == "camera_link_optical"
    assert "no ros_gz_bridge configuration found" in result.stderr
    text = run("topics", path)
    assert text.stdout.splitlines()[0].split() == [
        "topic",
        "type",
        "gz",
        "topic",
        "frame_id",
        "encoding",
        "rate",
        "sensor",
    ]
    assert re.search(r"^\(not bridged\)  sensor_msgs/msg/Image +/front/image ", text.stdout, re.M)


def test_gz_bridge_file_names_the_ros_topics(tmp_path: Path) -> None:
    path = write(tmp_path, robot(gz_camera(), extra=GZ_SENSORS_SYSTEM))
    bridge = tmp_path / "bridge.yaml"
    bridge.write_text(
        "- gz_topic_name: front/image\n"
        "  ros_topic_name: camera/image_raw\n"
        "  ros_type_name: sensor_msgs/msg/Image\n"
        "  gz_type_name: gz.msgs.Image\n"
        "  direction: GZ_TO_ROS\n"
        "- topic_name: /front/camera_info\n"  # one name for both (bridge_config.cpp:28-45)
        "  ros_type_name: sensor_msgs/msg/CameraInfo\n"
        "  gz_type_name: gz.msgs.CameraInfo\n"
        "  direction: ROS_TO_GZ\n"  # the wrong way: not to ROS
    )
    doc = topics_of(path, "--bridge", bridge)
    assert doc["bridge_files"] and doc["bridge_files"][0].endswith("bridge.yaml")
    got = {t["gz_topic"]: t for t in doc["topics"]}
    assert got["/front/image"]["topic"] == "/camera/image_raw"
    assert got["/front/image"]["bridged"] is True
    assert got["/front/image"]["bridge_entry"].endswith("bridge.yaml:1")
    assert got["/front/camera_info"]["topic"] is None
    text = run("topics", path, "--bridge", bridge, "--format", "list").stdout
    assert text.splitlines()[0] == "/camera/image_raw [sensor_msgs/msg/Image]"


def test_gz_sensor_without_topic_matches_its_scoped_name(tmp_path: Path) -> None:
    # Without <topic> gz-sim publishes on the scoped name plus a suffix
    # (gazebosim/gz-sim@gz-sim8:src/rendering/RenderUtil.cc:1723-1725, :1737-1744).
    path = write(tmp_path, robot(gz_camera(topic=None), extra=GZ_SENSORS_SYSTEM))
    bridge = tmp_path / "bridge.yaml"
    bridge.write_text(
        "- gz_topic_name: /world/empty/model/rover/link/base_link/sensor/front/image\n"
        "  ros_topic_name: front/image_raw\n"
        "  ros_type_name: sensor_msgs/msg/Image\n"
        "  gz_type_name: gz.msgs.Image\n"
        "  direction: GZ_TO_ROS\n"
    )
    doc = topics_of(path, "--bridge", bridge)
    got = {t["role"]: t for t in doc["topics"]}
    # camera_link is lumped into base_link by the URDF-to-SDF conversion
    assert got["image"]["gz_topic"] == "/world/WORLD/model/MODEL/link/base_link/sensor/front/image"
    assert got["image"]["topic"] == "/front/image_raw"
    assert got["camera_info"]["topic"] is None


def test_gz_unsupported_sensor_type_publishes_nothing(tmp_path: Path) -> None:
    # gz-sim creates no CPU lidar (gazebosim/gz-sim@gz-sim8:src/SdfEntityCreator.cc:1092-1098)
    sensor = (
        '<sensor name="laser" type="ray"><topic>scan</topic><ray><scan><horizontal><samples>10'
        "</samples><min_angle>-1</min_angle><max_angle>1</max_angle></horizontal></scan><range>"
        "<min>0.1</min><max>5</max></range></ray></sensor>"
    )
    result = run(
        "topics",
        write(tmp_path, robot(sensor, extra=GZ_SENSORS_SYSTEM)),
        "--target",
        "harmonic",
        "--format",
        "json",
    )
    assert result.exit_code == 0
    assert json.loads(result.stdout)["topics"] == []
    assert "never creates a 'ray' sensor" in result.stderr


def test_new_gz_package_shows_gz_and_bridged_names(tmp_path: Path) -> None:
    spec = tmp_path / "robot.yaml"
    spec.write_text(
        "name: gz_bot\nsim: gz\ngz_version: fortress\nnamespace: robot1\nsensors:\n"
        "  - {type: camera, name: front_camera, xyz: [0.25, 0, 0.1], options: {update_rate: 20}}\n"
        "  - {type: depth_camera, name: rgbd, xyz: [0.2, 0, 0.15]}\n"
        "  - {type: lidar_3d, name: lidar, xyz: [0, 0, 0.3]}\n"
    )
    out = tmp_path / "gz_bot_description"
    assert run("new", spec, "-o", out).exit_code == 0
    doc = topics_of(out / "urdf" / "gz_bot.urdf.xacro")
    assert doc["target"] == "fortress"
    assert doc["bridge_files"] and doc["bridge_files"][0].endswith("config/bridge.yaml")
    bridge = yaml.safe_load((out / "config" / "bridge.yaml").read_text())
    carried = {"/" + e["gz_topic_name"]: "/" + e["ros_topic_name"] for e in bridge}
    got = {t["gz_topic"]: t for t in doc["topics"]}
    for gz, t in got.items():
        assert t["topic"] == carried.get(gz), gz
        assert t["bridged"] is (gz in carried)
    assert got["/robot1/rgbd/image"]["topic"] == "/robot1/rgbd/image_raw"
    assert got["/robot1/rgbd/depth_image"]["topic"] == "/robot1/rgbd/depth/image_raw"
    assert got["/robot1/rgbd/depth_image"]["encoding"] == "32FC1"
    assert got["/robot1/front_camera/image_raw"]["encoding"] == "rgb8"
    assert got["/robot1/front_camera/image_raw"]["rate"] == 20.0
    assert got["/robot1/front_camera/image_raw"]["frame_id"] == "front_camera_optical_frame"
    assert got["/robot1/rgbd/points"]["bridged"] is False  # x-forward cloud: left out on purpose
    assert got["/robot1/lidar/scan/points"]["topic"] == "/robot1/lidar/points"
    assert all(t["gz_type"].startswith("ignition.msgs.") for t in doc["topics"])


# --------------------------------------------------------------------------- refusals


def test_unknown_format_and_missing_file_are_one_line_exit_2(tmp_path: Path) -> None:
    path = write(tmp_path, robot(classic_depth_camera()))
    for result in (
        run("topics", path, "--format", "yaml"),
        run("topics", tmp_path / "missing.urdf"),
        run("topics", path, "--target", "gazebo"),
    ):
        assert result.exit_code == 2, result.stdout
        assert result.stdout == ""
        message = result.stderr.strip()
        assert message.startswith("sensorkit: ") and "\n" not in message


def test_bridge_on_a_classic_robot_is_ignored_with_a_note(tmp_path: Path) -> None:
    path = write(tmp_path, robot(classic_depth_camera()))
    result = run("topics", path, "--bridge", tmp_path / "nothing.yaml")
    assert result.exit_code == 0
    assert "--bridge ignored" in result.stderr


# --------------------------------------------------------------------------- frames to disk

ROOT = Path(__file__).resolve().parent.parent
NODE = ROOT / "templates" / "package" / "save_frames.py"


@pytest.fixture(scope="module")
def node() -> Any:
    """templates/package/save_frames.py, imported with rclpy and sensor_msgs unimportable:
    its ROS-free part must not need them."""
    import importlib.util
    import sys

    blocked = ("rclpy", "sensor_msgs", "cv_bridge")
    saved = {name: sys.modules.get(name) for name in blocked}
    for name in blocked:
        sys.modules[name] = None  # type: ignore[assignment]  # import raises ImportError
    try:
        spec = importlib.util.spec_from_file_location("save_frames_under_test", NODE)
        assert spec is not None and spec.loader is not None
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
    finally:
        for name, value in saved.items():
            if value is None:
                del sys.modules[name]
            else:
                sys.modules[name] = value
    return module


def image_msg(
    pixels: Any,
    encoding: str,
    *,
    big_endian: bool = False,
    pad: int = 0,
    sec: int = 0,
    nanosec: int = 0,
) -> Any:
    """A sensor_msgs/Image-shaped object holding ``pixels`` (rows padded by ``pad`` bytes)."""
    from types import SimpleNamespace

    import numpy as np

    arr = np.asarray(pixels)
    height, width = arr.shape[:2]
    order = ">" if big_endian else "<"
    raw = arr.astype(arr.dtype.newbyteorder(order)).reshape(height, -1).view(np.uint8)
    rows = np.hstack([raw, np.full((height, pad), 0xAB, dtype=np.uint8)])
    stamp = SimpleNamespace(sec=sec, nanosec=nanosec)
    return SimpleNamespace(
        header=SimpleNamespace(stamp=stamp, frame_id="camera_link_optical"),
        height=height,
        width=width,
        encoding=encoding,
        is_bigendian=int(big_endian),
        step=rows.shape[1],
        data=rows.tobytes(),
    )


def decode_png(data: bytes) -> tuple[int, int, Any]:
    """``(bit depth, colour type, pixels)`` of a non-interlaced PNG with filter 0 rows."""
    import struct
    import zlib

    import numpy as np

    assert data.startswith(b"\x89PNG\r\n\x1a\n")
    pos, idat, header = 8, b"", b""
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos : pos + 4])
        kind, body = data[pos + 4 : pos + 8], data[pos + 8 : pos + 8 + length]
        (crc,) = struct.unpack(">I", data[pos + 8 + length : pos + 12 + length])
        assert zlib.crc32(kind + body) == crc
        header = body if kind == b"IHDR" else header
        idat += body if kind == b"IDAT" else b""
        pos += 12 + length
    width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", header)
    assert interlace == 0
    channels = {0: 1, 2: 3, 4: 2, 6: 4}[colour]
    raw = np.frombuffer(zlib.decompress(idat), dtype=np.uint8).reshape(height, -1)
    assert (raw[:, 0] == 0).all()  # filter type 0
    sample = np.dtype(">u2") if depth == 16 else np.dtype(np.uint8)
    pixels = raw[:, 1:].copy().view(sample).astype(sample.newbyteorder("="))
    shape = (height, width) if channels == 1 else (height, width, channels)
    return depth, colour, pixels.reshape(shape)


def test_node_imports_without_ros(node: Any) -> None:
    assert callable(node.main) and callable(node.image_to_array)
    text = NODE.read_text()
    assert text.startswith("#!/usr/bin/env python3\n")
    top_level = text.split("\ndef main(", 1)[0]
    assert "import rclpy" not in top_level and "cv_bridge" not in top_level


@pytest.mark.parametrize("big_endian", [False, True])
@pytest.mark.parametrize(
    ("encoding", "dtype", "channels"),
    [
        ("rgb8", "u1", 3),
        ("bgr8", "u1", 3),
        ("mono8", "u1", 1),
        ("mono16", "u2", 1),
        ("16UC1", "u2", 1),
        ("32FC1", "f4", 1),
        ("rgba8", "u1", 4),
        ("rgb16", "u2", 3),
    ],
)
def test_image_to_array_reads_every_encoding(
    node: Any, encoding: str, dtype: str, channels: int, big_endian: bool
) -> None:
    import numpy as np

    rng = np.random.default_rng(7)
    shape = (3, 5) if channels == 1 else (3, 5, channels)
    if dtype == "f4":
        pixels = rng.uniform(0.1, 9.0, shape).astype(np.float32)
    else:
        pixels = rng.integers(0, np.iinfo(dtype).max, shape, endpoint=True).astype(dtype)
    for pad in (0, 3):  # a step longer than a row: the padding is dropped
        msg = image_msg(pixels, encoding, big_endian=big_endian, pad=pad)
        got = node.image_to_array(msg)
        assert got.dtype == np.dtype(dtype).newbyteorder("=")
        assert got.shape == shape
        np.testing.assert_array_equal(got, pixels)


def test_image_to_array_refuses_what_it_cannot_read(node: Any) -> None:
    import numpy as np

    msg = image_msg(np.zeros((2, 2, 3), np.uint8), "rgb8")
    msg.encoding = "yuv422"
    with pytest.raises(ValueError, match="yuv422"):
        node.image_to_array(msg)
    msg = image_msg(np.zeros((2, 2, 3), np.uint8), "rgb8")
    msg.step = 5  # shorter than a row of 2 rgb8 pixels
    with pytest.raises(ValueError, match="step"):
        node.image_to_array(msg)
    msg = image_msg(np.zeros((2, 2, 3), np.uint8), "rgb8")
    msg.data = msg.data[:-1]
    with pytest.raises(ValueError, match="bytes of data"):
        node.image_to_array(msg)


def test_colour_frames_are_rgb_pngs(node: Any) -> None:
    import numpy as np

    rgb = np.array([[[255, 0, 0], [0, 255, 0]], [[0, 0, 255], [10, 20, 30]]], np.uint8)
    for encoding, pixels in (("rgb8", rgb), ("bgr8", rgb[..., ::-1])):
        ext, data = node.frame_file(image_msg(pixels, encoding, pad=2))
        assert ext == "png"
        depth, colour, got = decode_png(data)
        assert (depth, colour) == (8, 2)
        np.testing.assert_array_equal(got, rgb)  # bgr8 stored in RGB order
    ext, data = node.frame_file(image_msg(rgb[..., 0], "mono8"))
    assert decode_png(data)[:2] == (8, 0)
    mono16 = np.array([[0, 1000], [65535, 300]], np.uint16)
    depth, colour, got = decode_png(
        node.frame_file(image_msg(mono16, "mono16", big_endian=True))[1]
    )
    assert (depth, colour) == (16, 0)
    np.testing.assert_array_equal(got, mono16)


def test_pngs_open_in_pillow(node: Any) -> None:
    pil = pytest.importorskip("PIL.Image")
    import io

    import numpy as np

    rgb = np.arange(2 * 3 * 3, dtype=np.uint8).reshape(2, 3, 3) * 10
    image = pil.open(io.BytesIO(node.frame_file(image_msg(rgb[..., ::-1], "bgr8"))[1]))
    assert image.mode == "RGB"
    np.testing.assert_array_equal(np.asarray(image), rgb)
    depth = np.array([[0.5, 1.25], [np.nan, 3.0]], np.float32)
    image = pil.open(io.BytesIO(node.frame_file(image_msg(depth, "32FC1"))[1]))
    assert image.mode.startswith("I")
    np.testing.assert_array_equal(np.asarray(image), [[500, 1250], [0, 3000]])


def test_depth_to_millimetres_rounds_and_blanks_what_has_no_depth(node: Any) -> None:
    # 32FC1 depth is metres with non-finite values for no depth; 16UC1 is millimetres with
    # 0 for an invalid depth (ros-infrastructure/rep@79f7f76:rep-0118.rst:28-32, :43-48).
    import numpy as np

    metres = np.array(
        [[1.2346, 0.0004, 0.0006, 65.535], [np.nan, np.inf, -np.inf, 0.0], [-1.0, 65.6, 2.0, 1e-9]],
        np.float32,
    )
    mm = node.depth_to_millimetres(metres, "32FC1")
    assert mm.dtype == np.uint16
    np.testing.assert_array_equal(mm, [[1235, 0, 1, 65535], [0, 0, 0, 0], [0, 0, 2000, 0]])
    raw = np.array([[0, 1234], [65535, 7]], np.uint16)  # 16UC1: millimetres already
    np.testing.assert_array_equal(node.depth_to_millimetres(raw, "16UC1"), raw)
    with pytest.raises(ValueError, match="depth encoding"):
        node.depth_to_millimetres(raw, "mono16")


def test_depth_frames_png_in_millimetres_or_npy(node: Any) -> None:
    import io

    import numpy as np

    metres = np.array([[0.5, np.nan], [np.inf, 2.25]], np.float32)
    msg = image_msg(metres, "32FC1", big_endian=True, pad=4)
    ext, data = node.frame_file(msg, "png")
    depth, colour, got = decode_png(data)
    assert (ext, depth, colour) == ("png", 16, 0)
    np.testing.assert_array_equal(got, [[500, 0], [0, 2250]])
    ext, data = node.frame_file(msg, "npy")
    assert ext == "npy"
    np.testing.assert_array_equal(np.load(io.BytesIO(data)), metres)
    with pytest.raises(ValueError, match="png or npy"):
        node.frame_file(msg, "tiff")


def test_interval_and_names(node: Any) -> None:
    assert node.is_due(None, 0.0, 5.0)
    assert not node.is_due(10.0, 14.999, 5.0)
    assert node.is_due(10.0, 15.0, 5.0)
    assert node.is_due(10.0, 3.0, 5.0)  # the clock went back: a reset simulation
    assert node.is_due(10.0, 10.0, 0.0)  # interval 0: every frame
    assert node.topic_folder("/rgbd/depth/image_raw") == "rgbd__depth__image_raw"
    assert node.topic_folder("front_camera/image_raw") == "front_camera__image_raw"
    with pytest.raises(ValueError):
        node.topic_folder("/")
    assert node.frame_name(12, 345000000, "png") == "0000000012_345000000.png"
    names = [node.frame_name(s, n, "png") for s, n in ((9, 999999999), (10, 0), (100, 5))]
    assert names == sorted(names)


def test_frame_saver_writes_one_frame_per_interval(node: Any, tmp_path: Path) -> None:
    import numpy as np

    warnings: list[str] = []
    saver = node.FrameSaver(
        ["/cam/image_raw", "/cam/depth/image_raw"],
        encodings=["bgr8", "32FC1"],
        interval=2.0,
        folder=str(tmp_path / "frames"),
        warn=warnings.append,
    )
    bgr = np.zeros((2, 2, 3), np.uint8)
    saved = [
        saver.offer("/cam/image_raw", image_msg(bgr, "bgr8", sec=s, nanosec=n))
        for s, n in ((1, 0), (2, 500000000), (3, 0), (3, 1))
    ]
    assert [p is not None for p in saved] == [True, False, True, False]
    assert saved[0] == str(tmp_path / "frames" / "cam__image_raw" / "0000000001_000000000.png")
    assert Path(saved[2]).is_file()
    depth = np.ones((2, 2), np.float32)
    path = saver.offer("/cam/depth/image_raw", image_msg(depth, "32FC1", sec=1))
    assert path is not None and path.endswith("cam__depth__image_raw/0000000001_000000000.png")
    # an unexpected encoding is saved, with one warning per topic
    saver.offer("/cam/image_raw", image_msg(bgr, "rgb8", sec=9))
    saver.offer("/cam/image_raw", image_msg(bgr, "rgb8", sec=20))
    assert len([w for w in warnings if "expected 'bgr8'" in w]) == 1
    # an encoding it cannot read is not saved, with one warning
    bad = image_msg(bgr, "rgb8", sec=40)
    bad.encoding = "yuv422"
    assert saver.offer("/cam/image_raw", bad) is None
    assert any("not saved" in w for w in warnings)
    files = sorted(p.name for p in (tmp_path / "frames").rglob("*"))
    assert not any(name.endswith(".tmp") for name in files)
    for wrong in ({"interval": -1.0}, {"depth_format": "jpg"}, {"encodings": ["rgb8"]}):
        with pytest.raises(ValueError):
            node.FrameSaver(["/a", "/b"], **wrong)


# --------------------------------------------------------------------------- generated launch


def _launch_topics(path: Path) -> list[tuple[str, str]]:
    import ast

    tree = ast.parse(path.read_text(), str(path))
    for stmt in tree.body:
        if isinstance(stmt, ast.Assign) and any(
            isinstance(t, ast.Name) and t.id == "TOPICS" for t in stmt.targets
        ):
            value: list[tuple[str, str]] = ast.literal_eval(stmt.value)
            return value
    raise AssertionError(f"{path}: no TOPICS")


def _camera_images(xacro: Path, target: str, bridge: Path | None) -> set[tuple[str, str | None]]:
    from sensorkit.describe.sensorinfo import describe, load
    from sensorkit.describe.topics import BridgeConfig, robot_topics
    from sensorkit.loading.bridge import read_bridge

    info = describe(load(xacro), target)
    config = BridgeConfig([str(bridge)], read_bridge(bridge)) if bridge else None
    return {
        (t.name, t.encoding)
        for t in robot_topics(info, config).ros_topics
        if t.role in ("image", "depth_image") and t.name
    }


CAMERAS_YAML = """\
name: {name}
sim: {sim}
gz_version: jetty
sensors:
  - {{type: camera, name: front_camera, xyz: [0.25, 0, 0.1], options: {{format: B8G8R8}}}}
  - {{type: depth_camera, name: rgbd, xyz: [0.2, 0, 0.15]}}
  - {{type: stereo_camera, name: stereo, xyz: [0.2, 0, 0.3]}}
  - {{type: lidar_2d, name: laser, xyz: [0, 0, 0.3]}}
"""


@pytest.mark.parametrize("sim", ["classic", "gz"])
def test_generated_save_frames_launch_names_every_camera_topic(tmp_path: Path, sim: str) -> None:
    spec = tmp_path / "robot.yaml"
    spec.write_text(CAMERAS_YAML.format(name=f"{sim}_bot", sim=sim))
    out = tmp_path / "pkg"
    result = run("new", spec, "-o", out)
    assert result.exit_code == 0, result.stderr
    launch = out / "launch" / "save_frames.launch.py"
    compile(launch.read_text(), str(launch), "exec")
    topics = _launch_topics(launch)
    target = "classic" if sim == "classic" else "jetty"
    bridge = out / "config" / "bridge.yaml" if sim == "gz" else None
    expected = _camera_images(out / "urdf" / f"{sim}_bot.urdf.xacro", target, bridge)
    assert set(topics) == expected
    names = {t for t, _ in topics}
    assert {"/front_camera/image_raw", "/rgbd/depth/image_raw", "/stereo/left/image_raw"} <= names
    assert "/stereo/right/image_raw" in names and not any("laser" in t for t in names)
    encodings = dict(topics)
    assert encodings["/rgbd/depth/image_raw"] == "32FC1"
    # B8G8R8: bgr8 on Classic (gazebo_ros_camera.cpp:306-308); gz-sensors renders it as
    # R8G8B8 (gz-sensors10:src/CameraSensor.cc:223-251) -> rgb8
    assert encodings["/front_camera/image_raw"] == ("bgr8" if sim == "classic" else "rgb8")
    node_file = out / "scripts" / "save_frames.py"
    assert node_file.read_bytes() == NODE.read_bytes()
    assert node_file.stat().st_mode & 0o111
    cmake = (out / "CMakeLists.txt").read_text()
    assert "PROGRAMS scripts/save_frames.py" in cmake and "DESTINATION lib/${PROJECT_NAME}" in cmake
    deps = (out / "package.xml").read_text()
    for dep in ("rclpy", "sensor_msgs", "python3-numpy"):
        assert f"<exec_depend>{dep}</exec_depend>" in deps
    readme = (out / "README.md").read_text()
    assert "save_frames.launch.py" in readme and "`/rgbd/depth/image_raw`" in readme
    assert f"sensorkit topics urdf/{sim}_bot.urdf.xacro" in readme


def test_no_save_frames_without_cameras_or_simulator(tmp_path: Path) -> None:
    cases = {
        "lidar_only": "name: lidar_only\nsim: gz\nsensors:\n  - {type: lidar_2d, name: laser}\n",
        "bare": CAMERAS_YAML.format(name="bare", sim="none"),
    }
    for name, text in cases.items():
        spec = tmp_path / f"{name}.yaml"
        spec.write_text(text)
        out = tmp_path / name
        assert run("new", spec, "-o", out).exit_code == 0
        assert not (out / "launch" / "save_frames.launch.py").exists()
        assert not (out / "scripts").exists()
        assert "PROGRAMS" not in (out / "CMakeLists.txt").read_text()
        assert "rclpy" not in (out / "package.xml").read_text()


def test_settings_file_and_untrusted_apply(tmp_path: Path) -> None:
    # A sensor with <topic> and a Classic plugin: auto takes Classic, sensorkit.toml says gz.
    sensor = gz_camera().replace(
        "</sensor>",
        '<plugin name="c" filename="libgazebo_ros_camera.so">'
        "<frame_name>camera_link_optical</frame_name></plugin></sensor>",
    )
    path = write(tmp_path, robot(sensor))
    assert topics_of(path)["target"] == "classic"
    (tmp_path / "sensorkit.toml").write_text('target = "fortress"\n')
    result = run("topics", path, "--format", "json", "--untrusted")
    assert result.exit_code == 0, result.stderr
    doc = json.loads(result.stdout)
    assert doc["target"] == "fortress" and "sensorkit.toml" in doc["target_reason"]
    assert {t["gz_type"] for t in doc["topics"]} == {
        "ignition.msgs.Image",
        "ignition.msgs.CameraInfo",
    }
    assert "target fortress from" in result.stderr
    assert topics_of(path, "--target", "classic")["target"] == "classic"  # the flag wins


@pytest.mark.parametrize("rate", ["inf", "0", "-5", "nan"])
def test_a_rate_that_is_no_rate_is_null(tmp_path: Path, rate: str) -> None:
    sensor = classic_depth_camera().replace(
        "<update_rate>15</update_rate>", f"<update_rate>{rate}</update_rate>"
    )
    doc = topics_of(write(tmp_path, robot(sensor)))
    assert len(doc["topics"]) == 5
    assert {t["rate"] for t in doc["topics"]} == {None}


def test_a_triggered_camera_subscribes_to_image_trigger_under_its_name(tmp_path: Path) -> None:
    # gazebo_ros_pkgs@d52f7c4 gazebo_plugins/src/gazebo_ros_camera.cpp:271 reads <triggered>
    # from the plugin element; a <triggered> inside <camera> is not what it reads.
    from builders import camera_sensor, robot

    from sensorkit.lint.rules.topic_names import plugin_topics
    from sensorkit.model import load_robot

    def names(params: str, camera_extra: str = "") -> list[str]:
        cam = camera_sensor(params="<frame_name>camera_optical_frame</frame_name>" + params)
        if camera_extra:
            cam = cam.replace("<camera>", "<camera>" + camera_extra, 1)
        path = tmp_path / "r.urdf"
        path.write_text(robot(camera=cam))
        loaded = load_robot(path)
        assert loaded.robot is not None
        s = next(x for x in loaded.robot.sensors if x.name == "front_camera")
        return plugin_topics(s.plugins[0], s)

    assert "front_camera/image_trigger" in names("<triggered>true</triggered>")
    assert "front_camera/image_trigger" not in names("", "<triggered>true</triggered>")
    assert "front_camera/image_trigger" not in names("<triggered>false</triggered>")


NESTED_ROVER = """<?xml version="1.0"?>
<sdf version="1.9">
  <model name="rover">
    <link name="chassis">
      <sensor name="imu" type="imu"><update_rate>100</update_rate><topic>imu</topic><imu/></sensor>
    </link>
    <include><uri>model://HEAD</uri><name>head</name><pose>0 0 0.5 0 0 0</pose></include>
  </model>
</sdf>
"""
NESTED_HEAD = f"""<?xml version="1.0"?>
<sdf version="1.9">
  <model name="head">
    <link name="cam_link">
      <sensor name="cam" type="camera"><update_rate>30</update_rate><topic>cam</topic>
        {camera_block()}</sensor>
    </link>
  </model>
</sdf>
"""
NESTED_WORLD = """<?xml version="1.0"?>
<sdf version="1.9">
  <world name="demo"><include><uri>model://rover</uri></include></world>
</sdf>
"""


def test_a_missing_nested_include_is_said_with_its_chain(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Issue 38: a model included by a model the world includes, when missing, left half
    the sensors out of `topics` without a word (exit 0). It is said as a world's own
    include is (SK107, what libsdformat does with it: sdf_includes.py), naming the chain
    of includes; validate's SK107 names the chain too."""
    models = tmp_path / "models"
    for name, text in (("rover", NESTED_ROVER.replace("HEAD", "hed")), ("head", NESTED_HEAD)):
        (models / name).mkdir(parents=True)
        (models / name / "model.sdf").write_text(text)
    monkeypatch.setenv("GZ_SIM_RESOURCE_PATH", str(models))  # as gz-sim finds models
    world = write(tmp_path, NESTED_WORLD, "world.sdf")
    res = run("topics", world)
    assert res.exit_code == 0
    said = [ln for ln in res.stderr.splitlines() if "SK107" in ln]
    assert len(said) == 1, res.stderr
    # A model:// URI on none of the paths searched may still be on the model path when the
    # simulation runs (issue 35: cannot tell, info): said as a note, never silent.
    assert "sensorkit: note: " in said[0]
    assert "model.sdf:7: SK107: <include> 'model://hed' is not on the paths sensorkit searched" in said[0]
    assert "world.sdf -> model://rover -> model://hed)" in said[0] and "(nested: " in said[0]
    assert "(what it holds is not listed)" in said[0]
    res = run("validate", world, "--target", "harmonic", "--format", "json")
    (f,) = [f for f in json.loads(res.stdout)["findings"] if f["rule"] == "SK107"]
    assert f["severity"] == "info" and "model://rover -> model://hed)" in f["message"]
    # near miss: the nested include found, both sensors listed and nothing said
    (models / "rover" / "model.sdf").write_text(NESTED_ROVER.replace("HEAD", "head"))
    res = run("topics", world)
    assert res.exit_code == 0 and "SK107" not in res.stderr and "warning" not in res.stderr
    assert "/cam" in res.stdout and "/imu" in res.stdout
