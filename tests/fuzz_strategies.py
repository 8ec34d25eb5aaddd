"""Hypothesis strategies for robot descriptions: valid, nearly valid, broken and hostile.

Nothing here runs sensorkit: a strategy draws a :class:`Case` (the files of a robot, the
one to open, xacro arguments) or the knobs a command takes. Cases are plain data and
round-trip through JSON, so a failing input is kept under ``tests/regressions/fuzz/``
and replayed (``tests/fuzz_targets.py`` drives the commands; ``tests/test_fuzz.py`` and
``benchmarks/fuzz_long.py`` run them).

How a robot is made (:func:`robots`): a random kinematic tree of links and joints with
inertials, geometry and meshes, ``<gazebo>`` blocks holding sensors (camera, depth,
multicamera, rgbd, ray/gpu_ray/lidar/gpu_lidar, imu, others) and plugins (every library
in ``sensorkit.knowledge.plugins``, as ROS 2, ROS 1 and Gazebo Sim name them, plus unknown
ones), optical frames, transmissions and ros2_control blocks. An "oddness" rate decides
how often each choice strays: duplicate and dangling names, odd numbers (nan, inf, 1e308,
-0, huge integers, empty, ``1 2``, unicode digits), wrong sensor blocks, garbage
elements. Xacro robots add properties, args, macros, conditionals and included files,
and sometimes hostile xacro (recursive macros, include loops, missing includes,
``$(find nonexistent)``, runaway expressions, huge strings). Broken files then get
text-level damage (truncation, stray characters, a DTD, another encoding).
"""

from __future__ import annotations

import base64
import json
import random
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any
from xml.sax.saxutils import escape, quoteattr

from hypothesis import strategies as st

from sensorkit.edit.kinds import KINDS
from sensorkit.knowledge.plugins import PLUGINS, PluginSpec

XACRO_NS = "http://www.ros.org/wiki/xacro"
OPTICAL_RPY = "-1.5707963267948966 0 -1.5707963267948966"
TARGETS = ("auto", "classic", "ros1", "fortress", "harmonic", "jetty")

# ------------------------------------------------------------------------------ the data


@dataclass
class Case:
    """One robot on disk: ``files`` (relative path -> bytes), ``main`` the file to open."""

    files: dict[str, bytes]
    main: str
    args: dict[str, str] = field(default_factory=dict)
    label: str = "valid"  # valid | near | broken | hostile (what the generator meant)
    links: list[str] = field(default_factory=list)  # link names as generated (hints for add)
    sensors: list[str] = field(default_factory=list)

    def write(self, folder: Any) -> Any:
        """Write every file under ``folder`` (a Path); return the main file's path."""
        for rel, data in self.files.items():
            path = folder / rel
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_bytes(data)
        return folder / self.main

    def to_json(self) -> dict[str, Any]:
        files: dict[str, Any] = {}
        for rel, data in self.files.items():
            try:
                text = data.decode("utf-8")
            except UnicodeDecodeError:
                files[rel] = {"base64": base64.b64encode(data).decode("ascii")}
            else:
                files[rel] = {"text": text}
        return {
            "files": files,
            "main": self.main,
            "args": self.args,
            "label": self.label,
            "links": self.links,
            "sensors": self.sensors,
        }

    @classmethod
    def from_json(cls, data: dict[str, Any]) -> Case:
        files = {
            rel: base64.b64decode(v["base64"]) if "base64" in v else v["text"].encode("utf-8")
            for rel, v in data["files"].items()
        }
        return cls(
            files=files,
            main=data["main"],
            args=dict(data.get("args", {})),
            label=data.get("label", ""),
            links=list(data.get("links", [])),
            sensors=list(data.get("sensors", [])),
        )


@dataclass
class FuzzInput:
    """What one fuzz target runs: a case and the knobs of the command (JSON-able)."""

    target: str
    case: Case
    knobs: dict[str, Any] = field(default_factory=dict)

    def dumps(self) -> str:
        return json.dumps(
            {"target": self.target, "case": self.case.to_json(), "knobs": self.knobs},
            indent=1,
            ensure_ascii=True,
        )

    @classmethod
    def loads(cls, text: str) -> FuzzInput:
        data = json.loads(text)
        return cls(data["target"], Case.from_json(data["case"]), dict(data.get("knobs", {})))


# ------------------------------------------------------------------------- odd values

ODD_NUMBERS = (
    "nan", "NaN", "-nan", "inf", "-inf", "Infinity", "1e308", "-1e308", "1.7976931348623157e308",
    "1e309", "-0", "-0.0", "0", "0.0", "1e-320", "5e-324", "-5e-324", "9" * 400, "-" + "9" * 40,
    "18446744073709551617", "", " ", "1 2", "1 2 3", "1,5", "0x1A", "1_000", "\u0661\u0662",
    "\uff11", "\u00bd", "+.5", "5.", ".", "e5", "1e", "--1", "true", "None", "1e+308", "  7  ",
    "\u00a01", "3.14159265358979323846264338327950288419716939937510", "2147483648",
    "-2147483649", "4294967296", "1e-7", "-1", "1e5", "100000000", "1.5", "\u2212" + "1",
)  # fmt: skip
ODD_NAMES = (
    "", " ", "a b", " base_link", "base_link ", "\u00fcn\u00efc\u00f8d\u00e9", "\u540d\u524d",
    "a/b", "/abs", "a.b", "-x", "1link", "x" * 300, "&", "<", '"', "'", "\t", "world", "map",
    "odom", "${x}", "$(arg x)", "\u200b", "emoji\U0001f600", "a\u0301", "a:b", "__", "~",
    "a//b", "base_link/", "~/out", "{sensor}",
)  # fmt: skip
ODD_TOPICS = (
    "scan", "/scan", "~/out", "", "a//b", "1bad", "ns/{x}", "\u00fc", "/", "image_raw",
    "camera/image_raw", "/robot/points", "a b", "~", "out:=x", "scan/",
)  # fmt: skip
LINK_POOL = (
    "base_footprint", "base_link", "chassis", "camera_link", "laser_link", "lidar_link",
    "imu_link", "wheel_left", "wheel_right", "arm", "head", "mast", "depth_link", "stereo",
    "sensor_mount", "caster",
)  # fmt: skip
JOINT_TYPES = ("fixed", "revolute", "continuous", "prismatic", "floating", "planar")
ODD_JOINT_TYPES = ("", "Fixed", "hinge", "ball", "revolute ", "screw", "gearbox")
CAMERA_TYPES = ("camera", "depth", "depth_camera", "rgbd_camera", "rgbd", "multicamera",
                "wideanglecamera", "thermal", "segmentation", "boundingbox_camera")  # fmt: skip
LIDAR_TYPES = ("ray", "gpu_ray", "lidar", "gpu_lidar")
OTHER_TYPES = ("imu", "gps", "navsat", "contact", "force_torque", "altimeter", "sonar",
               "magnetometer", "air_pressure", "", "bogus", "Camera", "rfid")  # fmt: skip
FORMATS = ("R8G8B8", "B8G8R8", "L8", "L16", "R_FLOAT32", "RGB_INT8", "BAYER_RGGB8", "R16G16B16",
           "", "rgb", "BGR_INT8", "FLOAT32")  # fmt: skip
GZ_SYSTEM_NAMES = ("gz::sim::systems::Sensors", "ignition::gazebo::systems::Sensors",
                   "gz::sim::systems::Imu", "gz::sim::systems::DiffDrive", "", "bogus")  # fmt: skip
UNKNOWN_PLUGINS = (
    "libmy_plugin.so", "", "libgazebo_ros_camera", "gz-sim-nonexistent-system", "lib.so", ".so",
    "lib", "/", "libgazebo_ros_cameraX.so", "libgazebo_ros_camera.so.1", "gazebo_ros_camera.dll",
    "/opt/ros/humble/lib/libgazebo_ros_camera.so", "libgazebo_ros_laser.so ", "LIBGAZEBO_ROS_CAMERA.SO",
    "ignition-gazebo-sensors-system.so", "libgz-sim-sensors-system.so", "\u00fc.so",
)  # fmt: skip
ROS1_PARAMS = ("robotNamespace", "frameName", "topicName", "cameraName", "imageTopicName",
               "cameraInfoTopicName", "updateRate", "bodyName", "gaussianNoise", "alwaysOn",
               "pointCloudTopicName", "depthImageTopicName", "hackBaseline", "CxPrime",
               "distortionK1", "serviceName")  # fmt: skip
ROS2_PARAMS = ("frame_name", "camera_name", "output_type", "hack_baseline", "min_depth",
               "max_depth", "radiation_type", "initial_orientation_as_reference", "update_rate",
               "body_name", "topic_name", "Cx", "focal_length")  # fmt: skip
GZ_SENSOR_TAGS = ("topic", "gz_frame_id", "ignition_frame_id", "frame_id", "enable_metrics",
                  "visualize", "always_on")  # fmt: skip
GARBAGE_ELEMENTS = (
    "<foo/>", '<bar baz="1">text</bar>', "<sensor/>", "<link/>", "<joint/>", "<gazebo/>",
    "<plugin/>", "<camera/>", "<!-- a comment -->", "<?pi data?>", "<![CDATA[ <robot> & ]]>",
    '<ns:thing xmlns:ns="urn:x"/>', "\u00fcnicode text \u2603", "<image/>", "<ray/>", "<lidar/>",
    '<origin xyz="1 2 3"/>', "<noise><type>gaussian</type></noise>", "<pose>1 2 3 4 5 6</pose>",
    "<material/>", '<mesh filename="package://nope/x.stl"/>', "<inertial/>", "<visual/>",
    "<ros><remapping>~/out:=scan</remapping></ros>", "<update_rate>nan</update_rate>",
)  # fmt: skip

SENSOR_PLUGINS: tuple[PluginSpec, ...] = tuple(p for p in PLUGINS if p.level == "sensor")
MODEL_PLUGINS: tuple[PluginSpec, ...] = tuple(p for p in PLUGINS if p.level != "sensor")


def plugin_params(spec: PluginSpec) -> list[str]:
    """Every parameter name the knowledge table says ``spec`` reads."""
    names = list(spec.frame_params)
    names += [p for p, _ in spec.topics if p]
    if spec.topic_ns_param:
        names.append(spec.topic_ns_param)
    if spec.owns is not None and spec.owns.param:
        names.append(spec.owns.param)
    if spec.owner_class_param:
        names.append(spec.owner_class_param)
    if spec.frame_default_param:
        names.append(spec.frame_default_param)
    return list(dict.fromkeys(names))


def attr(value: str) -> str:
    return quoteattr(value)


# --------------------------------------------------------------------------- generator


def _rng(draw: st.DrawFn) -> random.Random:
    """A plain ``random.Random`` seeded by Hypothesis: reproducible from Hypothesis' seed,
    uniform, and fast (Hypothesis' own Random costs ~10 us a call)."""
    return random.Random(draw(st.randoms(use_true_random=True)).getrandbits(64))


class Gen:
    """Choices from one seeded ``random.Random``: ``rate`` per mille of them stray.

    The Random comes from Hypothesis (``st.randoms``), so runs are reproducible from its
    seed (and ``derandomize``); its choices are uniform and cheap, which Hypothesis' own
    draws (biased towards small values, shrinkable) are not. Failing inputs are saved
    whole rather than shrunk.
    """

    def __init__(
        self, rnd: random.Random, rate: int, *, xacro: bool = False, tiny: bool = False
    ) -> None:
        self.rnd = rnd
        self.rate = rate
        self.xacro = xacro
        self.tiny = tiny  # sizes a render can do in milliseconds
        self.props: list[str] = []  # xacro properties defined (numbers)
        self.hostile = False  # hostile xacro was added

    def odd(self, scale: int = 1) -> bool:
        return self.rate > 0 and self.rnd.randrange(1000) < min(1000, self.rate * scale)

    def pick(self, items: Any) -> Any:
        return self.rnd.choice(list(items))

    def chance(self, per_mille: int) -> bool:
        return self.rnd.randrange(1000) < per_mille

    def int_(self, lo: int, hi: int) -> int:
        return self.rnd.randint(lo, hi)

    def num(self, lo: float = -2.0, hi: float = 2.0, *, integer: bool = False) -> str:
        if self.odd():
            return str(self.pick(ODD_NUMBERS))
        if self.xacro and self.props and self.chance(60):
            p = self.pick(self.props)
            return self.pick([f"${{{p}}}", f"${{{p}*1}}", f"${{{p}+0}}"])
        if integer:
            return str(self.int_(int(lo), int(hi)))
        if self.xacro and self.chance(30):
            return self.pick(["${pi/2}", "${-pi/2}", "${radians(30)}", "${0.1*2}", "${1/3}"])
        v = self.pick([lo, hi, 0.0]) if self.chance(50) else self.rnd.uniform(lo, hi)
        return repr(round(float(v), self.pick([1, 3, 5, 17])))

    def vec(self, n: int = 3, lo: float = -2.0, hi: float = 2.0) -> str:
        if self.odd():
            return str(self.pick(["", "1 2", "1 2 3 4", "1,2,3", "1\t2\n3", "a b c", " 0  0  0 ",
                                  "nan 0 0", "0 inf 0", "1e308 1e308 1e308", "-0 -0 -0", "1 2 3 4 5 6 7"]))  # fmt: skip
        return " ".join(self.num(lo, hi) for _ in range(n))

    def rpy(self) -> str:
        return self.vec(3, -3.2, 3.2)

    def name(self, base: str, used: dict[str, None] | set[str] | None = None) -> str:
        """``base`` made unique in ``used`` (a dict keeps the order deterministic), or odd."""
        if self.odd():
            if used and self.chance(500):
                taken = list(used) if isinstance(used, dict) else sorted(used)
                return str(taken[self.rnd.randrange(len(taken))])  # a duplicate
            return str(self.pick(ODD_NAMES))
        name = base
        i = 1
        while used is not None and name in used:
            name = f"{base}_{i}"
            i += 1
        return name

    def topic(self) -> str:
        if self.odd(3):
            return str(self.pick(ODD_TOPICS))
        return str(
            self.pick(["scan", "image_raw", "points", "imu/data", "camera/image", "front/scan"])
        )

    def garbage(self) -> str:
        return str(self.pick(GARBAGE_ELEMENTS)) if self.odd() else ""

    def text(self, value: str) -> str:
        return value if self.odd() else escape(value)

    def q(self, value: str) -> str:
        """An attribute value, quoted (and escaped, unless odd)."""
        if self.odd():
            return f'"{value}"'
        return attr(value)


# ----------------------------------------------------------------------- building parts


def _inertial(g: Gen) -> str:
    if g.odd():
        return str(g.pick(["", "<inertial/>", "<inertial><mass/></inertial>",
                           '<inertial><mass value="1"/></inertial>']))  # fmt: skip
    m = g.num(0.01, 20.0)
    i = g.num(1e-5, 1.0)
    inertia = " ".join(
        f'{k}="{i if k in ("ixx", "iyy", "izz") else "0"}"'
        for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
    )
    origin = f'<origin xyz="{g.vec()}" rpy="{g.rpy()}"/>' if g.chance(300) else ""
    return f'<inertial>{origin}<mass value="{m}"/><inertia {inertia}/></inertial>'


def _geometry(g: Gen) -> str:
    kind = g.int_(0, 4)
    if kind == 0:
        return f'<box size="{g.vec(3, 0.01, 1.0)}"/>'
    if kind == 1:
        return f'<cylinder radius="{g.num(0.01, 0.5)}" length="{g.num(0.01, 1.0)}"/>'
    if kind == 2:
        return f'<sphere radius="{g.num(0.01, 0.5)}"/>'
    if kind == 3:
        uri = g.pick(["package://nonexistent/meshes/a.stl", "file:///nonexistent/a.dae", "meshes/a.stl",
                      "", "package://", "package:///x.stl", "file://", "model://m/x.dae",
                      "http://example.invalid/x.stl", "../../../../etc/passwd", "\u00fc.stl",
                      "package://robot_pkg/meshes/base.stl", "meshes/base.stl"])  # fmt: skip
        scale = f' scale="{g.vec(3, 0.001, 2.0)}"' if g.chance(300) else ""
        return f"<mesh filename={attr(uri)}{scale}/>"
    return str(
        g.pick(["", "<capsule radius='0.1' length='0.2'/>", "<box/>", "<plane/>", "<cylinder/>"])
    )


def _link(g: Gen, name: str) -> str:
    body = ""
    if not g.chance(150):
        body += _inertial(g)
    for tag in ("visual", "collision"):
        if g.chance(400):
            origin = f'<origin xyz="{g.vec()}" rpy="{g.rpy()}"/>' if g.chance(400) else ""
            mat = ""
            if tag == "visual" and g.chance(300):
                mat = f'<material name={attr(g.pick(["grey", "red", ""]))}><color rgba="{g.vec(4, 0, 1)}"/></material>'
            body += f"<{tag}>{origin}<geometry>{_geometry(g)}</geometry>{mat}</{tag}>"
    body += g.garbage()
    if not body and g.chance(500):
        return f"<link name={g.q(name)}/>"
    return f"<link name={g.q(name)}>{body}</link>"


def _joint(g: Gen, name: str, parent: str, child: str, jtype: str | None = None) -> str:
    jtype = jtype or (g.pick(ODD_JOINT_TYPES) if g.odd() else g.pick(JOINT_TYPES))
    parts = []
    if not g.odd():
        parts.append(f"<parent link={g.q(parent)}/>")
    if not g.odd():
        parts.append(f"<child link={g.q(child)}/>")
    if g.chance(800):
        parts.append(f'<origin xyz="{g.vec()}" rpy="{g.rpy()}"/>')
    if jtype in ("revolute", "continuous", "prismatic", "planar") or g.odd():
        if not g.odd():
            parts.append(
                f'<axis xyz="{g.pick(["1 0 0", "0 1 0", "0 0 1"]) if not g.odd() else g.vec()}"/>'
            )
        if jtype in ("revolute", "prismatic") and not g.odd():
            parts.append(
                f'<limit lower="{g.num(-3, 0)}" upper="{g.num(0, 3)}" effort="{g.num(0, 100)}" velocity="{g.num(0, 10)}"/>'
            )
    if g.chance(50):
        parts.append(f'<dynamics damping="{g.num(0, 1)}" friction="{g.num(0, 1)}"/>')
    if g.odd():
        parts.append(f'<mimic joint={g.q(g.pick(ODD_NAMES))} multiplier="{g.num()}"/>')
    parts.append(g.garbage())
    if g.odd():
        g.rnd.shuffle(parts)
    return f"<joint name={g.q(name)} type={g.q(jtype)}>{''.join(parts)}</joint>"


def _noise(g: Gen) -> str:
    if not g.chance(300):
        return ""
    ntype = (
        g.pick(["gaussian", "gaussian_quantized", "none", "", "bogus"]) if g.odd() else "gaussian"
    )
    return f"<noise><type>{ntype}</type><mean>{g.num(-0.1, 0.1)}</mean><stddev>{g.num(0, 0.1)}</stddev></noise>"


def camera_block(g: Gen, name: str | None = None, depth: bool = False) -> str:
    if g.tiny and not g.odd():
        w, h = str(g.int_(2, 48)), str(g.int_(2, 48))
    else:
        w = g.num(1, 4096, integer=True)
        h = g.num(1, 4096, integer=True)
    parts = [f"<horizontal_fov>{g.num(0.05, 3.1)}</horizontal_fov>"]
    fmt = f"<format>{g.pick(FORMATS) if g.odd(5) else 'R8G8B8'}</format>" if g.chance(700) else ""
    parts.append(f"<image><width>{w}</width><height>{h}</height>{fmt}</image>")
    if g.chance(850):
        parts.append(f"<clip><near>{g.num(0.01, 0.5)}</near><far>{g.num(1.0, 300.0)}</far></clip>")
    if depth and g.chance(300):
        parts.append(
            f"<depth_camera><clip><near>{g.num(0.01, 1)}</near><far>{g.num(1, 20)}</far></clip></depth_camera>"
        )
    parts.append(_noise(g))
    if g.chance(200):
        ks = "".join(
            f"<{k}>{g.num(-0.5, 0.5)}</{k}>"
            for k in ("k1", "k2", "k3", "p1", "p2")
            if g.chance(700)
        )
        parts.append(f"<distortion>{ks}<center>0.5 0.5</center></distortion>")
    if g.chance(200):
        lens = ""
        if g.chance(500):
            lens += (
                "<intrinsics>"
                + "".join(f"<{k}>{g.num(0, 1000)}</{k}>" for k in ("fx", "fy", "cx", "cy", "s"))
                + "</intrinsics>"
            )
        if g.chance(500):
            lens += (
                "<projection>"
                + "".join(
                    f"<{k}>{g.num(-10, 1000)}</{k}>"
                    for k in ("p_fx", "p_fy", "p_cx", "p_cy", "tx", "ty")
                    if g.chance(800)
                )
                + "</projection>"
            )
        if g.chance(300):
            lens += (
                f"<type>{g.pick(['pinhole', 'stereographic', 'equidistant', 'custom', ''])}</type>"
            )
        parts.append(f"<lens>{lens}</lens>")
    if g.chance(100):
        parts.append(
            f"<optical_frame_id>{g.text(g.name('camera_optical_frame'))}</optical_frame_id>"
        )
    if g.chance(80):
        parts.append(f"<camera_info_topic>{g.text(g.topic())}</camera_info_topic>")
    if name is not None or g.chance(50):
        parts.append(f"<pose>{g.vec(6, -0.2, 0.2)}</pose>")
    parts.append(g.garbage())
    nattr = f" name={g.q(name)}" if name is not None else ""
    return f"<camera{nattr}>{''.join(parts)}</camera>"


def lidar_block(g: Gen, tag: str) -> str:
    samples = str(g.int_(1, 90)) if g.tiny and not g.odd() else g.num(1, 4000, integer=True)
    horiz = (
        f"<horizontal><samples>{samples}</samples><resolution>{g.num(0.1, 2)}</resolution>"
        f"<min_angle>{g.num(-3.2, 0)}</min_angle><max_angle>{g.num(0, 3.2)}</max_angle></horizontal>"
    )
    vert = ""
    if g.chance(300):
        vs = str(g.int_(1, 4)) if g.tiny and not g.odd() else g.num(1, 128, integer=True)
        vert = (
            f"<vertical><samples>{vs}</samples><resolution>{g.num(0.1, 2)}</resolution>"
            f"<min_angle>{g.num(-0.6, 0)}</min_angle><max_angle>{g.num(0, 0.6)}</max_angle></vertical>"
        )
    rng = f"<range><min>{g.num(0.01, 1)}</min><max>{g.num(1, 200)}</max><resolution>{g.num(0.001, 0.1)}</resolution></range>"
    if g.odd():
        rng = g.pick(["", "<range/>", "<range><min>5</min><max>1</max></range>"])
    return f"<{tag}><scan>{horiz}{vert}</scan>{rng}{_noise(g)}{g.garbage()}</{tag}>"


def imu_block(g: Gen) -> str:
    axes = ""
    for kind in ("angular_velocity", "linear_acceleration"):
        if g.chance(600):
            axes += (
                f"<{kind}>"
                + "".join(
                    f"<{a}><noise type={attr('gaussian' if not g.odd() else g.pick(['', 'none', 'x']))}>"
                    f"<mean>{g.num(-0.1, 0.1)}</mean><stddev>{g.num(0, 0.1)}</stddev></noise></{a}>"
                    for a in ("x", "y", "z")
                )
                + f"</{kind}>"
            )
    return f"<imu>{axes}{g.garbage()}</imu>"


def _plugin_value(g: Gen, param: str, frames: list[str]) -> str:
    low = param.lower()
    if "frame" in low and frames:
        return g.name(g.pick(frames))
    if "namespace" in low:
        return g.pick(["", "/", "robot1", "/robot1/", "a b", "1bad"]) if g.odd(3) else "robot1"
    if "name" in low or "topic" in low:
        return g.topic()
    return g.num(0, 100)


def plugin(
    g: Gen, *, level: str, sensor_type: str | None, frames: list[str], sensor_name: str
) -> str:
    """A ``<plugin>``: known (from the knowledge table), sometimes unknown or bent."""
    if g.chance(150):
        filename = g.pick(UNKNOWN_PLUGINS)
        spec = None
    else:
        pool = SENSOR_PLUGINS if level == "sensor" else MODEL_PLUGINS
        if level == "sensor" and sensor_type and not g.odd(3):
            fitting = [p for p in pool if not p.sensor_types or sensor_type in p.sensor_types]
            pool = tuple(fitting) or pool
        spec = g.pick(pool)
        lib = g.pick(spec.libraries)
        if spec.ros == "gz":
            filename = lib if not g.odd(3) else g.pick([f"lib{lib}.so", f"{lib}.so", lib.upper()])
        else:
            filename = (
                f"lib{lib}.so"
                if not g.odd(3)
                else g.pick([lib, f"lib{lib}", f"/usr/lib/lib{lib}.so"])
            )
    if spec is not None and spec.ros == "gz":
        pname = g.pick(GZ_SYSTEM_NAMES)
    else:
        pname = g.name(f"{sensor_name}_controller")
    params: list[str] = []
    names = plugin_params(spec) if spec is not None else []
    if spec is None or spec.ros == "ros2":
        names += g.rnd.sample(ROS2_PARAMS, g.int_(0, 2))
    if spec is None or spec.ros == "ros1":
        names += g.rnd.sample(ROS1_PARAMS, g.int_(0, 2))
    for p in dict.fromkeys(names):
        if g.chance(700) or g.odd():
            params.append(f"<{p}>{g.text(_plugin_value(g, p, frames))}</{p}>")
    if (spec is None or spec.ros == "ros2" or g.odd()) and g.chance(500):
        ros = ""
        if g.chance(600):
            ros += f"<namespace>{g.text(g.pick(['robot1', '/robot1', '', '/', 'a b', 'ns/'] if g.odd(3) else ['robot1', '/demo']))}</namespace>"
        for _ in range(g.int_(0, 2)):
            left = g.pick(
                ["~/out", "image_raw", "camera_info", "points", "~/imu", "depth/image_raw", "out"]
            )
            rule = g.pick(
                [
                    f"{left}:={g.topic()}",
                    f"--remap {left}:=x",
                    f"-r {left}:=y",
                    "garbage",
                    ":=",
                    f"{left}:=",
                ]
            )
            ros += f"<remapping>{g.text(rule)}</remapping>"
        if g.chance(200):
            ros += "<argument>--ros-args</argument><parameter name='use_sim_time'>true</parameter>"
        params.append(f"<ros>{ros}</ros>")
    if spec is not None and spec.ros == "gz" and g.chance(300):
        params.append(f"<render_engine>{g.pick(['ogre2', 'ogre', ''])}</render_engine>")
    params.append(g.garbage())
    fattr = "" if g.odd() else f" filename={g.q(filename)}"
    nattr = "" if g.odd() else f" name={g.q(pname)}"
    return f"<plugin{nattr}{fattr}>{''.join(params)}</plugin>"


def sensor(g: Gen, name: str, frames: list[str]) -> tuple[str, str]:
    """``(type, <sensor> text)`` for a sensor called ``name``."""
    family = g.int_(0, 3)
    if family == 0:
        stype = g.pick(CAMERA_TYPES)
    elif family == 1:
        stype = g.pick(LIDAR_TYPES)
    elif family == 2:
        stype = "imu"
    else:
        stype = g.pick(OTHER_TYPES) if g.odd(5) else g.pick(["camera", "gpu_lidar", "depth_camera"])
    parts = []
    if g.chance(850):
        parts.append(f"<update_rate>{g.num(1, 100)}</update_rate>")
    if g.chance(300):
        parts.append(f"<always_on>{g.pick(['true', '1', 'false', 'yes'])}</always_on>")
    if g.chance(200):
        parts.append(f"<visualize>{g.pick(['true', 'false'])}</visualize>")
    if g.chance(200):
        parts.append(f"<pose>{g.vec(6, -0.3, 0.3)}</pose>")
    for tag in GZ_SENSOR_TAGS[:4]:
        if g.chance(120):
            value = g.topic() if tag == "topic" else g.name(g.pick(frames) if frames else "frame")
            parts.append(f"<{tag}>{g.text(value)}</{tag}>")
    kind = stype if not g.odd(3) else g.pick((*CAMERA_TYPES, *LIDAR_TYPES, "imu"))
    if kind == "multicamera":
        for i in range(g.int_(0 if g.odd() else 1, 3)):
            parts.append(camera_block(g, name=g.pick(["left", "right", "center", ""]) + str(i)))
    elif kind in CAMERA_TYPES:
        parts.append(camera_block(g, depth=kind not in ("camera", "wideanglecamera", "thermal")))
        if g.odd():
            parts.append(camera_block(g))  # a second <camera> in a single camera
    elif kind in LIDAR_TYPES:
        tag = (
            ("lidar" if kind in ("lidar", "gpu_lidar") else "ray")
            if not g.odd(3)
            else g.pick(["ray", "lidar"])
        )
        parts.append(lidar_block(g, tag))
    elif kind == "imu":
        parts.append(imu_block(g))
    for _ in range(g.int_(0, 2) if not g.odd() else g.int_(0, 4)):
        parts.append(plugin(g, level="sensor", sensor_type=stype, frames=frames, sensor_name=name))
    parts.append(g.garbage())
    tattr = f" type={g.q(stype)}" if not g.odd() else ""
    return stype, f"<sensor name={g.q(name)}{tattr}>{''.join(parts)}</sensor>"


def _urdfdom_sensor(g: Gen, name: str, parent: str) -> str:
    return (
        f"<sensor name={g.q(name)} type={g.q(g.pick(['camera', 'ray', 'imu']))} update_rate={attr(g.num(1, 60))}>"
        f"<parent link={g.q(parent)}/><origin xyz='{g.vec()}' rpy='{g.rpy()}'/>"
        f"<camera><image width={attr(g.num(1, 640, integer=True))} height={attr(g.num(1, 480, integer=True))} "
        f"hfov={attr(g.num(0.1, 3))} format='RGB8' near='0.1' far='10'/></camera></sensor>"
    )


# ------------------------------------------------------------------------------ robots


@dataclass
class _Body:
    parts: list[str]
    links: list[str]
    joints: list[str]
    sensors: list[str]


def _body(g: Gen, max_links: int) -> _Body:
    """Links, joints, gazebo blocks and extras of one robot, as XML text pieces."""
    n = g.int_(0 if g.odd() else 1, max_links)
    if max_links >= 10 and g.chance(8):
        n = g.pick([200, 1000, 3000])  # big: slow paths, deep chains
    shape = g.pick(["tree", "tree", "chain", "star"])
    links: list[str] = []
    used: dict[str, None] = {}
    for i in range(n):
        base = g.pick(LINK_POOL) if i else g.pick(["base_footprint", "base_link", "world", "root"])
        name = g.name(base, used)
        used[name] = None
        links.append(name)
    parts: list[str] = []
    joints: list[str] = []
    jused: dict[str, None] = {}
    for i, name in enumerate(links):
        parts.append(_link(g, name))
        if i == 0:
            continue
        parent = links[{"tree": g.int_(0, i - 1), "chain": i - 1, "star": 0}[shape]]
        if g.odd():
            parent = g.pick([*links, "nonexistent_link", ""])
        jname = g.name(f"{name}_joint", jused)
        jused[jname] = None
        joints.append(jname)
        parts.append(_joint(g, jname, parent, name))
    sensors: list[str] = []
    sused: dict[str, None] = {}
    for _ in range(g.int_(0, 4)):
        if not links:
            break
        host = g.pick(links)
        sname = g.name(
            g.pick(["front_camera", "laser", "imu", "depth", "stereo", "lidar", "cam"]), sused
        )
        sused[sname] = None
        sensors.append(sname)
        frames = [host]
        if g.chance(600):
            optical = g.name(f"{sname}_optical_frame", used)
            used[optical] = None
            links.append(optical)
            frames.append(optical)
            rpy = OPTICAL_RPY if not g.odd(3) else g.rpy()
            jname = g.name(f"{sname}_optical_joint", jused)
            parts.append(f"<link name={g.q(optical)}/>")
            parts.append(
                f"<joint name={g.q(jname)} type='fixed'><parent link={g.q(host)}/><child link={g.q(optical)}/>"
                f"<origin xyz='0 0 0' rpy='{rpy}'/></joint>"
            )
        _, text = sensor(g, sname, frames)
        ref = host if not g.odd() else g.pick([*joints, "nonexistent_link", "", host])
        rattr = f" reference={g.q(ref)}" if not g.odd() else ""
        extra = "<material>Gazebo/Red</material>" if g.chance(100) else ""
        parts.append(f"<gazebo{rattr}>{extra}{text}</gazebo>")
    for _ in range(g.int_(0, 2)):
        body = "".join(
            plugin(
                g,
                level="model",
                sensor_type=None,
                frames=links or ["base_link"],
                sensor_name="robot",
            )
            for _ in range(g.int_(1, 2))
        )
        parts.append(f"<gazebo>{body}</gazebo>")
    if g.chance(100) and joints:
        j = g.pick(joints)
        parts.append(
            f"<transmission name='t'><type>transmission_interface/SimpleTransmission</type>"
            f"<joint name={g.q(j)}><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>"
            "<actuator name='m'><mechanicalReduction>1</mechanicalReduction></actuator></transmission>"
        )
    if g.chance(100) and joints:
        parts.append(
            f"<ros2_control name='sys' type='system'><hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>"
            f"<joint name={g.q(g.pick(joints))}><command_interface name='velocity'/><state_interface name='position'/></joint></ros2_control>"
        )
    if g.chance(60) and links:
        parts.append(_urdfdom_sensor(g, g.name("urdf_sensor"), g.pick(links)))
    if g.chance(80):
        parts.append(
            f"<material name={attr(g.pick(['grey', 'blue']))}><color rgba='{g.vec(4, 0, 1)}'/></material>"
        )
    for _ in range(g.int_(0, 3) if g.odd() else 0):
        at = g.int_(0, len(parts))
        parts.insert(at, g.pick(GARBAGE_ELEMENTS))
    return _Body(parts, links, joints, sensors)


# Hostile xacro pieces (in the robot file itself). ``{bomb}`` ones run until a timeout.
HOSTILE_XACRO = (
    '<xacro:macro name="loop"><xacro:loop/></xacro:macro><xacro:loop/>',
    '<xacro:macro name="ping"><xacro:pong/></xacro:macro><xacro:macro name="pong"><xacro:ping/></xacro:macro><xacro:ping/>',
    '<xacro:include filename="missing_file.xacro"/>',
    '<xacro:include filename="$(find nonexistent_pkg)/urdf/x.xacro"/>',
    '<link name="$(find nonexistent_pkg)"/>',
    '<link name="${undefined_property}"/>',
    '<link name="$(arg undefined_arg)"/>',
    '<xacro:property name="self" value="${self}"/><link name="${self}"/>',
    '<xacro:property name="pa" value="${pb}"/><xacro:property name="pb" value="${pa}"/><link name="${pa}"/>',
    '<link name="${1/0}"/>',
    "<link name=\"${int('x')}\"/>",
    '<link name="${[1][5]}"/>',
    "<link name=\"${__import__('os').getpid()}\"/>",
    "<link name=\"${open('/etc/hostname').read()}\"/>",
    '<link name="$(env SENSORKIT_FUZZ_UNSET)"/>',
    '<link name="$(optenv SENSORKIT_FUZZ_UNSET default)"/>',
    "<link name=\"$(eval 1+1)\"/>",
    '<xacro:insert_block name="missing_block"/>',
    '<xacro:call macro="${\'nope\'}"/>',
    '<xacro:nonexistent_macro a="1"/>',
    '<xacro:if value="maybe"><link name="if_link"/></xacro:if>',
    '<xacro:unless value="2"><link name="unless_link"/></xacro:unless>',
    '<xacro:element xacro:name="${\'link\'}" name="elem_link"/>',
    '<xacro:element xacro:name="" name="x"/>',
    '<link name="attr_link"><xacro:attribute name="" value="1"/></link>',
    '<xacro:macro name="m2" params="a b:=1 *blk **blks"><link name="${a}"/></xacro:macro><xacro:m2/>',
    '<xacro:macro name="" params=""/>',
    '<xacro:property name="big" value="${\'x\'*1000000}"/><link name="big_${len(big)}"/>',
    '<link name="${load_yaml(\'nonexistent.yaml\')}"/>',
    "<xacro:property name=\"y\" value=\"${xacro.load_yaml('/etc/hostname')}\"/>",
    '<xacro:property name="d" value="${dict(a=1)}"/><link name="${d[\'b\']}"/>',
    '<link name="${\'\\u00fc\' * 3}"/>',
    "<xacro:arg name=\"a1\" default=\"$(arg a1)\"/><link name=\"$(arg a1)\"/>",
    '<xacro:include filename="/dev/null"/>',
    '<xacro:include filename="/"/>',
    '<xacro:include filename="robot.urdf.xacro"/>',
    '<xacro:include filename="parts/loop_a.xacro"/>',
)  # fmt: skip
# Issue 36: objects as values, reads above the repository, a FIFO include, and sizes the
# evaluator must count before it builds them (validate runs a share with --untrusted).
HOSTILE_XACRO += (
    '<link name="${xacro.load_yaml}"/>',
    "<link name=\"${'%(load_yaml)r' % xacro}\"/>",
    '<link name="${min([], default=math)}"/>',
    '<link name="${str(xacro)}"/>',
    "<link name=\"${xacro.load_yaml('../../../../../../etc/hostname')}\"/>",
    '<xacro:include filename="../../../../../../etc/hostname"/>',
    '<xacro:include filename="/dev/zero"/>',
)
BOMBS = (
    '<link name="${round(7, -10**8)}"/>',
    '<xacro:arg name="rb36" default="}"/><link name="${len((\'{0$(arg rb36)\'*20000).format(\'a\'*1000))}"/>',
    "<link name=\"${len([s + 'x' for s in ['a'*100000]*1000])}\"/>",
    "<link name=\"${len([xacro.message('a'*100000) for i in python.range(70)])}\"/>",
    '<link name="${10**10**10}"/>',
    '<link name="${2**2**40}"/>',
    "<xacro:property name=\"huge\" value=\"${'x'*(10**9)}\"/><link name=\"h_${len(huge)}\"/>",
    '<link name="${[0]*(10**10)}"/>',
    '<link name="${sum(range(10**12))}"/>',
)  # fmt: skip


def _xacro_wrap(
    g: Gen, body: _Body, files: dict[str, bytes], *, hostile: bool, bombs: bool
) -> tuple[str, str]:
    """(header, footer) xacro material around the body; extra files go into ``files``."""
    head: list[str] = []
    tail: list[str] = []
    for p in g.props:
        head.append(f'<xacro:property name="{p}" value="{g.num(0.01, 1.0)}"/>')
    if g.chance(400):
        head.append('<xacro:arg name="prefix" default=""/>')
        head.append('<xacro:property name="pre" value="$(arg prefix)"/>')
    if g.chance(500) and body.links:
        parent = g.pick(body.links)
        n = g.int_(1, 3)
        head.append(
            '<xacro:macro name="box_link" params="name parent *origin size:=0.1">'
            '<link name="${name}"><visual><geometry><box size="${size} ${size} ${size}"/></geometry></visual></link>'
            '<joint name="${name}_joint" type="fixed"><parent link="${parent}"/><child link="${name}"/>'
            '<xacro:insert_block name="origin"/></joint></xacro:macro>'
        )
        for i in range(n):
            lname = g.name(f"extra{i}", set(body.links)) if not g.odd(3) else g.pick(body.links)
            tail.append(
                f'<xacro:box_link name={g.q(lname)} parent={g.q(parent)} size="{g.num(0.01, 0.5)}">'
                f'<origin xyz="{g.vec()}" rpy="0 0 0"/></xacro:box_link>'
            )
    if g.chance(300):
        cond = (
            g.pick(["true", "false", "${1 == 1}", "1", "0"])
            if not g.odd(3)
            else g.pick(["maybe", "", "2", "${none}"])
        )
        tail.append(f'<xacro:if value="{cond}"><link name="cond_link"/></xacro:if>')
    if g.chance(300) and body.parts:
        # move some parts into an included file
        k = g.int_(1, len(body.parts))
        moved, body.parts[:] = body.parts[-k:], body.parts[:-k]
        inc = "parts/extra.urdf.xacro"
        files[inc] = (
            f'<?xml version="1.0"?>\n<robot xmlns:xacro="{XACRO_NS}">\n'
            + "\n".join(moved)
            + "\n</robot>\n"
        ).encode()
        how = (
            g.pick([inc, f"$(cwd)/{inc}", "${'parts'}/extra.urdf.xacro", "./" + inc])
            if g.odd(3)
            else inc
        )
        tail.append(f'<xacro:include filename="{how}"/>')
    if hostile and g.chance(600):
        for _ in range(g.int_(1, 2)):
            piece = g.pick(HOSTILE_XACRO)
            if "loop_a" in piece:
                files["parts/loop_a.xacro"] = (
                    f'<robot xmlns:xacro="{XACRO_NS}"><xacro:include filename="loop_b.xacro"/></robot>'
                ).encode()
                files["parts/loop_b.xacro"] = (
                    f'<robot xmlns:xacro="{XACRO_NS}"><xacro:include filename="loop_a.xacro"/></robot>'
                ).encode()
            tail.append(piece)
            g.hostile = True
    if bombs and g.chance(15):
        tail.append(g.pick(BOMBS))
        g.hostile = True
    if g.chance(80):
        size = g.pick([10**3, 10**5, 2 * 10**6])
        tail.append(
            f'<xacro:property name="long" value="{"y" * size}"/><link name="long_${{len(long)}}"/>'
        )
    return "\n".join(head), "\n".join(tail)


SUPPRESSIONS = (
    "<!-- sensorkit: ignore SK501 -->", "<!-- sensorkit: ignore -->", "<!-- sensorkit:ignore SK9999 -->",
    "<!-- sensorkit: ignore-file SK104 SK105 -->", "<!-- sensorkit: ignore-file -->",
    "<!--sensorkit: IGNORE sk501-->", "<!-- sensorkit: ignore SK2 -->", "<!-- sensorkit: -->",
)  # fmt: skip


def _suppressions(g: Gen, parts: list[str]) -> None:
    """Inline suppression comments between the parts (rarely thousands of them)."""
    if not g.chance(100):
        return
    count = g.pick([20000]) if g.chance(20) else g.int_(1, 4)
    for _ in range(count):
        parts.insert(g.int_(0, len(parts)), g.pick(SUPPRESSIONS))


def _layout(g: Gen, decl: str, comment: str, attrs: str, indent: str, inner: str) -> bytes:
    """The file's bytes, written as people (and editors) write them: newlines, encodings,
    the root's tags spelled oddly, a ``</robot>`` in a comment before the real one."""
    root = "robot"
    if g.chance(10):
        root = "r:robot"
        attrs += ' xmlns:r="urn:robot"'
    start = f"<{root}{attrs}>"
    if g.chance(50):
        start = f"<{root}" + attrs.replace(" ", "\n    ") + "\n>"  # one attribute per line
    end = f"</{root}>"
    if g.chance(50):
        end = g.pick([f"</{root} >", f"</{root}\n>", f"</{root}\t>"])
    before_end = ""
    if g.chance(50):
        before_end = g.pick(
            [
                "<!-- </robot> -->",
                "<![CDATA[</robot>]]>",
                "<?pi </robot>?>",
                "<!-- a\n</robot>\n-->",
            ]
        )
    after = ""
    if g.chance(50):
        after = g.pick(
            ["<!-- trailing -->\n", "<?pi after?>\n", "\n\n\n", "   ", "<!-- </robot> -->"]
        )
    newline = "\n" if not g.chance(100) else g.pick(["\r\n", "\r\n", "\r"])
    last = "\n" if not g.chance(100) else ""
    if g.chance(20) and not inner.strip():
        text = f"{decl}{comment}<{root}{attrs}/>{last}"  # an empty, self-closed root
    else:
        text = f"{decl}{comment}{start}{indent}{inner}{indent}{before_end}\n{end}{last}{after}"
    text = text.replace("\n", newline) if newline != "\n" else text
    enc = "utf-8"
    if g.chance(40):
        enc = g.pick(["utf-16", "utf-16-le", "utf-16-be", "latin-1", "utf-8-sig"])
        if enc in ("latin-1",) or g.chance(500):
            name = {"utf-8-sig": "utf-8", "latin-1": "ISO-8859-1"}.get(enc, enc)
            text = (
                f'<?xml version="1.0" encoding="{name}"?>'
                + newline
                + text.removeprefix(decl.replace("\n", newline))
            )
            if enc == "latin-1":
                text = text.replace("rover", "r\u00f6ver", 1)
    if enc == "utf-16":  # a BOM, as editors write it
        return text.encode("utf-16", "surrogatepass")
    return text.encode(enc, "replace" if enc == "latin-1" else "surrogatepass")


def _damage(g: Gen, data: bytes) -> bytes:
    """Text-level damage: the file no longer is what it was (often not XML at all)."""
    for _ in range(g.int_(1, 3)):
        how = g.int_(0, 11)
        n = len(data)
        at = g.int_(0, n)
        if how == 0:
            data = data[:at]  # truncated
        elif how == 1:
            end = min(n, at + g.int_(1, 40))
            data = data[:at] + data[end:]
        elif how == 2:
            junk = g.pick([b"<", b">", b"&", b'"', b"\x00", b"\x0b", b"]]>", b"<!--", b"</robot>", b"<robot>",
                           b"\xff\xfe", b"\xc3(", b"&nbsp;", b"&#0;", b"&#x110000;", b"<?xml version='1.0'?>"])  # fmt: skip
            data = data[:at] + junk + data[at:]
        elif how == 3:
            end = min(n, at + g.int_(1, 200))
            data = data[:end] + data[at:]  # a slice twice
        elif how == 4:
            data = (
                b'<!DOCTYPE robot [<!ENTITY a "aaaaaaaaaa"><!ENTITY b "&a;&a;&a;&a;">]>\n'
                + data.replace(b"<robot", b"<robot x='&b;'", 1)
            )
        elif how == 5:
            data = b"<!DOCTYPE robot SYSTEM 'http://example.invalid/robot.dtd'>\n" + data
        elif how == 6:
            data = data.replace(b"\n", b"\r\n") if g.chance(500) else data.replace(b"\n", b"\r")
        elif how == 7:
            data = b"\xef\xbb\xbf" + data
        elif how == 8:
            text = data.decode("utf-8", "replace")
            enc = g.pick(["utf-16", "utf-16-le", "latin-1", "cp1252", "utf-32"])
            data = text.encode(enc, "replace")
        elif how == 9:
            depth = g.pick([100, 1000, 10000, 60000])
            data = data.replace(b"</robot>", b"<a>" * depth + b"</a>" * depth + b"</robot>", 1)
        elif how == 10:
            data = data.replace(
                b"<robot", g.pick([b"<sdf", b"<model", b"<Robot", b"<robot:robot"]), 1
            )
        else:
            data = g.pick([b"", b" \n", b"<robot/>", b"<robot name='r'></robot>", b"not xml at all",
                           b"<?xml version='1.0' encoding='bogus'?><robot/>", b"\x00\x01\x02"]) if g.chance(300) else data  # fmt: skip
    return data


@st.composite
def robots(
    draw: st.DrawFn,
    *,
    xacro: bool | None = None,
    hostile: bool = True,
    bombs: bool = False,
    tiny: bool = False,
    max_links: int = 10,
    damage: bool = True,
    package: bool = True,
    rates: tuple[int, ...] = (0, 0, 0, 5, 20, 60, 200, 500),
) -> Case:
    """A robot as files: valid (rate 0), nearly valid, broken or hostile.

    ``bombs`` allows expressions that only a timeout stops (``${10**10**10}``): only for
    callers that pass a short timeout. ``tiny`` keeps cameras and lidars small enough to
    render in milliseconds.
    """
    rnd = _rng(draw)
    rate = rnd.choice(rates)
    is_xacro = rnd.random() < 0.5 if xacro is None else xacro
    g = Gen(rnd, rate, xacro=is_xacro, tiny=tiny)
    if is_xacro and g.chance(500):
        g.props = [f"p{i}" for i in range(g.int_(1, 3))]
    files: dict[str, bytes] = {}
    body = _body(g, max_links)
    name = g.name("rover") if not g.odd() else g.pick(ODD_NAMES)
    ns = ""
    head = tail = ""
    if is_xacro:
        head, tail = _xacro_wrap(g, body, files, hostile=hostile and rate > 0, bombs=bombs)
        ns = (
            f' xmlns:xacro="{XACRO_NS}"'
            if not g.odd(3)
            else g.pick(
                ["", ' xmlns:xacro="urn:wrong"', ' xmlns:xacro="http://ros.org/wiki/xacro"']
            )
        )
    if g.chance(30):
        ns += ' xmlns="http://www.ros.org"'
    decl = (
        '<?xml version="1.0"?>\n'
        if g.chance(800)
        else g.pick(["", '<?xml version="1.0" encoding="utf-8"?>\n'])
    )
    comment = "<!-- generated by sensorkit's fuzz strategies -->\n" if g.chance(300) else ""
    nattr = f" name={g.q(name)}" if not g.odd() else ""
    indent = g.pick(["\n  ", "\n", "\n\t", ""]) if g.chance(500) else "\n  "
    parts = [head, *body.parts, tail]
    _suppressions(g, parts)
    inner = indent.join(x for x in parts if x)
    data = _layout(g, decl, comment, nattr + ns, indent, inner)
    label = "valid" if rate == 0 else "near"
    if damage and rate >= 60 and g.chance(400):
        data = _damage(g, data)
        label = "broken"
    if g.hostile:
        label = "hostile"
    if is_xacro:
        main = (
            g.pick(["robot.urdf.xacro", "robot.xacro", "robot.urdf"])
            if g.chance(200)
            else "robot.urdf.xacro"
        )
    else:
        main = (
            g.pick(["robot.urdf", "robot.xml", "robot", "r\u00f6bot.urdf", "robot.URDF"])
            if g.chance(100)
            else "robot.urdf"
        )
    if package and g.chance(150):
        # inside a ROS package (bridges in config/, $(find) of itself, package:// meshes)
        prefix = "src/robot_pkg/"
        files = {prefix + "urdf/" + k: v for k, v in files.items()}
        files[prefix + "package.xml"] = b"<package format='3'><name>robot_pkg</name></package>"
        files[prefix + "meshes/base.stl"] = b"solid x\nendsolid x\n"
        if g.chance(500):
            files[prefix + "config/bridge.yaml"] = _bridge_yaml(g)
        main = prefix + "urdf/" + main
    files[main] = data
    args: dict[str, str] = {}
    if is_xacro and g.chance(200):
        args = {
            g.pick(["prefix", "undefined", "a1", ""]): g.pick(["x_", "", "${1/0}", "$(arg prefix)"])
        }
    return Case(
        files=files, main=main, args=args, label=label, links=body.links, sensors=body.sensors
    )


def _bridge_yaml(g: Gen) -> bytes:
    kind = g.int_(0, 6)
    if kind <= 2:
        entries = "".join(
            f"- ros_topic_name: {g.topic() or 'none'}\n  gz_topic_name: {g.topic() or 'x'}\n"
            f"  ros_type_name: sensor_msgs/msg/{g.pick(['Image', 'LaserScan', 'Imu', 'CameraInfo'])}\n"
            f"  gz_type_name: gz.msgs.{g.pick(['Image', 'LaserScan', 'IMU'])}\n"
            f"  direction: {g.pick(['GZ_TO_ROS', 'ROS_TO_GZ', 'BIDIRECTIONAL', 'sideways'])}\n"
            for _ in range(g.int_(0, 4))
        )
        return entries.encode()
    if kind == 3:
        depth = g.pick([10, 500, 5000, 100000])
        return b"- " + b"[" * depth + b"]" * depth + b"\n"
    if kind == 4:
        return b"a: &a [x, y]\nb: &b [*a, *a, *a]\nc: [*b, *b, *b]\n"
    if kind == 5:
        return g.pick(
            [
                b"",
                b"- 1\n- 2\n",
                b"{",
                b"\xff\xfe\x00",
                b"- {gz_topic_name: !!python/object:os.system x}\n",
            ]
        )
    return b"- topic_name: " + b"x" * g.pick([10, 2 * 1024 * 1024]) + b"\n"


# ---------------------------------------------------------------------- command knobs


@st.composite
def validate_knobs(draw: st.DrawFn) -> dict[str, Any]:
    """Options for validate: target, select/ignore, fail-on, output format."""
    return {
        "target": draw(st.sampled_from(TARGETS)),
        "select": draw(
            st.lists(
                st.sampled_from(["SK1", "SK2", "SK4", "SK5", "SK6", "SK104", "SK501"]), max_size=2
            )
        ),
        "ignore": draw(st.lists(st.sampled_from(["SK1", "SK3", "SK6", "SK105"]), max_size=1)),
        "fail_on": draw(st.sampled_from(["error", "warning", "info"])),
        "format": draw(st.sampled_from(["text", "json", "sarif", "github"])),
        "untrusted": draw(st.integers(0, 9)) < 3,  # issue 36: a share under --untrusted
    }


def _add_value(g: Gen, param: str) -> str:
    if g.odd(3):
        return str(
            g.pick(
                [*ODD_NUMBERS[:30], "${1}", "$(arg x)", '"', "<", "&", "\u00fc", "x" * 5000, "a\nb"]
            )
        )
    if param == "sim":
        return str(g.pick(["classic", "gz", "none"]))
    if param == "gz_version":
        return str(g.pick(["fortress", "harmonic", "jetty"]))
    if param == "namespace":
        return str(
            g.pick(["", "robot1", "/robot1/sensors", "r2/", "_ns", "a//b", "1x", "my robot"])
        )
    if param == "format":
        return str(g.pick(FORMATS))
    if param == "size":
        return g.vec(3, 0.01, 0.2)
    if param in ("width", "height", "samples", "vertical_samples"):
        return g.num(1, 2000, integer=True)
    return g.num(0.001, 100.0)


@st.composite
def add_knobs(draw: st.DrawFn, case: Case) -> dict[str, Any]:
    """An add-* request for ``case``: kind, name, parent, mount, macro parameters."""
    from sensorkit.edit.kinds import read_macro, shipped_macro

    rnd = _rng(draw)
    g = Gen(rnd, rnd.choice([0, 0, 30, 200]))
    kind = g.pick(sorted(KINDS))
    taken = [*case.links, *case.sensors]
    if g.odd(3) and taken:
        name = g.pick(taken)
    elif g.odd():
        name = g.pick([*ODD_NAMES, "base", "a" * 200, "Cam", "x1"])
    else:
        name = g.pick(
            ["fuzz_cam", "front_cam2", "new_lidar", "imu0", "rgbd1", "pair", "new_sensor"]
        )
    if case.links and not g.odd(3):
        parent = g.pick(case.links)
    else:
        parent = g.pick([*ODD_NAMES[:12], "base_link", "nonexistent"])
    mount: list[list[float]] = []
    for lo, hi in ((-2.0, 2.0), (-3.2, 3.2)):
        vals = []
        for _ in range(3):
            if g.odd():
                vals.append(
                    float(g.pick([float("nan"), float("inf"), -float("inf"), 1e308, -0.0, 5e-324]))
                )
            else:
                vals.append(g.rnd.uniform(lo, hi) if not g.chance(50) else g.pick([0.0, lo, hi]))
        mount.append(vals)
    info = read_macro(shipped_macro(KINDS[kind]), KINDS[kind].macro_name)
    pnames = [p.name for p in info.params if p.name not in ("name", "parent")] if info else []
    params = {}
    for p in g.rnd.sample(pnames, min(len(pnames), g.int_(0, 4))):
        params[p] = _add_value(g, p)
    if g.odd():
        params[g.pick(["bogus", "name", "parent", "origin", ""])] = "1"
    return {
        "kind": kind,
        "name": name,
        "parent": parent,
        "xyz": mount[0],
        "rpy": mount[1],
        "params": params,
        "output": g.chance(100),
        "dry_run": g.chance(100),
    }


@st.composite
def intrinsics_knobs(draw: st.DrawFn, case: Case) -> dict[str, Any]:
    fmt = draw(
        st.sampled_from(
            ["json", "camera-info", "orbslam3", "orbslam3-v1", "kalibr", "opencv", "bogus"]
        )
    )
    sensor = draw(st.one_of(st.none(), st.sampled_from([*case.sensors, "nope", "a/b"])))
    return {
        "format": fmt,
        "sensor": sensor,
        "convention": draw(st.sampled_from([None, "classic", "gz", "ideal"])),
        "target": draw(st.sampled_from(TARGETS)),
    }


@st.composite
def export_knobs(draw: st.DrawFn) -> dict[str, Any]:
    rnd = _rng(draw)
    return {
        "target": rnd.choice(TARGETS),
        "force": rnd.random() < 0.5,
        "existing": rnd.random() < 0.2,  # --out already holds a file
    }


@st.composite
def pyprojects(draw: st.DrawFn) -> str | None:
    """A pyproject.toml the CLI may find in its working folder ([tool.sensorkit]).

    Text with undecodable bytes kept as surrogates (``surrogateescape``), so it is JSON-able.
    """
    rnd = _rng(draw)
    if rnd.random() < 0.6:
        return None
    data: bytes = rnd.choice([
        b'[tool.sensorkit]\ntarget = "harmonic"\nselect = ["SK5"]\n',
        b'[tool.sensorkit]\ntarget = "bogus"\n',
        b'[tool.sensorkit]\nfail-on = "nope"\n',
        b'[tool.sensorkit]\nselect = "SK999"\n',
        b'[tool.sensorkit]\nargs = { prefix = "x_", n = 3 }\n',
        b'[tool.sensorkit]\npackage-path = ["src", "robot_pkg=src/robot_pkg"]\n',
        b"[tool.sensorkit]\nunknown = 1\n",
        b"[tool]\nsensorkit = 3\n",
        b"tool = 1\n",
        b"tool = [1, 2]\n",
        b"[tool.sensorkit]\nselect = [1, 2]\n",
        b"[tool.sensorkit]\nargs = [1]\n",
        b"[tool.sensorkit\n",
        b"\xff\xfe",
        b"[tool.sensorkit]\ntarget = 3\n",
        b"[tool.sensorkit]\npackage-path = [\"\"]\n",
    ])  # fmt: skip
    return data.decode("utf-8", "surrogateescape")


def _macro_beside(rnd: random.Random, case: Case, kind: str) -> None:
    """Something already at ``sensors/<macro file>`` beside the robot: sensorkit's own
    copy, a user's modified copy, a file that defines no such macro, or a folder."""
    from sensorkit.edit.kinds import shipped_macro

    folder = str(Path(case.main).parent)
    rel = ("" if folder == "." else folder + "/") + "sensors/" + KINDS[kind].macro_file
    shipped = shipped_macro(KINDS[kind]).read_bytes()
    how = rnd.randrange(6)
    if how == 0:
        case.files[rel] = shipped
    elif how == 1:
        case.files[rel] = shipped.replace(b"update_rate:=", b"update_rate:=1", 1)  # modified copy
    elif how == 2:
        case.files[rel] = b'<robot xmlns:xacro="http://www.ros.org/wiki/xacro"/>'
    elif how == 3:
        case.files[rel] = b"not xml <<<"
    elif how == 4:
        case.files[rel + "/inside"] = b"a folder where the macro file would go"
    else:
        case.files[rel] = shipped.replace(b'params="', b'params="extra_required ', 1)


CLI_SHARE = 200  # per mille of intrinsics/export/render inputs also run through the CLI


@st.composite
def fuzz_inputs(draw: st.DrawFn, target: str) -> FuzzInput:
    """A whole input for ``target`` (a key of ``fuzz_targets.TARGETS``)."""
    if target in ("validate", "validate_paths", "cli_validate"):
        case = draw(robots(bombs=True))
        knobs = draw(validate_knobs())
        rnd = _rng(draw)
        if rnd.random() < 0.05:  # --bridge FILE (a bad one is a usage error, exit 2)
            knobs["bridge"] = _bridge_yaml(Gen(rnd, 100)).decode("utf-8", "surrogateescape")
        if target == "cli_validate":
            knobs["pyproject"] = draw(pyprojects())
        return FuzzInput(target, case, knobs)
    if target in ("add", "cli_add"):
        case = draw(robots(rates=(0, 0, 0, 0, 5, 20, 60, 200)))
        knobs = draw(add_knobs(case))
        rnd = _rng(draw)
        if rnd.random() < 0.08:
            _macro_beside(rnd, case, knobs["kind"])
        return FuzzInput(target, case, knobs)
    if target == "intrinsics":
        case = draw(robots())
        knobs = draw(intrinsics_knobs(case))
        knobs["cli"] = _rng(draw).randrange(1000) < CLI_SHARE
        return FuzzInput(target, case, knobs)
    if target == "export":
        case = draw(robots())
        knobs = draw(export_knobs())
        knobs["cli"] = _rng(draw).randrange(1000) < CLI_SHARE
        return FuzzInput(target, case, knobs)
    if target == "render":
        case = draw(robots(tiny=True, max_links=6, rates=(0, 0, 0, 0, 5, 20, 60)))
        rnd = _rng(draw)
        knobs: dict[str, Any] = {"target": rnd.choice(TARGETS), "cli": rnd.random() < 0.3}
        if case.sensors and rnd.random() < 0.2:
            knobs["sensors"] = rnd.sample([*case.sensors, "nope"], 1)
        if case.links and rnd.random() < 0.2:
            value = rnd.choice(["0.5", "-1", "nan", "inf", "1e308", "x", ""])
            knobs["joints"] = {rnd.choice([*case.links, "nope"]) + "_joint": value}
        return FuzzInput(target, case, knobs)
    if target == "cli_subprocess":
        case = draw(robots(tiny=True))
        command = draw(st.sampled_from(["validate", "add", "intrinsics", "export", "render"]))
        knobs = draw(add_knobs(case)) if command == "add" else {}
        knobs.update(
            command=command,
            pyproject=draw(pyprojects()),
            format=draw(st.sampled_from(["text", "json", "sarif", "github"])),
        )
        return FuzzInput(target, case, knobs)
    msg = f"no fuzz target {target!r}"
    raise ValueError(msg)


__all__ = [
    "Case",
    "FuzzInput",
    "add_knobs",
    "export_knobs",
    "fuzz_inputs",
    "intrinsics_knobs",
    "pyprojects",
    "robots",
    "validate_knobs",
]
