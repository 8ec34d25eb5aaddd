"""Tests for the xacro sensor macros in macros/.

Every macro is expanded with the real xacro library for every simulator variant
(classic; gz with fortress, harmonic and jetty; none), inside a tiny robot written to a
temporary folder, and the result is checked with urdfdom's check_urdf, with lxml against
the frame, plugin, topic and intrinsics rules, and by loading it in pybullet.
"""

from __future__ import annotations

import math
import shutil
import subprocess
import sys
from collections.abc import Callable, Iterable
from pathlib import Path

import pytest
import xacro
from conftest import sdformat_tool
from lxml import etree

try:
    from macro_cases import (
        CASE_IDS,
        CASES,
        CLASSIC_PLUGIN,
        GZ_FRAME_TAG,
        MACROS_DIR,
        OPTICAL_RPY,
        ROS1_TAGS,
        SIM_VARIANTS,
        XACRO_NS,
        MacroCase,
    )
except ImportError:  # tests/ collected as a package
    from tests.macro_cases import (
        CASE_IDS,
        CASES,
        CLASSIC_PLUGIN,
        GZ_FRAME_TAG,
        MACROS_DIR,
        OPTICAL_RPY,
        ROS1_TAGS,
        SIM_VARIANTS,
        XACRO_NS,
        MacroCase,
    )

VARIANT_IDS = [f"{sim}-{gz}" if sim == "gz" else sim for sim, gz in SIM_VARIANTS]
CAMERA_CASES = [case for case in CASES if case.eyes]
NAME = "front_sensor"  # non-default instance name used by the single-instance tests
ORIGIN = '<origin xyz="0.12 -0.03 0.31" rpy="0 0.1 0.2"/>'
BASE_LINK = (
    '<link name="base_link"><inertial><mass value="2.0"/>'
    '<inertia ixx="0.02" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.02"/></inertial></link>'
)


# --------------------------------------------------------------------------- helpers


def robot_source(case_calls: Iterable[tuple[MacroCase, dict[str, str]]]) -> str:
    """A tiny robot including each macro file once and calling the macros as listed."""
    calls = list(case_calls)
    includes = []
    for case in dict.fromkeys(case for case, _ in calls):
        includes.append(f'  <xacro:include filename="{case.path}"/>')
    bodies = []
    for index, (case, params) in enumerate(calls):
        attrs = " ".join(f'{key}="{value}"' for key, value in params.items())
        origin = ORIGIN if index == 0 else f'<origin xyz="0 {0.2 * index:.1f} 0.3" rpy="0 0 0"/>'
        bodies.append(
            f'  <xacro:{case.macro} parent="base_link" {attrs}>\n    {origin}\n'
            f"  </xacro:{case.macro}>"
        )
    return "\n".join(
        [
            '<?xml version="1.0"?>',
            f'<robot name="macro_test" xmlns:xacro="{XACRO_NS}">',
            *includes,
            f"  {BASE_LINK}",
            *bodies,
            "</robot>",
            "",
        ]
    )


def expand_file(path: Path) -> str:
    """Expand a xacro file in-process, isolating xacro's module-level state."""
    xacro.all_includes.clear()
    try:
        return str(xacro.process_file(str(path)).toxml())
    finally:
        xacro.init_stacks(None)
        xacro.all_includes.clear()


def expand(tmp_dir: Path, case_calls: Iterable[tuple[MacroCase, dict[str, str]]]) -> str:
    tmp_dir.mkdir(parents=True, exist_ok=True)
    source = tmp_dir / "robot.urdf.xacro"
    source.write_text(robot_source(case_calls))
    return expand_file(source)


def params(
    name: str = NAME, sim: str = "classic", gz_version: str = "harmonic", **extra: str
) -> dict[str, str]:
    return {"name": name, "sim": sim, "gz_version": gz_version, **extra}


@pytest.fixture(scope="session")
def expanded(tmp_path_factory: pytest.TempPathFactory) -> Callable[..., str]:
    """Expand one instance of a macro; cached, as many tests read the same expansion."""
    cache: dict[tuple[str, tuple[tuple[str, str], ...]], str] = {}

    def get(case: MacroCase, **kwargs: str) -> str:
        args = params(**kwargs)
        key = (case.key, tuple(sorted(args.items())))
        if key not in cache:
            cache[key] = expand(tmp_path_factory.mktemp(case.key), [(case, args)])
        return cache[key]

    return get


def parse(urdf: str) -> etree._Element:
    parser = etree.XMLParser(resolve_entities=False, no_network=True, remove_comments=True)
    return etree.fromstring(urdf.encode(), parser)


def floats(text: str | None) -> list[float]:
    assert text is not None
    return [float(v) for v in text.split()]


def text_of(elem: etree._Element, path: str) -> str:
    found = elem.find(path)
    assert found is not None, f"missing <{path}> in <{elem.tag} name={elem.get('name')}>"
    assert found.text is not None
    return found.text.strip()


def check_urdf_binary() -> str:
    found = shutil.which("check_urdf")
    if found is None and Path("/usr/bin/check_urdf").exists():
        found = "/usr/bin/check_urdf"
    if found is None:
        pytest.fail(
            "check_urdf (urdfdom's parser) is not installed: run `apt-get install liburdfdom-tools`"
        )
    return found


def run_check_urdf(urdf: str, tmp_path: Path) -> None:
    path = tmp_path / "expanded.urdf"
    path.write_text(urdf)
    proc = subprocess.run(
        [check_urdf_binary(), str(path)], capture_output=True, text=True, timeout=30, check=False
    )
    assert proc.returncode == 0, f"check_urdf failed:\n{proc.stdout}\n{proc.stderr}"


def sensors_of(root: etree._Element) -> dict[str, etree._Element]:
    return {s.get("name"): s for s in root.iter("sensor")}


def resolve(name: str, namespace: str) -> str:
    """Resolve a relative ROS name against a node namespace."""
    if name.startswith("/"):
        return name
    return namespace.rstrip("/") + "/" + name


def classic_graph(root: etree._Element) -> tuple[list[str], list[str]]:
    """(topics, node names) the gazebo_ros plugins of a robot will create.

    Follows gazebo_ros_camera / gazebo_ros_ray_sensor / gazebo_ros_imu_sensor: node name
    = plugin name in <ros><namespace> (default /); camera topics are camera_name (default
    the sensor name) + /image_raw, /camera_info (+ depth ones for a depth sensor); the
    ray and imu plugins publish ~/out; <remapping> rules apply.
    """
    topics: list[str] = []
    nodes: list[str] = []
    for sensor in root.iter("sensor"):
        for plugin in sensor.iter("plugin"):
            ns = (plugin.findtext("ros/namespace") or "").strip() or "/"
            ns = "/" + ns.strip("/")
            node = resolve(plugin.get("name", ""), ns)
            nodes.append(node)
            remaps = {}
            for remap in plugin.iterfind("ros/remapping"):
                src, dst = (remap.text or "").strip().split(":=")
                remaps[src] = dst
            if plugin.get("filename") == CLASSIC_PLUGIN["camera"]:
                cam = (plugin.findtext("camera_name") or sensor.get("name", "")).strip()
                suffixes = ["image_raw", "camera_info"]
                if sensor.get("type") == "depth":
                    suffixes += ["depth/image_raw", "depth/camera_info", "points"]
                topics += [resolve(f"{cam}/{s}", ns) for s in suffixes]
            else:
                out = remaps.get("~/out")
                topics.append(resolve(out, ns) if out else node + "/out")
    return topics, nodes


def gz_topics(root: etree._Element) -> list[str]:
    """gz-transport topics the Gazebo Sim sensors of a robot will publish."""
    topics: list[str] = []
    for sensor in root.iter("sensor"):
        topic = text_of(sensor, "topic")
        assert "//" not in topic, topic
        kind = sensor.get("type")
        if kind == "rgbd_camera":
            topics += [f"{topic}/{s}" for s in ("image", "depth_image", "points", "camera_info")]
        elif kind == "camera":
            topics += [topic, text_of(sensor, "camera/camera_info_topic")]
        elif kind == "gpu_lidar":
            topics += [topic, f"{topic}/points"]
        else:
            topics.append(topic)
    return ["/" + t.lstrip("/") for t in topics]


def rotation(rpy: list[float]) -> list[list[float]]:
    r, p, y = rpy
    cr, sr = math.cos(r), math.sin(r)
    cp, sp = math.cos(p), math.sin(p)
    cy, sy = math.cos(y), math.sin(y)
    return [
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ]


# --------------------------------------------------------------------------- the files


EXPECTED_DEFAULTS: dict[str, dict[str, object]] = {
    "camera": {
        "update_rate": 30,
        "width": 640,
        "height": 480,
        "hfov": 1.3962634,
        "format": "R8G8B8",
        "near": 0.05,
        "far": 50.0,
        "noise_stddev": 0.007,
    },
    "depth_camera": {
        "update_rate": 30,
        "width": 640,
        "height": 480,
        "hfov": 1.3962634,
        "format": "R8G8B8",
        "near": 0.05,
        "far": 10.0,
        "noise_stddev": 0.007,
        "min_depth": 0.1,
        "max_depth": 10.0,
    },
    "stereo_camera": {
        "update_rate": 30,
        "width": 640,
        "height": 480,
        "hfov": 1.3962634,
        "format": "R8G8B8",
        "near": 0.05,
        "far": 50.0,
        "noise_stddev": 0.007,
        "baseline": 0.12,
    },
    "lidar_2d": {
        "update_rate": 10,
        "samples": 360,
        "resolution": 1,
        "min_angle": -math.pi,
        "max_angle": math.pi,
        "range_min": 0.12,
        "range_max": 12.0,
        "range_resolution": 0.01,
        "noise_stddev": 0.01,
    },
    "lidar_3d": {
        "update_rate": 10,
        "samples": 1800,
        "resolution": 1,
        "min_angle": -math.pi,
        "max_angle": math.pi,
        "range_min": 0.12,
        "range_max": 100.0,
        "range_resolution": 0.01,
        "noise_stddev": 0.01,
        "vertical_samples": 16,
        "vertical_min_angle": -0.2618,
        "vertical_max_angle": 0.2618,
    },
    "imu": {"update_rate": 100, "gyro_noise_stddev": 2e-4, "accel_noise_stddev": 1.7e-2},
}
COMMON_DEFAULTS = {"namespace": "", "sim": "classic", "gz_version": "harmonic"}


def default_value(text: str) -> object:
    text = text.strip()
    if len(text) >= 2 and text[0] == text[-1] == "'":
        return text[1:-1]
    if text.startswith("${") and text.endswith("}"):
        return eval(text[2:-1], {"__builtins__": {}}, {"pi": math.pi})
    for convert in (int, float):
        try:
            return convert(text)
        except ValueError:
            pass
    return text


@pytest.mark.parametrize("case", CASES, ids=CASE_IDS)
def test_file_is_a_self_contained_macro_wrapper(case: MacroCase) -> None:
    root = etree.parse(str(case.path)).getroot()
    assert root.tag == "robot"
    assert root.nsmap.get("xacro") == XACRO_NS
    children = [c for c in root if isinstance(c.tag, str)]
    assert [c.tag for c in children] == [f"{{{XACRO_NS}}}macro"], (
        "the file must hold the macro definition only (no include, no top-level property)"
    )
    macro = children[0]
    assert macro.get("name") == case.macro

    names: list[str] = []
    defaults: dict[str, object] = {}
    rest = macro.get("params", "")
    while rest.strip():
        param, value, rest = xacro.parse_macro_arg(rest)
        names.append(param)
        if value is not None:
            defaults[param] = default_value(value[1])
    assert names[:3] == ["name", "parent", "*origin"]
    expected = {**EXPECTED_DEFAULTS[case.key], **COMMON_DEFAULTS}
    for param, value in expected.items():
        assert param in defaults, f"{case.macro}: parameter {param} missing or without default"
        got = defaults[param]
        if isinstance(value, float):
            assert float(got) == pytest.approx(value, rel=1e-12), param  # type: ignore[arg-type]
        else:
            assert got == value, param
    assert float(defaults["mass"]) > 0  # type: ignore[arg-type]
    size = [float(v) for v in str(defaults["size"]).split()]
    assert len(size) == 3 and min(size) > 0


@pytest.mark.parametrize("case", CASES, ids=CASE_IDS)
def test_macros_have_no_ros1_tags(case: MacroCase) -> None:
    root = etree.parse(str(case.path)).getroot()
    used = {el.tag for el in root.iter() if isinstance(el.tag, str)}
    assert not used & ROS1_TAGS


# --------------------------------------------------------------------------- expansion


@pytest.mark.parametrize(("sim", "gz_version"), SIM_VARIANTS, ids=VARIANT_IDS)
@pytest.mark.parametrize("case", CASES, ids=CASE_IDS)
def test_expansion_passes_check_urdf(
    case: MacroCase, sim: str, gz_version: str, expanded: Callable[..., str], tmp_path: Path
) -> None:
    urdf = expanded(case, sim=sim, gz_version=gz_version)
    assert "${" not in urdf and "xacro:" not in urdf
    run_check_urdf(urdf, tmp_path)


@pytest.mark.parametrize(("sim", "gz_version"), SIM_VARIANTS, ids=VARIANT_IDS)
@pytest.mark.parametrize("case", CASES, ids=CASE_IDS)
def test_links_joints_and_optical_frames(
    case: MacroCase, sim: str, gz_version: str, expanded: Callable[..., str]
) -> None:
    root = parse(expanded(case, sim=sim, gz_version=gz_version))
    links = {link.get("name") for link in root.iter("link")}
    joints = {j.get("name"): j for j in root.iter("joint")}
    assert links == {"base_link", *case.links(NAME)}
    assert set(joints) == set(case.joints(NAME))

    mount = joints[f"{NAME}_joint"]
    assert mount.get("type") == "fixed"
    assert mount.find("parent").get("link") == "base_link"
    assert mount.find("child").get("link") == f"{NAME}_link"
    assert floats(mount.find("origin").get("xyz")) == pytest.approx([0.12, -0.03, 0.31])
    assert floats(mount.find("origin").get("rpy")) == pytest.approx([0.0, 0.1, 0.2])

    baseline = 0.12
    for eye in case.eyes:
        joint = joints[f"{NAME}{eye.optical_suffix.replace('_frame', '_joint')}"]
        assert joint.get("type") == "fixed"
        assert joint.find("parent").get("link") == f"{NAME}_link"
        assert joint.find("child").get("link") == f"{NAME}{eye.optical_suffix}"
        rpy = floats(joint.find("origin").get("rpy"))
        assert rpy == pytest.approx(list(OPTICAL_RPY), abs=1e-9)
        # optical z = body x, optical x = -body y, optical y = -body z
        R = rotation(rpy)
        expected_R = [[0, 0, 1], [-1, 0, 0], [0, -1, 0]]
        for row, expected_row in zip(R, expected_R, strict=True):
            assert row == pytest.approx(expected_row, abs=1e-9)
        xyz = floats(joint.find("origin").get("xyz"))
        assert xyz == pytest.approx([0.0, eye.y_sign * baseline / 2, 0.0], abs=1e-12)


@pytest.mark.parametrize(("sim", "gz_version"), SIM_VARIANTS, ids=VARIANT_IDS)
@pytest.mark.parametrize("case", CASES, ids=CASE_IDS)
def test_every_link_has_a_physical_inertia(
    case: MacroCase, sim: str, gz_version: str, expanded: Callable[..., str]
) -> None:
    root = parse(expanded(case, sim=sim, gz_version=gz_version))
    body_links = [link for link in root.iter("link") if link.get("name", "").endswith("_link")]
    assert len(body_links) >= 2
    for link in body_links:
        name = link.get("name")
        inertial = link.find("inertial")
        assert inertial is not None, f"{name} has no <inertial>: Gazebo would drop it"
        assert float(inertial.find("mass").get("value")) > 0
        inertia = inertial.find("inertia")
        ixx, iyy, izz = (float(inertia.get(k)) for k in ("ixx", "iyy", "izz"))
        assert min(ixx, iyy, izz) > 0, name
        assert ixx + iyy >= izz and iyy + izz >= ixx and ixx + izz >= iyy, name
        if name != "base_link":
            assert link.find("visual/geometry/box") is not None, name
            assert link.find("collision/geometry/box") is not None, name
    for link in root.iter("link"):
        if not link.get("name", "").endswith("_link"):
            assert link.get("name", "").endswith("_frame")
            assert link.find("inertial") is None  # massless frame on a fixed joint


def test_box_inertia_values(expanded: Callable[..., str]) -> None:
    case = CASES[CASE_IDS.index("lidar_2d")]
    root = parse(expanded(case, sim="none", mass="2.0", size="0.1 0.2 0.3"))
    inertia = root.find(f"link[@name='{NAME}_link']/inertial/inertia")
    m, x, y, z = 2.0, 0.1, 0.2, 0.3
    assert float(inertia.get("ixx")) == pytest.approx(m * (y * y + z * z) / 12)
    assert float(inertia.get("iyy")) == pytest.approx(m * (x * x + z * z) / 12)
    assert float(inertia.get("izz")) == pytest.approx(m * (x * x + y * y) / 12)
    assert floats(root.find(f"link[@name='{NAME}_link']/collision/geometry/box").get("size")) == [
        x,
        y,
        z,
    ]


@pytest.mark.parametrize(("sim", "gz_version"), SIM_VARIANTS, ids=VARIANT_IDS)
@pytest.mark.parametrize("case", CASES, ids=CASE_IDS)
def test_sensor_blocks_per_sim(
    case: MacroCase, sim: str, gz_version: str, expanded: Callable[..., str]
) -> None:
    root = parse(expanded(case, sim=sim, gz_version=gz_version))
    used = {el.tag for el in root.iter() if isinstance(el.tag, str)}
    assert not used & ROS1_TAGS
    assert "optical_frame_id" not in used
    gazebo = list(root.iter("gazebo"))
    if sim == "none":
        assert gazebo == []
        return
    assert {g.get("reference") for g in gazebo} == {f"{NAME}_link"}
    sensors = sensors_of(root)
    assert list(sensors) == case.sensors(NAME)
    expected_type = case.classic_type if sim == "classic" else case.gz_type
    for sensor in sensors.values():
        assert sensor.get("type") == expected_type
        assert text_of(sensor, "always_on") == "true"
        assert text_of(sensor, "visualize") in {"true", "false"}
        assert float(text_of(sensor, "update_rate")) == EXPECTED_DEFAULTS[case.key]["update_rate"]
        pose = floats(text_of(sensor, "pose"))
        assert len(pose) == 6 and pose[0] == pose[2] == 0 and pose[3:] == [0, 0, 0]
        if sim == "classic":
            assert len(sensor.findall("plugin")) == 1
            assert sensor.find("topic") is None
            assert not any(sensor.find(tag) is not None for tag in GZ_FRAME_TAG.values())
        else:
            assert sensor.find("plugin") is None
            assert sensor.find("topic") is not None


@pytest.mark.parametrize("case", CASES, ids=CASE_IDS)
def test_defaults_reach_the_sdf(case: MacroCase, expanded: Callable[..., str]) -> None:
    root = parse(expanded(case, sim="classic"))
    defaults = EXPECTED_DEFAULTS[case.key]
    for sensor in sensors_of(root).values():
        if case.eyes:
            cam = sensor.find("camera")
            assert float(text_of(cam, "horizontal_fov")) == defaults["hfov"]
            assert int(text_of(cam, "image/width")) == defaults["width"]
            assert int(text_of(cam, "image/height")) == defaults["height"]
            assert text_of(cam, "image/format") == defaults["format"]
            assert float(text_of(cam, "clip/near")) == defaults["near"]
            assert float(text_of(cam, "clip/far")) == defaults["far"]
            assert text_of(cam, "noise/type") == "gaussian"
            assert float(text_of(cam, "noise/stddev")) == defaults["noise_stddev"]
        elif case.kind.startswith("lidar"):
            ray = sensor.find("ray")
            assert int(text_of(ray, "scan/horizontal/samples")) == defaults["samples"]
            assert float(text_of(ray, "scan/horizontal/min_angle")) == pytest.approx(-math.pi)
            assert float(text_of(ray, "scan/horizontal/max_angle")) == pytest.approx(math.pi)
            assert float(text_of(ray, "range/min")) == defaults["range_min"]
            assert float(text_of(ray, "range/max")) == defaults["range_max"]
            assert float(text_of(ray, "range/resolution")) == defaults["range_resolution"]
            assert float(text_of(ray, "noise/stddev")) == defaults["noise_stddev"]
            if case.kind == "lidar_3d":
                assert int(text_of(ray, "scan/vertical/samples")) == 16
                assert float(text_of(ray, "scan/vertical/min_angle")) == -0.2618
                assert float(text_of(ray, "scan/vertical/max_angle")) == 0.2618
            else:
                assert ray.find("scan/vertical") is None
        else:
            for axis in "xyz":
                gyro = text_of(sensor, f"imu/angular_velocity/{axis}/noise/stddev")
                accel = text_of(sensor, f"imu/linear_acceleration/{axis}/noise/stddev")
                assert float(gyro) == 2e-4 and float(accel) == 1.7e-2


@pytest.mark.parametrize(
    ("sim", "gz_version"),
    [v for v in SIM_VARIANTS if v[0] != "none"],
    ids=[i for i in VARIANT_IDS if i != "none"],
)
@pytest.mark.parametrize("case", CASES, ids=CASE_IDS)
def test_zero_noise_emits_no_noise_block(
    case: MacroCase, sim: str, gz_version: str, expanded: Callable[..., str]
) -> None:
    zero = (
        {"gyro_noise_stddev": "0", "accel_noise_stddev": "0.0"}
        if case.kind == "imu"
        else {"noise_stddev": "0"}
    )
    root = parse(expanded(case, sim=sim, gz_version=gz_version, **zero))
    assert not list(root.iter("noise"))


# --------------------------------------------------------------------------- Gazebo Classic


@pytest.mark.parametrize("case", CASES, ids=CASE_IDS)
@pytest.mark.parametrize("namespace", ["", "/robot1/"], ids=["no-ns", "ns"])
def test_classic_plugins_are_ros2(
    case: MacroCase, namespace: str, expanded: Callable[..., str]
) -> None:
    root = parse(expanded(case, sim="classic", namespace=namespace))
    for sensor_name, sensor in sensors_of(root).items():
        (plugin,) = sensor.findall("plugin")
        assert plugin.get("filename") == CLASSIC_PLUGIN[case.plugin]
        assert plugin.get("name") == f"{sensor_name}_controller"
        assert text_of(plugin, "frame_name") == case.frame(NAME, sensor_name)
        for child in plugin.iter():
            assert child.tag not in ROS1_TAGS
        ns_elem = plugin.find("ros/namespace")
        if namespace:
            assert ns_elem is not None and ns_elem.text == "/robot1"
        else:
            assert ns_elem is None
        if case.plugin == "camera":
            eye = sensor_name[len(NAME) :].lstrip("_")
            expected_cam = f"{NAME}/{eye}" if eye else NAME
            assert text_of(plugin, "camera_name") == expected_cam
        if case.kind == "depth":
            assert float(text_of(plugin, "min_depth")) == 0.1
            assert float(text_of(plugin, "max_depth")) == 10.0
        if case.kind == "lidar_2d":
            assert text_of(plugin, "output_type") == "sensor_msgs/LaserScan"
        if case.kind == "lidar_3d":
            assert text_of(plugin, "output_type") == "sensor_msgs/PointCloud2"
        if case.kind == "stereo":
            hack = plugin.find("hack_baseline")
            if sensor_name.endswith("_right"):
                assert hack is not None and float(hack.text) == 0.12
            else:
                assert hack is None

    topics, nodes = classic_graph(root)
    assert set(topics) == case.expected_topics(NAME, "classic", namespace)
    ns = "/robot1" if namespace else ""
    assert set(nodes) == {f"{ns}/{s}_controller" for s in case.sensors(NAME)}


# --------------------------------------------------------------------------- Gazebo Sim


@pytest.mark.parametrize("gz_version", ["fortress", "harmonic", "jetty"])
@pytest.mark.parametrize("case", CASES, ids=CASE_IDS)
def test_gz_frame_tag_is_the_one_the_version_reads(
    case: MacroCase, gz_version: str, expanded: Callable[..., str]
) -> None:
    root = parse(expanded(case, sim="gz", gz_version=gz_version))
    wanted = GZ_FRAME_TAG[gz_version]
    ignored = set(GZ_FRAME_TAG.values()) - {wanted}
    for sensor_name, sensor in sensors_of(root).items():
        tags = sensor.findall(wanted)
        assert len(tags) == 1, f"{sensor_name}: expected exactly one <{wanted}>"
        assert tags[0].text == case.frame(NAME, sensor_name)
        assert tags[0].getparent() is sensor
    for elem in root.iter():
        assert elem.tag not in ignored, f"<{elem.tag}> is ignored by {gz_version}"
        assert elem.tag != "optical_frame_id"


@pytest.mark.parametrize("gz_version", ["fortress", "harmonic", "jetty"])
@pytest.mark.parametrize("case", CASES, ids=CASE_IDS)
@pytest.mark.parametrize("namespace", ["", "robot1", "/robot1/"], ids=["no-ns", "rel", "abs"])
def test_gz_topics(
    case: MacroCase, gz_version: str, namespace: str, expanded: Callable[..., str]
) -> None:
    root = parse(expanded(case, sim="gz", gz_version=gz_version, namespace=namespace))
    for sensor in root.iter("sensor"):
        topic = text_of(sensor, "topic")
        assert not topic.startswith("/") and not topic.endswith("/") and "//" not in topic
    expected = {"/" + t for t in case.expected_topics(NAME, "gz", namespace)}
    assert set(gz_topics(root)) == expected


@pytest.mark.parametrize("gz_version", ["fortress", "harmonic", "jetty"])
@pytest.mark.parametrize("case", CAMERA_CASES, ids=[c.key for c in CAMERA_CASES])
@pytest.mark.parametrize(
    "lens",
    [(640, 480, 1.3962634), (1280, 720, 2.0), (333, 111, 0.5)],
    ids=["default", "wide", "odd"],
)
def test_gz_intrinsics_are_pinned(
    case: MacroCase,
    gz_version: str,
    lens: tuple[int, int, float],
    expanded: Callable[..., str],
) -> None:
    width, height, hfov = lens
    extra = (
        {}
        if lens == (640, 480, 1.3962634)
        else {"width": str(width), "height": str(height), "hfov": str(hfov)}
    )
    root = parse(expanded(case, sim="gz", gz_version=gz_version, **extra))
    fx = width / (2 * math.tan(hfov / 2))
    for sensor in sensors_of(root).values():
        cam = sensor.find("camera")
        assert int(text_of(cam, "image/width")) == width
        assert float(text_of(cam, "horizontal_fov")) == hfov
        intr = cam.find("lens/intrinsics")
        assert intr is not None
        assert float(text_of(intr, "fx")) == pytest.approx(fx, rel=1e-12)
        assert float(text_of(intr, "fy")) == pytest.approx(fx, rel=1e-12)
        assert float(text_of(intr, "cx")) == pytest.approx(width / 2, rel=1e-12)
        assert float(text_of(intr, "cy")) == pytest.approx(height / 2, rel=1e-12)
        assert float(text_of(intr, "s")) == 0.0


def test_gz_rgbd_depth_clip_follows_min_max_depth(expanded: Callable[..., str]) -> None:
    case = CASES[CASE_IDS.index("depth_camera")]
    root = parse(expanded(case, sim="gz", min_depth="0.3", max_depth="6.5"))
    cam = sensors_of(root)[NAME].find("camera")
    assert float(text_of(cam, "depth_camera/clip/near")) == 0.3
    assert float(text_of(cam, "depth_camera/clip/far")) == 6.5


# --------------------------------------------------------------------------- stereo


@pytest.mark.parametrize(
    ("sim", "gz_version"),
    [v for v in SIM_VARIANTS if v[0] != "none"],
    ids=[i for i in VARIANT_IDS if i != "none"],
)
def test_stereo_eyes_render_at_their_optical_frames(
    sim: str, gz_version: str, expanded: Callable[..., str]
) -> None:
    case = CASES[CASE_IDS.index("stereo_camera")]
    baseline = 0.2
    root = parse(expanded(case, sim=sim, gz_version=gz_version, baseline=str(baseline)))
    joints = {j.get("name"): j for j in root.iter("joint")}
    sensors = sensors_of(root)
    for eye in case.eyes:
        sensor = sensors[f"{NAME}{eye.sensor_suffix}"]
        joint = joints[f"{NAME}{eye.optical_suffix.replace('_frame', '_joint')}"]
        pose = floats(text_of(sensor, "pose"))
        assert pose[:3] == pytest.approx(floats(joint.find("origin").get("xyz")), abs=1e-12)
        assert pose[1] == pytest.approx(eye.y_sign * baseline / 2)
        assert pose[3:] == [0, 0, 0]  # the sensor looks along the body x axis
    right = sensors[f"{NAME}_right"]
    left = sensors[f"{NAME}_left"]
    if sim == "gz":
        proj = right.find("camera/lens/projection")
        # Both eyes pin P = K; only the right eye carries a Tx.
        assert float(text_of(left.find("camera/lens/projection"), "tx")) == 0.0
        # Every gz version fills camera_info P from <lens><projection>, tx included
        # (gazebosim/gz-sensors@ign-sensors6:src/CameraSensor.cc:755-758 since 6.8.0 for
        # Fortress; @gz-sensors8:src/CameraSensor.cc:741-752): the right eye carries its Tx.
        fx = 640 / (2 * math.tan(1.3962634 / 2))
        assert float(text_of(proj, "tx")) == pytest.approx(-fx * baseline, rel=1e-12)
        assert float(text_of(proj, "p_fx")) == pytest.approx(fx, rel=1e-12)
        assert float(text_of(proj, "p_cx")) == 320.0
        assert float(text_of(proj, "p_cy")) == 240.0
    else:
        assert float(text_of(right, "plugin/hack_baseline")) == baseline


# --------------------------------------------------------------------------- two instances


@pytest.mark.parametrize("namespace", ["", "/robot1"], ids=["no-ns", "ns"])
@pytest.mark.parametrize(("sim", "gz_version"), SIM_VARIANTS, ids=VARIANT_IDS)
@pytest.mark.parametrize("case", CASES, ids=CASE_IDS)
def test_two_instances_share_no_topic_or_node(
    case: MacroCase, sim: str, gz_version: str, namespace: str, tmp_path: Path
) -> None:
    common = {"sim": sim, "gz_version": gz_version, "namespace": namespace}
    urdf = expand(tmp_path, [(case, {"name": "a", **common}), (case, {"name": "b", **common})])
    run_check_urdf(urdf, tmp_path)
    root = parse(urdf)
    names = [link.get("name") for link in root.iter("link")]
    assert len(names) == len(set(names))
    if sim == "none":
        assert not list(root.iter("gazebo"))
        return
    sensor_names = [s.get("name") for s in root.iter("sensor")]
    assert len(sensor_names) == len(set(sensor_names))
    if sim == "classic":
        topics, nodes = classic_graph(root)
        assert len(nodes) == len(set(nodes)), nodes
        plugin_names = [p.get("name") for p in root.iter("plugin")]
        assert len(plugin_names) == len(set(plugin_names))
        expected = case.expected_topics("a", sim, namespace) | case.expected_topics(
            "b", sim, namespace
        )
    else:
        topics = gz_topics(root)
        expected = {"/" + t for n in ("a", "b") for t in case.expected_topics(n, sim, namespace)}
    assert len(topics) == len(set(topics)), topics
    assert set(topics) == expected


# --------------------------------------------------------------------------- together


@pytest.mark.parametrize(("sim", "gz_version"), SIM_VARIANTS, ids=VARIANT_IDS)
def test_all_macros_in_one_robot(sim: str, gz_version: str, tmp_path: Path) -> None:
    calls = [
        (case, params(name=f"s_{case.key}", sim=sim, gz_version=gz_version, namespace="r2"))
        for case in CASES
    ]
    urdf = expand(tmp_path, calls)
    run_check_urdf(urdf, tmp_path)
    root = parse(urdf)
    expected_links = {"base_link"}
    for case in CASES:
        expected_links |= set(case.links(f"s_{case.key}"))
    assert {link.get("name") for link in root.iter("link")} == expected_links
    if sim == "classic":
        topics, nodes = classic_graph(root)
        for group in (topics, nodes):
            assert len(group) == len(set(group))
    elif sim == "gz":
        topics = gz_topics(root)
        assert len(topics) == len(set(topics))


@pytest.mark.parametrize("case", CASES, ids=CASE_IDS)
def test_robot_properties_do_not_leak_into_the_macros(case: MacroCase, tmp_path: Path) -> None:
    """A robot that defines properties with the macros' local or generic names gets the
    same expansion: the macros keep their values local."""
    args = params(sim="gz", gz_version="harmonic", namespace="r3")
    plain = expand(tmp_path / "plain", [(case, args)])
    source = robot_source([(case, args)])
    clutter = "".join(
        f'<xacro:property name="{name}" value="{value}"/>'
        for name, value in [
            ("sx", "9"),
            ("sy", "9"),
            ("sz", "9"),
            ("fx", "1"),
            ("half_b", "5"),
            ("ns_clean", "x"),
            ("gz_ns", "x/"),
            ("gz_frame_tag", "bogus"),
            ("imu_block", "0"),
            ("size", "1 1 1"),
            ("mass", "-1"),
            ("width", "7"),
            ("namespace", "nope"),
        ]
    )
    cluttered_dir = tmp_path / "cluttered"
    cluttered_dir.mkdir()
    cluttered = cluttered_dir / "robot.urdf.xacro"
    cluttered.write_text(source.replace(f"  {BASE_LINK}", clutter + BASE_LINK))

    def canonical(urdf: str) -> bytes:
        return etree.tostring(parse(urdf), method="c14n")

    assert canonical(expand_file(cluttered)) == canonical(plain)


# --------------------------------------------------------------------------- pybullet


@pytest.mark.parametrize(("sim", "gz_version"), SIM_VARIANTS, ids=VARIANT_IDS)
@pytest.mark.parametrize("case", CASES, ids=CASE_IDS)
def test_loads_in_pybullet(
    case: MacroCase, sim: str, gz_version: str, expanded: Callable[..., str], tmp_path: Path
) -> None:
    import pybullet

    urdf = expanded(case, sim=sim, gz_version=gz_version)
    run_check_urdf(urdf, tmp_path)  # pybullet may crash, not fail, on a malformed URDF
    path = tmp_path / "robot.urdf"
    path.write_text(urdf)
    client = pybullet.connect(pybullet.DIRECT)
    try:
        body = pybullet.loadURDF(str(path), useFixedBase=True, physicsClientId=client)
        assert body >= 0
        joint_names = {
            pybullet.getJointInfo(body, i, physicsClientId=client)[1].decode()
            for i in range(pybullet.getNumJoints(body, physicsClientId=client))
        }
        assert joint_names == set(case.joints(NAME))
    finally:
        pybullet.disconnect(client)


# --------------------------------------------------------------------------- bad input


@pytest.mark.parametrize("case", CASES, ids=CASE_IDS)
@pytest.mark.parametrize(
    ("param", "bad"),
    [("sim", "gazebo11_bogus"), ("gz_version", "garden_bogus")],
    ids=["sim", "gz_version"],
)
def test_unknown_value_fails_and_names_it(
    case: MacroCase, param: str, bad: str, tmp_path: Path
) -> None:
    with pytest.raises(xacro.XacroException) as info:
        expand(tmp_path, [(case, {"name": NAME, param: bad})])
    message = str(info.value)
    assert f"{param}={bad}" in message
    assert case.macro in message


@pytest.mark.parametrize("case", CASES, ids=CASE_IDS)
def test_non_positive_mass_fails(case: MacroCase, tmp_path: Path) -> None:
    with pytest.raises(xacro.XacroException, match="mass must be > 0"):
        expand(tmp_path, [(case, {"name": NAME, "mass": "0"})])


def test_unknown_sim_fails_on_the_command_line(tmp_path: Path) -> None:
    """What a user sees: xacro exits non-zero and stderr names the bad value."""
    case = CASES[0]
    source = tmp_path / "robot.urdf.xacro"
    source.write_text(robot_source([(case, {"name": NAME, "sim": "gazebo_bogus"})]))
    cli = Path(sys.executable).with_name("xacro")
    command = [str(cli)] if cli.exists() else [sys.executable, "-m", "xacro"]
    proc = subprocess.run(
        [*command, str(source)], capture_output=True, text=True, timeout=60, check=False
    )
    assert proc.returncode != 0
    assert "sim=gazebo_bogus" in proc.stderr


def test_macros_dir_holds_exactly_the_six_files() -> None:
    assert sorted(p.name for p in MACROS_DIR.glob("*.xacro")) == sorted(c.file for c in CASES)


@pytest.mark.parametrize("case", CAMERA_CASES, ids=[c.key for c in CAMERA_CASES])
def test_classic_cameras_each_serve_their_own_set_camera_info(
    case: MacroCase, expanded: Callable[..., str]
) -> None:
    # camera_info_manager creates "set_camera_info" relative to the node's namespace, so two
    # cameras in one namespace would both serve /set_camera_info: each remaps it under its name.
    root = parse(expanded(case, sim="classic"))
    plugins = [p for p in root.iter("plugin") if p.get("filename") == "libgazebo_ros_camera.so"]
    assert plugins
    for plugin in plugins:
        camera = text_of(plugin, "camera_name")
        remaps = [r.text for r in plugin.iter("remapping")]
        assert f"set_camera_info:={camera}/set_camera_info" in remaps


@pytest.mark.parametrize(("sim", "gz_version"), SIM_VARIANTS, ids=VARIANT_IDS)
@pytest.mark.parametrize("case", CASES, ids=CASE_IDS)
def test_macro_validates_clean_and_gazebo_keeps_every_sensor(
    case: MacroCase, sim: str, gz_version: str, tmp_path: Path
) -> None:
    from sensorkit.base.findings import Severity
    from sensorkit.lint.engine import Options, validate_file
    from sensorkit.model.sdf import convert

    source = tmp_path / "robot.urdf.xacro"
    calls = [
        (case, params(name="a", sim=sim, gz_version=gz_version)),
        (case, params(name="b", sim=sim, gz_version=gz_version)),
    ]
    source.write_text(robot_source(calls))
    target = gz_version if sim == "gz" else "classic"
    report = validate_file(source, Options(target=target))
    assert report.error is None and not report.internal_errors
    assert [(f.rule, f.message) for f in report.findings if f.severity >= Severity.WARNING] == []
    robot = report.robot
    assert robot is not None
    assert len(robot.sensors) == (0 if sim == "none" else 2 * max(1, len(case.eyes)))
    conv = convert(robot)
    assert not conv.dropped, conv.dropped  # every link keeps its mass through the conversion
    for sensor in robot.sensors:
        assert sensor.reference in robot.link_map and sensor.reference not in conv.dropped


@pytest.mark.parametrize("gz_version", ["fortress", "harmonic", "jetty"])
@pytest.mark.parametrize("case", [c for c in CASES if c.key in ("camera", "depth_camera", "stereo_camera")], ids=lambda c: c.key)
def test_every_gz_camera_pins_its_projection(expanded: Callable[..., str], case: MacroCase, gz_version: str) -> None:
    # gz-sensors fills camera_info P from <lens><projection> (gazebosim/gz-sensors@gz-sensors8:
    # src/CameraSensor.cc:741-752); without it P comes from the render camera, and ign-sensors 6
    # reads the projection only from 6.8.0 (@ign-sensors6:src/CameraSensor.cc:290-312, 755-758).
    # Pinned, P = K on every version (issue 9).
    root = etree.fromstring(expanded(case, sim="gz", gz_version=gz_version).encode())
    cams = [c for c in root.iter("camera") if c.find("lens/intrinsics") is not None]
    assert cams
    for cam in cams:
        proj, intr = cam.find("lens/projection"), cam.find("lens/intrinsics")
        assert proj is not None
        for p_tag, k_tag in (("p_fx", "fx"), ("p_fy", "fy"), ("p_cx", "cx"), ("p_cy", "cy")):
            assert float(proj.findtext(p_tag)) == float(intr.findtext(k_tag)), p_tag


# --------------------------------------------------------------------------- libsdformat
# Every macro x simulator variant goes through libsdformat, Gazebo's own URDF reader: it
# converts URDF to SDF the way Gazebo does at spawn (fixed-joint lumping, the <gazebo>
# extensions). tests/tools/urdf2sdf.cc is a 20-line reader built against Debian's
# libsdformat-dev (installed by tests/run) that prints its errors and the sensors it keeps.
# Issue 9: the pinned <lens><projection> must still convert cleanly on every version.

TOOL_SOURCE = Path(__file__).resolve().parent / "tools" / "urdf2sdf.cc"


@pytest.fixture(scope="session")
def urdf2sdf(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return sdformat_tool(tmp_path_factory, TOOL_SOURCE)


@pytest.mark.parametrize(("sim", "gz_version"), [v for v in SIM_VARIANTS if v[0] != "none"], ids=str)
@pytest.mark.parametrize("case", CASES, ids=[c.key for c in CASES])
def test_macro_converts_cleanly_and_keeps_its_sensors(
    urdf2sdf: Path, expanded: Callable[..., str], tmp_path: Path, case: MacroCase, sim: str, gz_version: str
) -> None:
    text = expanded(case, sim=sim, gz_version=gz_version)
    path = tmp_path / "robot.urdf"
    path.write_text(text)
    res = subprocess.run([str(urdf2sdf), str(path)], capture_output=True, text=True, timeout=60, check=False)
    errors = [line for line in res.stdout.splitlines() if line.startswith("ERROR")]
    assert res.returncode == 0 and not errors, errors or res.stderr
    kept = {line.split()[1] for line in res.stdout.splitlines() if line.startswith("SENSOR")}
    written = {s.get("name") for s in etree.fromstring(text.encode()).iter("sensor")}
    assert written and written == kept, (written, kept)
