"""``sensorkit validate --fix | --diff [--unsafe-fixes]``.

For each fixable rule a robot that triggers it: after fixing no finding of that rule is
left, every byte outside the fixed elements is the same (both files compared with the
fixed elements cut out), a second fix changes nothing, and xacro results still expand
with the real ``xacro`` and pass Debian's ``check_urdf``. Then the edges: included files
(inside the package: fixed; another package: refused), a fix that would add an error
(skipped), ``--diff`` (writes nothing), read-only files, ``--untrusted``, and the
real-world corpora (fixed on copies: no crash, idempotent, still expanding, no new error).
"""

from __future__ import annotations

import codecs
import re
import shutil
import stat
import subprocess
import sys
from collections import Counter
from collections.abc import Callable
from pathlib import Path

import pytest
from conftest import CORPUS, REALWORLD, needs_corpus
from typer.testing import CliRunner

from sensorkit.base.findings import Severity
from sensorkit.cli import app
from sensorkit.fix.apply import FileFix, fix_paths
from sensorkit.fix.registry import subject
from sensorkit.fix.source import SourceFile, Tag
from sensorkit.lint.engine import Options, validate_file

XACRO_BIN = Path(sys.executable).parent / "xacro"
OPTICAL = "-1.5707963267948966 0 -1.5707963267948966"
XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'

# --------------------------------------------------------------------------- helpers


def cli(*args: object) -> tuple[int, str, str]:
    result = CliRunner().invoke(app, [str(a) for a in args])
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        raise result.exception
    return result.exit_code, result.stdout, result.stderr


def fix(path: Path, *, unsafe: bool = False, target: str = "classic", **kw: object) -> FileFix:
    run = fix_paths([path], Options(target=target, **kw), unsafe=unsafe)  # type: ignore[arg-type]
    return run.files[0]


def rules(path: Path, target: str = "classic", **kw: object) -> Counter[str]:
    report = validate_file(path, Options(target=target, **kw))  # type: ignore[arg-type]
    assert report.error is None, report.error
    assert not report.internal_errors, report.internal_errors
    return Counter(f.rule for f in report.findings)


Pred = Callable[[Tag], bool]


def named(local: str, name: str) -> Pred:
    return lambda t: (
        t.local == local and t.attr("name") is not None and t.attr("name").value == name
    )  # type: ignore[union-attr]


def tag(local: str) -> Pred:
    return lambda t: t.local == local


def cut(data: bytes, *preds: Pred) -> str:
    """The file's text without the elements ``preds`` pick (whole lines where they stand
    alone), outermost first: what must be byte-identical before and after a fix."""
    sf = SourceFile("x", data)
    spans: list[tuple[int, int]] = []
    for t in sf.tags:
        if any(p(t) for p in preds) and not any(s <= t.start < e for s, e in spans):
            spans.append(sf.span(t))
    out, last = [], 0
    for s, e in sorted(spans):
        out.append(sf.text[last:s])
        last = e
    out.append(sf.text[last:])
    return "".join(out)


def assert_only(old: bytes, new: bytes, *preds: Pred) -> None:
    assert old != new, "nothing was fixed"
    assert cut(old, *preds) == cut(new, *preds), "bytes outside the fixed elements changed"


def assert_idempotent(path: Path, **kw: object) -> None:
    before = path.read_bytes()
    again = fix(path, **kw)  # type: ignore[arg-type]
    assert not again.applied, [(f.finding.rule, f.title) for f in again.applied]
    assert path.read_bytes() == before


def check_urdf(path: Path) -> None:
    exe = shutil.which("check_urdf") or "/usr/bin/check_urdf"
    if not Path(exe).exists():
        pytest.fail("check_urdf is missing (apt-get install liburdfdom-tools)")
    run = subprocess.run([exe, str(path)], capture_output=True, text=True, timeout=30, check=False)
    assert run.returncode == 0, run.stdout + run.stderr


def xacro_then_check_urdf(path: Path) -> str:
    """Expand with the real xacro command and hand the result to check_urdf."""
    run = subprocess.run(
        [str(XACRO_BIN), path.name],
        cwd=path.parent,
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )
    assert run.returncode == 0, run.stderr
    out = path.parent / (path.name + ".expanded.urdf")
    out.write_text(run.stdout)
    check_urdf(out)
    out.unlink()
    return run.stdout


def robot(
    *,
    params: str = "        <frame_name>camera_optical_frame</frame_name>",
    optical: str | None = OPTICAL,
    sensor_extra: str = "      <update_rate>30</update_rate>",
    extra: str = "",
    xacro: bool = False,
    sensor_type: str = "camera",
    plugin: str = "libgazebo_ros_camera.so",
) -> str:
    """A small rover: base_footprint -> base_link -> camera_link (-> camera_optical_frame)."""
    ns = f" {XACRO_NS}" if xacro else ""
    optical_block = (
        f"""  <link name="camera_optical_frame"/>
  <joint name="camera_optical_joint" type="fixed">
    <parent link="camera_link"/>
    <child link="camera_optical_frame"/>
    <origin xyz="0 0 0" rpy="{optical}"/>
  </joint>
"""
        if optical is not None
        else ""
    )
    return f"""<?xml version="1.0"?>
<!-- a rover for sensorkit's fix tests -->
<robot name="rover"{ns}>
  <link name="base_footprint"/>
  <joint name="base_joint" type="fixed">
    <parent link="base_footprint"/>
    <child link="base_link"/>
    <origin xyz="0 0 0.1" rpy="0 0 0"/>
  </joint>
  <link name="base_link">
    <inertial>
      <mass value="5"/>
      <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/>
    </inertial>
  </link>
  <link name="camera_link">
    <inertial>
      <mass value="0.1"/>
      <inertia ixx="0.0001" ixy="0" ixz="0" iyy="0.0001" iyz="0" izz="0.0001"/>
    </inertial>
  </link>
  <joint name="camera_joint" type="fixed">
    <parent link="base_link"/>
    <child link="camera_link"/>
    <origin xyz="0.25 0 0.1" rpy="0 0 0"/>
  </joint>
{optical_block}  <gazebo reference="camera_link">
    <sensor name="front_camera" type="{sensor_type}">
{sensor_extra}
      <camera>
        <horizontal_fov>1.3962634</horizontal_fov>
        <image><width>640</width><height>480</height><format>R8G8B8</format></image>
        <clip><near>0.05</near><far>50</far></clip>
      </camera>
      <plugin name="front_camera_controller" filename="{plugin}">
{params}
      </plugin>
    </sensor>
  </gazebo>
{extra}</robot>
"""


LIDAR = """  <link name="laser_link">
    <inertial>
      <mass value="0.1"/>
      <inertia ixx="0.0001" ixy="0" ixz="0" iyy="0.0001" iyz="0" izz="0.0001"/>
    </inertial>
  </link>
  <joint name="laser_joint" type="fixed">
    <parent link="base_link"/>
    <child link="laser_link"/>
    <origin xyz="0 0 0.2" rpy="0 0 0"/>
  </joint>
  <gazebo reference="laser_link">
    <sensor name="laser" type="ray">
      <update_rate>10</update_rate>
      <ray>
        <scan><horizontal><samples>360</samples><resolution>1</resolution><min_angle>-3.14159</min_angle><max_angle>3.14159</max_angle></horizontal></scan>
        <range><min>0.12</min><max>12</max><resolution>0.01</resolution></range>
      </ray>
      <plugin name="laser_controller" filename="{plugin}">
{params}
      </plugin>
    </sensor>
  </gazebo>
"""


def lidar(plugin: str = "libgazebo_ros_ray_sensor.so", params: str = "") -> str:
    return LIDAR.format(plugin=plugin, params=params)


@pytest.fixture
def here(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    monkeypatch.chdir(tmp_path)
    return tmp_path


def write(folder: Path, name: str, text: str) -> Path:
    path = folder / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path


# --------------------------------------------------------------------------- SK505


def test_sk505_urdf_gets_full_precision(here: Path) -> None:
    path = write(here, "rover.urdf", robot(optical="-1.57 0 -1.57"))
    old = path.read_bytes()
    assert rules(path)["SK505"] == 1
    ff = fix(path)
    assert [f.finding.rule for f in ff.applied] == ["SK505"]
    new = path.read_bytes()
    assert f'<origin xyz="0 0 0" rpy="{OPTICAL}"/>'.encode() in new
    assert_only(old, new, named("joint", "camera_optical_joint"))
    assert rules(path)["SK505"] == 0
    check_urdf(path)
    assert_idempotent(path)


def test_sk505_xacro_writes_pi_and_still_expands(here: Path) -> None:
    path = write(here, "rover.urdf.xacro", robot(optical="-1.5707 0.0 -1.5707", xacro=True))
    old = path.read_bytes()
    fix(path)
    new = path.read_bytes()
    assert b'rpy="${-pi/2} 0.0 ${-pi/2}"' in new  # only the approximate numbers change
    assert_only(old, new, named("joint", "camera_optical_joint"))
    assert rules(path)["SK505"] == 0
    xacro_then_check_urdf(path)
    assert_idempotent(path)


def test_sk505_macro_parameter_is_not_fixed(here: Path) -> None:
    text = robot(optical=None, xacro=True).replace(
        "</robot>",
        """  <xacro:macro name="optical" params="rpy">
    <link name="camera_optical_frame"/>
    <joint name="camera_optical_joint" type="fixed">
      <parent link="camera_link"/>
      <child link="camera_optical_frame"/>
      <origin xyz="0 0 0" rpy="${rpy}"/>
    </joint>
  </xacro:macro>
  <xacro:optical rpy="-1.57 0 -1.57"/>
</robot>""",
    )
    path = write(here, "rover.urdf.xacro", text)
    old = path.read_bytes()
    code, _, err = cli("validate", "--fix", "--target", "classic", path)
    assert path.read_bytes() == old
    assert "not fixed" in err and "SK505" in err and "computed by xacro" in err
    assert "fixed 0 findings (1 remain)" in err
    assert code == 0  # an info only


def test_lexical_scan_skips_comments_cdata_and_quoted_markup(here: Path) -> None:
    """A look-alike in a comment, in CDATA or in an attribute value is never edited; an
    element on a line with others is found by its place among them."""
    text = (
        robot(optical="-1.57 0 -1.57")
        .replace(
            '    <origin xyz="0 0 0" rpy="-1.57 0 -1.57"/>',
            '    <!-- <origin rpy="-1.57 0 -1.57"/> --><origin xyz="0 0 0" rpy="-1.57 0 -1.57"/>'
            '<![CDATA[ <origin rpy="-1.57 0 -1.57"/> ]]>',
        )
        .replace(
            '<link name="camera_optical_frame"/>', '<link name="camera_optical_frame" type="a>b"/>'
        )
    )
    path = write(here, "rover.urdf", text)
    fix(path)
    new = path.read_text()
    assert new.count('rpy="-1.57 0 -1.57"') == 2  # the comment and the CDATA
    assert f'--><origin xyz="0 0 0" rpy="{OPTICAL}"/><![CDATA[' in new
    flat = re.sub(r">\s+<", "><", robot(optical="-1.57 0 -1.57"))
    one_line = write(here, "flat.urdf", flat)
    assert flat.count("\n") == 1
    fix(one_line)
    assert rules(one_line)["SK505"] == 0
    assert one_line.read_text() == flat.replace('rpy="-1.57 0 -1.57"', f'rpy="{OPTICAL}"')


def test_bom_non_ascii_and_latin1_keep_their_bytes(here: Path) -> None:
    text = robot(optical="-1.57 0 -1.57").replace("<!-- a rover", "<!-- caméra ü ∑ a rover")
    path = here / "utf8.urdf"
    path.write_bytes(codecs.BOM_UTF8 + text.encode())
    old = path.read_bytes()
    fix(path)
    assert_only(old, path.read_bytes(), named("joint", "camera_optical_joint"))
    assert path.read_bytes().startswith(codecs.BOM_UTF8)
    latin = text.replace(" ∑", "").replace(
        '<?xml version="1.0"?>', '<?xml version="1.0" encoding="ISO-8859-1"?>'
    )
    path = here / "latin1.urdf"
    path.write_bytes(latin.encode("latin-1"))
    old = path.read_bytes()
    fix(path)
    assert_only(old, path.read_bytes(), named("joint", "camera_optical_joint"))
    assert "caméra ü".encode("latin-1") in path.read_bytes() and rules(path)["SK505"] == 0


def test_a_write_meanwhile_is_not_lost(here: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Another writer changes the file between planning and writing: the plan is made again
    under the folder lock, from what that writer left."""
    from sensorkit.fix import apply

    path = write(here, "rover.urdf", robot(optical="-1.57 0 -1.57"))
    plan = apply.plan_file
    calls: list[int] = []

    def meddling(*args: object, **kw: object) -> FileFix:
        out = plan(*args, **kw)  # type: ignore[arg-type]
        if not calls:
            path.write_text(path.read_text().replace("a rover for", "another writer's rover for"))
        calls.append(1)
        return out

    monkeypatch.setattr(apply, "plan_file", meddling)
    fix(path)
    assert len(calls) == 2
    text = path.read_text()
    assert "another writer's rover" in text and f'rpy="{OPTICAL}"' in text


# --------------------------------------------------------------------------- SK602


ROS1_CAMERA = """        <frameName>camera_optical_frame</frameName>
        <robotNamespace>/rover</robotNamespace>
        <cameraName>front</cameraName>
        <imageTopicName>color/image_raw</imageTopicName>
        <cameraInfoTopicName>/front/color/camera_info</cameraInfoTopicName>
        <updateRate>30</updateRate>
        <hackBaseline>0</hackBaseline>
        <Cx>0</Cx>"""


def test_sk602_ros1_tags_take_their_ros2_form(here: Path) -> None:
    path = write(here, "rover.urdf", robot(params=ROS1_CAMERA))
    old = path.read_bytes()
    before = rules(path)
    assert before["SK602"] == 8
    ff = fix(path)
    new = path.read_text()
    assert rules(path)["SK602"] == 0
    assert not {"SK303", "SK502", "SK503"} & set(rules(path))  # the frame is read now
    assert_only(old, new.encode(), tag("plugin"))
    plugin = new[new.index("      <plugin") : new.index("</plugin>") + 9]
    assert plugin == (
        '      <plugin name="front_camera_controller" filename="libgazebo_ros_camera.so">\n'
        "        <frame_name>camera_optical_frame</frame_name>\n"
        "        <ros>\n"
        "          <namespace>/rover</namespace>\n"
        "          <remapping>front/image_raw:=front/color/image_raw</remapping>\n"
        "          <remapping>front/camera_info:=/front/color/camera_info</remapping>\n"
        "        </ros>\n"
        "        <camera_name>front</camera_name>\n"
        "        <hack_baseline>0</hack_baseline>\n"
        "      </plugin>"
    )
    # The topics are where ROS 1 put them: /NS/CAMERA/TOPIC, an absolute name as it is.
    from sensorkit.lint.rules.topic_names import resolved_topics
    from sensorkit.model import load_robot

    loaded = load_robot(path)
    assert loaded.robot is not None
    (sensor,) = loaded.robot.sensors
    topics = dict(resolved_topics(sensor.plugins[0], sensor))
    assert topics["front/image_raw"] == "/rover/front/color/image_raw"
    assert topics["front/camera_info"] == "/front/color/camera_info"
    assert len(ff.applied) == 8
    check_urdf(path)
    assert_idempotent(path)


def test_sk602_update_rate_differs_only_with_unsafe_fixes(here: Path) -> None:
    path = write(here, "rover.urdf", robot(params=ROS1_CAMERA.replace(">30<", ">15<")))
    ff = fix(path)
    assert rules(path)["SK602"] == 1
    (note,) = [n for n in ff.notes if n.finding.rule == "SK602"]
    assert note.kind == "unsafe" and "30 -> 15" in note.text
    old = path.read_bytes()
    fix(path, unsafe=True)
    assert rules(path)["SK602"] == 0
    new = path.read_bytes()
    assert b"<update_rate>15</update_rate>" in new and b"updateRate" not in new
    assert_only(old, new, tag("sensor"))
    assert_idempotent(path, unsafe=True)


def test_sk602_follows_tabs_and_crlf(here: Path) -> None:
    text = robot(params=ROS1_CAMERA).replace("  ", "\t").replace("\n", "\r\n")
    path = here / "rover.urdf"
    path.write_bytes(text.encode())
    fix(path)
    new = path.read_bytes()
    assert b"\t\t\t\t<ros>\r\n\t\t\t\t\t<namespace>/rover</namespace>\r\n" in new
    assert b"\t\t\t\t</ros>\r\n" in new
    assert new.count(b"\n") == new.count(b"\r\n")
    assert rules(path)["SK602"] == 0


def test_sk602_remap_becomes_remapping(here: Path) -> None:
    params = '        <ros>\n          <remap from="image_raw" to="image"/>\n        </ros>\n        <frame_name>camera_optical_frame</frame_name>'
    path = write(here, "rover.urdf", robot(params=params))
    fix(path)
    assert "<remapping>image_raw:=image</remapping>" in path.read_text()
    assert rules(path)["SK602"] == 0


# --------------------------------------------------------------------------- SK601


def test_sk601_ros1_laser_becomes_the_ray_sensor(here: Path) -> None:
    params = "        <topicName>scan</topicName>\n        <frameName>laser_link</frameName>"
    path = write(here, "rover.urdf", robot(extra=lidar("libgazebo_ros_laser.so", params)))
    old = path.read_bytes()
    assert rules(path)["SK601"] == 1
    ff = fix(path)
    assert {f.finding.rule for f in ff.applied} == {"SK601", "SK602"}
    found = rules(path)
    assert found["SK601"] == found["SK602"] == found["SK606"] == 0
    new = path.read_text()
    assert 'filename="libgazebo_ros_ray_sensor.so"' in new
    assert "<output_type>sensor_msgs/LaserScan</output_type>" in new
    assert (
        "<remapping>~/out:=scan</remapping>" in new and "<frame_name>laser_link</frame_name>" in new
    )
    assert_only(old, new.encode(), named("plugin", "laser_controller"))
    check_urdf(path)
    assert_idempotent(path)


def test_sk601_openni_kinect_becomes_the_camera_plugin(here: Path) -> None:
    params = "        <cameraName>front</cameraName>\n        <frameName>camera_optical_frame</frameName>"
    path = write(
        here,
        "rover.urdf",
        robot(params=params, sensor_type="depth", plugin="libgazebo_ros_openni_kinect.so"),
    )
    fix(path)
    found = rules(path)
    assert found["SK601"] == found["SK602"] == 0
    assert 'filename="libgazebo_ros_camera.so"' in path.read_text()


# --------------------------------------------------------------------------- SK502 / SK503 / SK303


def test_sk502_points_at_the_optical_frame_there(here: Path) -> None:
    path = write(here, "rover.urdf", robot(params="        <frame_name>camera_link</frame_name>"))
    old = path.read_bytes()
    assert rules(path)["SK502"] == 1
    fix(path)
    assert rules(path)["SK502"] == 0
    new = path.read_bytes()
    assert b"<frame_name>camera_optical_frame</frame_name>" in new
    assert_only(old, new, tag("plugin"))
    assert_idempotent(path)


@pytest.mark.parametrize("xacro", [False, True])
def test_sk502_adds_an_optical_frame_only_when_unsafe(here: Path, xacro: bool) -> None:
    name = "rover.urdf.xacro" if xacro else "rover.urdf"
    path = write(
        here,
        name,
        robot(params="        <frame_name>camera_link</frame_name>", optical=None, xacro=xacro),
    )
    old = path.read_bytes()
    ff = fix(path)
    assert path.read_bytes() == old
    assert any(n.kind == "unsafe" and n.finding.rule == "SK502" for n in ff.notes)
    fix(path, unsafe=True)
    assert rules(path)["SK502"] == 0
    new = path.read_text()
    rpy = "${-pi/2} 0 ${-pi/2}" if xacro else OPTICAL
    assert (
        '  </link>\n  <joint name="camera_link_optical_joint" type="fixed">\n'
        '    <parent link="camera_link"/>\n    <child link="camera_link_optical_frame"/>\n'
        f'    <origin xyz="0 0 0" rpy="{rpy}"/>\n  </joint>\n'
        '  <link name="camera_link_optical_frame"/>\n  <joint name="camera_joint"'
    ) in new
    assert "<frame_name>camera_link_optical_frame</frame_name>" in new
    new_parts = (
        named("joint", "camera_link_optical_joint"),
        named("link", "camera_link_optical_frame"),
    )
    assert_only(old, new.encode(), tag("plugin"), *new_parts)
    if xacro:
        xacro_then_check_urdf(path)
    else:
        check_urdf(path)
    assert_idempotent(path, unsafe=True)


def test_sk503_lidar_published_in_its_own_link(here: Path) -> None:
    params = "        <output_type>sensor_msgs/LaserScan</output_type>\n        <frame_name>base_link</frame_name>"
    path = write(here, "rover.urdf", robot(extra=lidar(params=params)))
    assert rules(path)["SK503"] == 1
    fix(path)
    assert rules(path)["SK503"] == 0
    assert "<frame_name>laser_link</frame_name>" in path.read_text()


def test_sk303_names_the_frame_the_sensor_sits_on(here: Path) -> None:
    imu = """  <link name="imu_link">
    <inertial>
      <mass value="0.01"/>
      <inertia ixx="1e-6" ixy="0" ixz="0" iyy="1e-6" iyz="0" izz="1e-6"/>
    </inertial>
  </link>
  <joint name="imu_joint" type="fixed">
    <parent link="base_link"/>
    <child link="imu_link"/>
  </joint>
  <gazebo reference="imu_link">
    <sensor name="imu" type="imu">
      <update_rate>100</update_rate>
      <plugin name="imu_plugin" filename="libgazebo_ros_imu_sensor.so">
        <initial_orientation_as_reference>false</initial_orientation_as_reference>
      </plugin>
    </sensor>
  </gazebo>
"""
    path = write(here, "rover.urdf", robot(params="", extra=imu))
    old = path.read_bytes()
    assert rules(path)["SK303"] == 2  # the camera and the IMU
    fix(path)
    assert rules(path)["SK303"] == 0
    new = path.read_text()
    assert "        <frame_name>imu_link</frame_name>\n      </plugin>" in new
    assert "        <frame_name>camera_optical_frame</frame_name>\n      </plugin>" in new
    assert_only(old, new.encode(), tag("plugin"))
    assert_idempotent(path)


# --------------------------------------------------------------------------- SK301


def test_sk301_placeholder_inertial_only_when_unsafe(here: Path) -> None:
    wheel = """  <link name="wheel"/>
  <joint name="wheel_joint" type="continuous">
    <parent link="base_link"/>
    <child link="wheel"/>
    <axis xyz="0 1 0"/>
  </joint>
"""
    path = write(here, "rover.urdf", robot(extra=wheel))
    old = path.read_bytes()
    assert rules(path)["SK301"] == 1
    fix(path)
    assert path.read_bytes() == old
    fix(path, unsafe=True)
    assert rules(path)["SK301"] == 0
    new = path.read_text()
    assert '  <link name="wheel">\n    <inertial>\n      <!-- sensorkit fix: a placeholder' in new
    assert '      <mass value="0.01"/>\n' in new and "    </inertial>\n  </link>\n" in new
    assert_only(old, new.encode(), named("link", "wheel"))
    check_urdf(path)
    assert_idempotent(path, unsafe=True)


# --------------------------------------------------------------------------- files and packages


def _package(folder: Path, name: str) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "package.xml").write_text(f"<package><name>{name}</name></package>\n")
    return folder


CAMERA_XACRO = f"""<?xml version="1.0"?>
<robot {XACRO_NS}>
  <xacro:macro name="front_camera">
    <link name="camera_optical_frame"/>
    <joint name="camera_optical_joint" type="fixed">
      <parent link="camera_link"/>
      <child link="camera_optical_frame"/>
      <origin xyz="0 0 0" rpy="-1.57 0 -1.57"/>
    </joint>
  </xacro:macro>
</robot>
"""


def _top(include: str) -> str:
    return robot(optical=None, xacro=True).replace(
        "</robot>", f'  <xacro:include filename="{include}"/>\n  <xacro:front_camera/>\n</robot>'
    )


@pytest.mark.parametrize(
    "include",
    ["sensors/camera.urdf.xacro", "$(find rover_description)/urdf/sensors/camera.urdf.xacro"],
)
def test_included_file_of_the_same_package_is_fixed(here: Path, include: str) -> None:
    pkg = _package(here / "ws" / "src" / "rover_description", "rover_description")
    cam = write(pkg, "urdf/sensors/camera.urdf.xacro", CAMERA_XACRO)
    top = write(pkg, "urdf/rover.urdf.xacro", _top(include))
    top_old, cam_old = top.read_bytes(), cam.read_bytes()
    ff = fix(top)
    assert [f.finding.rule for f in ff.applied] == ["SK505"]
    assert top.read_bytes() == top_old
    assert_only(cam_old, cam.read_bytes(), named("joint", "camera_optical_joint"))
    assert b'rpy="${-pi/2} 0 ${-pi/2}"' in cam.read_bytes()
    assert rules(top)["SK505"] == 0
    if "$(find" not in include:  # the xacro command resolves $(find) only in a ROS install
        xacro_then_check_urdf(top)
    assert_idempotent(top)


def test_included_file_of_another_package_is_left(here: Path) -> None:
    pkg = _package(here / "ws" / "src" / "rover_description", "rover_description")
    vendor = _package(here / "ws" / "src" / "vendor_camera", "vendor_camera")
    cam = write(vendor, "urdf/camera.urdf.xacro", CAMERA_XACRO)
    top = write(pkg, "urdf/rover.urdf.xacro", _top("$(find vendor_camera)/urdf/camera.urdf.xacro"))
    old = cam.read_bytes(), top.read_bytes()
    code, _, err = cli("validate", "--fix", "--target", "classic", top)
    assert (cam.read_bytes(), top.read_bytes()) == old
    assert "belongs to package 'vendor_camera', not to 'rover_description'" in err
    assert "fixed 0 findings (1 remain)" in err
    assert code == 0


def test_relative_include_next_to_a_file_in_no_package(here: Path) -> None:
    cam = write(here, "sensors/camera.urdf.xacro", CAMERA_XACRO)
    top = write(here, "rover.urdf.xacro", _top("sensors/camera.urdf.xacro"))
    fix(top)
    assert b"${-pi/2}" in cam.read_bytes()
    xacro_then_check_urdf(top)


# --------------------------------------------------------------------------- refusals


def test_a_fix_that_would_add_an_error_is_skipped(here: Path) -> None:
    """<frameName> names a link that does not exist: renaming it to <frame_name> would make
    the plugin publish in a frame TF never has (SK501): left, and said."""
    params = (
        "        <frameName>camera_optcal_frame</frameName>\n        <cameraName>front</cameraName>"
    )
    path = write(here, "rover.urdf", robot(params=params))
    old = path.read_bytes()
    code, _, err = cli("validate", "--fix", "--target", "classic", path)
    new = path.read_bytes()
    assert b"<frameName>camera_optcal_frame</frameName>" in new  # skipped
    assert b"<camera_name>front</camera_name>" in new  # the other fix landed
    assert_only(old, new, tag("plugin"))
    assert "would add an error: SK501" in err
    assert rules(path)["SK501"] == 0
    assert code == 1


def test_read_only_file_is_refused_in_one_line(here: Path) -> None:
    path = write(here, "rover.urdf", robot(optical="-1.57 0 -1.57"))
    path.chmod(0o444)
    try:
        code, _, err = cli("validate", "--fix", path)
        assert code == 2
        assert err.strip().count("\n") == 0 and "read-only" in err, err
        assert path.read_text() == robot(optical="-1.57 0 -1.57")
    finally:
        path.chmod(stat.S_IRUSR | stat.S_IWUSR)


def test_unsafe_fixes_alone_is_a_usage_error(here: Path) -> None:
    path = write(here, "rover.urdf", robot())
    code, _, err = cli("validate", "--unsafe-fixes", path)
    assert code == 2 and "--unsafe-fixes only means something with --fix or --diff" in err


# --------------------------------------------------------------------------- the command


def test_diff_writes_nothing_and_patch_applies_it(here: Path) -> None:
    text = robot(params=ROS1_CAMERA, optical="-1.57 0 -1.57")
    path = write(here, "rover.urdf", text)
    code, out, err = cli("validate", "--diff", "--target", "classic", path)
    assert path.read_text() == text
    assert out.startswith("--- a/rover.urdf\n+++ b/rover.urdf\n@@ ")
    assert "would fix 12 findings (0 would remain)" in err
    assert code == 1  # it would change a file (issue 27: --diff exits as ruff check --diff)
    (here / "patched").mkdir()
    patched = write(here / "patched", "rover.urdf", text)
    run = subprocess.run(
        ["patch", "-p1", "-s"],
        input=out,
        text=True,
        cwd=here / "patched",
        check=False,
        capture_output=True,
    )
    assert run.returncode == 0, run.stderr
    code, out2, err2 = cli("validate", "--fix", "--target", "classic", path)
    assert patched.read_bytes() == path.read_bytes()
    assert "fixed 12 findings (0 remain)" in err2
    assert "ok: no findings" in out2 and code == 0  # validate's report of what remains


def test_diff_of_two_files_sharing_an_include(here: Path) -> None:
    """The second file sees the first one's fixes: the shared include is patched once."""
    cam = write(here, "sensors/camera.urdf.xacro", CAMERA_XACRO)
    a = write(here, "a.urdf.xacro", _top("sensors/camera.urdf.xacro"))
    b = write(
        here, "b.urdf.xacro", _top("sensors/camera.urdf.xacro").replace('"rover"', '"rover_b"')
    )
    code, out, err = cli("validate", "--diff", "--target", "classic", a, b)
    assert code == 1  # it would change a file
    assert out.count("+++ b/sensors/camera.urdf.xacro") == 1 and "+++ b/a.urdf" not in out
    assert cam.read_text() == CAMERA_XACRO
    assert "would fix 1 finding (0 would remain)" in err


def test_exit_status_is_validate_s_after_fixing(here: Path) -> None:
    path = write(here, "rover.urdf", robot(params=ROS1_CAMERA.replace(">30<", ">15<")))
    code, out, err = cli("validate", "--fix", "--target", "classic", "--fail-on", "warning", path)
    # the updateRate (15 Hz on a 30 Hz sensor) that needs --unsafe-fixes remains: a warning,
    # since ROS 2 publishes at 30 Hz, which works (issue 23: SK602's severity by consequence)
    assert code == 1
    assert "warning" in out and "SK602" in out and "needs --unsafe-fixes" in err
    code, out, err = cli(
        "validate", "--fix", "--unsafe-fixes", "--target", "classic", "--format", "json",
        "--fail-on", "warning", path,
    )
    assert code == 0 and '"findings"' in out
    assert "fixed 1 finding (0 remain)" in err


def test_untrusted_fix(here: Path) -> None:
    path = write(here, "rover.urdf.xacro", robot(optical="-1.57 0 -1.57", xacro=True))
    code, _, err = cli("validate", "--fix", "--untrusted", "--target", "classic", path)
    assert code == 0, err
    assert b"${-pi/2}" in path.read_bytes()


def test_rules_say_what_is_fixable() -> None:
    code, out, _ = cli("rules")
    assert code == 0
    lines = {line.split()[0]: line.split()[2] for line in out.splitlines() if line.startswith("SK")}
    assert (
        lines["SK505"] == "safe" and lines["SK301"] == "unsafe" and lines["SK502"] == "safe/unsafe"
    )
    assert lines["SK101"] == "-"
    from sensorkit.fix import fixable
    from sensorkit.lint.report import rule_table

    assert "| SK505 | info |" in rule_table(fixable) and rule_table(fixable).splitlines()[0].endswith(
        "| `--fix` |"
    )


# --------------------------------------------------------------------------- the corpora


@needs_corpus
def test_real_world_corpora_fixed_on_copies(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Every corpus robot, fixed on a copy as robots.yaml validates it: no crash, nothing new
    at error level (but what a swapped ROS 1 plugin shows of its own parameters), each still
    expands, and a second --fix changes nothing."""
    sys.path.insert(0, str(Path(__file__).parent))
    import labelled

    # The corpora side by side as the labelled run reads them, the real-world set taken out
    # of the corpus folder it sits in, and the project's wrappers beside them.
    shutil.copytree(CORPUS, tmp_path / "corpus", symlinks=True, ignore=lambda d, names: ["realworld"] if Path(d) == CORPUS else [])
    shutil.copytree(REALWORLD, tmp_path / "realworld", symlinks=True)
    shutil.copytree(labelled.TESTS / "corpus_wrappers", tmp_path / "corpus_wrappers", symlinks=True)
    for p in tmp_path.rglob("*"):  # ../shared is read-only: the copies are ours to fix
        p.chmod(p.stat().st_mode | stat.S_IWUSR)
    repos = sorted(p for p in (tmp_path / "corpus").iterdir() if p.is_dir())
    corpora = (*map(str, repos), str(tmp_path / "realworld"))
    fixed = applied = robots = 0
    problems: list[str] = []
    for r in labelled.robots():
        path = (tmp_path / r.corpus.name / r.file).resolve()
        bridges = tuple(str(tmp_path / r.corpus.name / b) for b in r.bridge)
        options = Options(
            target=r.target,
            args=dict(r.args),
            package_paths=corpora,
            ignore=labelled.IGNORED,
            bridges=bridges,
        )
        run = fix_paths([path], options)
        ff = run.files[0]
        robots += 1
        fixed += run.fixed
        applied += len(ff.applied)
        if not run.changed():
            continue
        after = validate_file(path, options)
        if after.error or after.robot is None or after.internal_errors:
            problems.append(f"{r.id}: no longer expands: {after.error or after.internal_errors}")
            continue
        swapped = {x.finding.sensor for x in ff.applied if x.finding.rule == "SK601"}
        budget = Counter(subject(f) for f in ff.before if f.severity >= Severity.ERROR)
        for f in after.findings:
            if f.severity < Severity.ERROR:
                continue
            if budget[subject(f)] > 0:
                budget[subject(f)] -= 1
            elif f.sensor not in swapped:
                problems.append(f"{r.id}: new error {f.rule} {f.message}")
        snap = {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()}
        again = fix_paths([path], options).files[0]
        moved = [
            str(p) for p in tmp_path.rglob("*") if p.is_file() and snap.get(p) != p.read_bytes()
        ]
        if again.applied or moved:
            problems.append(f"{r.id}: a second --fix changed {moved}")
    with capsys.disabled():
        print(
            f"\n--fix on {robots} corpus robots: {fixed} findings fixed ({applied} fixes applied)"
        )
    assert not problems, "\n".join(problems)
    assert fixed >= 50


def test_edits_apply_back_to_front_and_overlaps_are_seen() -> None:
    from sensorkit.fix.source import Edit, apply_edits, overlaps

    data = b"<a><b/></a>"
    ins1, ins2 = Edit("f", 3, 3, b"<x/>"), Edit("f", 3, 3, b"<y/>")
    swap = Edit("f", 3, 7, b"<c/>")
    assert apply_edits(data, [ins1, ins2, swap]) == b"<a><x/><y/><c/></a>"
    assert not overlaps(ins1, ins2) and not overlaps(ins1, swap)
    assert overlaps(swap, Edit("f", 5, 9, b"")) and overlaps(swap, Edit("f", 4, 4, b"z"))
    assert not overlaps(swap, Edit("g", 3, 7, b""))


def test_sk602_keeps_a_stereo_baseline_off_a_monocular_camera(here: Path) -> None:
    """Renaming ROS 1 <hackBaseline> 0.07 to ROS 2 <hack_baseline> on a camera with no stereo
    partner would give its camera_info P[0][3] = -f * 0.07 (SK413; gazebo_ros_pkgs@ros2
    d52f7c4:gazebo_plugins/src/gazebo_ros_camera.cpp:399, :458): the fixer rejects that
    rename and applies the others."""
    path = write(here, "rover.urdf", robot(params=ROS1_CAMERA.replace("<hackBaseline>0<", "<hackBaseline>0.07<")))
    ff = fix(path)
    rejected = [n for n in ff.notes if n.kind == "rejected"]
    assert rejected and all("SK413" in n.text or "P[0][3]" in n.text for n in rejected), [n.text for n in ff.notes]
    new = path.read_bytes()
    assert b"<hackBaseline>0.07</hackBaseline>" in new and b"hack_baseline" not in new
    assert b"<frame_name>camera_optical_frame</frame_name>" in new
    assert rules(path).get("SK413", 0) == 0
