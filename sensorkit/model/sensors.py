"""Sensors and plugins as written in ``<gazebo>`` extensions, in Classic and Sim forms."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from lxml import etree

from sensorkit.base.findings import SourceRef
from sensorkit.model.parse import Origin, child, children, local, parse_float, parse_vec, text_of

Locate = Callable[[etree._Element], SourceRef]  # where an element was written

CAMERA_TYPES = {
    "camera": "camera",
    "depth": "depth",
    "depth_camera": "depth",
    "rgbd_camera": "rgbd",
    "rgbd": "rgbd",
    "multicamera": "multicamera",
    "wideanglecamera": "camera",
    "wide_angle_camera": "camera",
    "thermal_camera": "camera",
    "thermal": "camera",
    "segmentation_camera": "camera",
    "segmentation": "camera",
    "boundingbox_camera": "camera",
    "boundingbox": "camera",  # sdformat reads both names (sdf14 8512585:src/Sensor.cc:322-324)
}
LIDAR_TYPES = {"ray", "gpu_ray", "lidar", "gpu_lidar"}
DEPTH_KINDS = {"depth", "rgbd"}


@dataclass
class Noise:
    """A ``<noise>`` block as written."""

    type: str | None
    mean: float | None
    stddev: float | None
    source: SourceRef
    problems: list[str] = field(default_factory=list)


@dataclass
class CameraSpec:
    """One ``<camera>`` block: image, fov, clip, lens and distortion as written."""

    element: etree._Element
    source: SourceRef
    name: str | None
    width: int | None = None
    height: int | None = None
    format: str | None = None
    hfov: float | None = None
    near: float | None = None
    far: float | None = None
    depth_near: float | None = None  # gz <depth_camera><clip>
    depth_far: float | None = None
    lens_intrinsics: tuple[float, float, float, float, float] | None = None
    lens_projection: dict[str, float] = field(default_factory=dict)  # p_fx.. tx ty as written
    lens_intrinsics_given: dict[str, float] = field(default_factory=dict)  # fx.. s as written
    # each <lens> block written ("intrinsics", "projection") and the tags it leaves out
    lens_left_out: dict[str, tuple[str, ...]] = field(default_factory=dict)
    distortion: dict[str, float] = field(default_factory=dict)
    noise: Noise | None = None
    pose: Origin | None = None  # multicamera: each camera's own pose
    optical_frame_id: str | None = None
    camera_info_topic: str | None = None
    raw: dict[str, str | None] = field(default_factory=dict)
    problems: list[str] = field(default_factory=list)


@dataclass
class LidarSpec:
    """One ``<ray>`` or ``<lidar>`` block: horizontal and vertical scan, range, as written."""

    element: etree._Element
    source: SourceRef
    samples: int | None = None
    resolution: float | None = None
    min_angle: float | None = None
    max_angle: float | None = None
    v_samples: int | None = None
    v_resolution: float | None = None
    v_min_angle: float | None = None
    v_max_angle: float | None = None
    has_vertical: bool = False
    range_min: float | None = None
    range_max: float | None = None
    range_resolution: float | None = None
    noise: Noise | None = None
    raw: dict[str, str | None] = field(default_factory=dict)
    problems: list[str] = field(default_factory=list)


@dataclass
class Plugin:
    """A ``<plugin>``; ``params`` maps child tag -> elements (order kept)."""

    filename: str
    name: str
    element: etree._Element
    source: SourceRef
    sensor: Sensor | None = None

    @property
    def library(self) -> str:
        """The library's base name: ``libgazebo_ros_camera.so`` -> ``gazebo_ros_camera``."""
        base = self.filename.rsplit("/", 1)[-1]
        if base.startswith("lib"):
            base = base[3:]
        if base.endswith(".so"):
            base = base[:-3]
        return base

    def param(self, name: str) -> str | None:
        return text_of(self.element, name)

    def param_elements(self) -> list[etree._Element]:
        return [c for c in self.element if local(c)]

    def ros_block(self) -> etree._Element | None:
        return child(self.element, "ros")

    def namespace(self) -> str:
        return text_of(self.element, "ros", "namespace") or ""

    def remappings(self) -> list[tuple[str, str, etree._Element]]:
        """``<ros><remapping>from:=to</remapping>`` pairs (also ``--remap``/``-r`` args)."""
        out: list[tuple[str, str, etree._Element]] = []
        ros = self.ros_block()
        if ros is None:
            return out
        for el in children(ros, "remapping"):
            text = (el.text or "").strip()
            for prefix in ("--remap ", "-r "):
                if text.startswith(prefix):
                    text = text[len(prefix) :].strip()
            if ":=" in text:
                src, dst = text.split(":=", 1)
                out.append((src.strip(), dst.strip(), el))
        return out


@dataclass
class Sensor:
    """A ``<sensor>`` in a ``<gazebo reference="...">`` block."""

    name: str
    type: str
    kind: str  # camera | depth | rgbd | multicamera | lidar | imu | other
    reference: str | None
    element: etree._Element
    block: etree._Element
    source: SourceRef
    pose: Origin
    update_rate: float | None = None
    update_rate_text: str | None = None
    always_on: str | None = None
    topic: str | None = None
    frame_tags: dict[str, str] = field(default_factory=dict)  # gz_frame_id, ... (sensor level)
    misplaced_frame_tags: list[tuple[str, str, etree._Element]] = field(default_factory=list)
    cameras: list[CameraSpec] = field(default_factory=list)
    lidar: LidarSpec | None = None
    imu_noise: list[Noise] = field(default_factory=list)
    plugins: list[Plugin] = field(default_factory=list)
    problems: list[str] = field(default_factory=list)

    @property
    def is_camera(self) -> bool:
        return self.kind in ("camera", "depth", "rgbd", "multicamera")

    @property
    def is_depth(self) -> bool:
        return self.kind in DEPTH_KINDS

    @property
    def camera(self) -> CameraSpec | None:
        return self.cameras[0] if self.cameras else None


def _int(text: str | None, what: str, problems: list[str]) -> int | None:
    if text is None:
        return None
    value, why = parse_float(text)
    if why or value is None:
        problems.append(f"{what} {why}")
        return None
    if value != int(value):
        problems.append(f"{what} {text!r} is not a whole number")
        return None
    return int(value)


def _num(text: str | None, what: str, problems: list[str]) -> float | None:
    if text is None:
        return None
    value, why = parse_float(text)
    if why:
        problems.append(f"{what} {why}")
    return value


def read_noise(el: etree._Element | None, locate: Locate) -> Noise | None:
    if el is None:
        return None
    problems: list[str] = []
    ntype = el.get("type") or text_of(el, "type")
    mean = _num(text_of(el, "mean"), "noise mean", problems)
    stddev = _num(text_of(el, "stddev"), "noise stddev", problems)
    src = locate(el)
    return Noise(ntype, mean, stddev, src, problems)


def read_camera(el: etree._Element, locate: Locate) -> CameraSpec:
    src = locate(el)
    cam = CameraSpec(element=el, source=src, name=el.get("name"))
    p = cam.problems
    cam.raw = {
        "horizontal_fov": text_of(el, "horizontal_fov"),
        "width": text_of(el, "image", "width"),
        "height": text_of(el, "image", "height"),
        "format": text_of(el, "image", "format"),
        "near": text_of(el, "clip", "near"),
        "far": text_of(el, "clip", "far"),
    }
    cam.hfov = _num(cam.raw["horizontal_fov"], "horizontal_fov", p)
    cam.width = _int(cam.raw["width"], "image width", p)
    cam.height = _int(cam.raw["height"], "image height", p)
    cam.format = cam.raw["format"]
    cam.near = _num(cam.raw["near"], "clip near", p)
    cam.far = _num(cam.raw["far"], "clip far", p)
    cam.depth_near = _num(text_of(el, "depth_camera", "clip", "near"), "depth clip near", p)
    cam.depth_far = _num(text_of(el, "depth_camera", "clip", "far"), "depth clip far", p)
    intr = child(child(el, "lens"), "intrinsics")
    if intr is not None:
        vals = [
            _num(text_of(intr, k), f"lens intrinsics {k}", p) for k in ("fx", "fy", "cx", "cy", "s")
        ]
        tags = ("fx", "fy", "cx", "cy", "s")
        cam.lens_left_out["intrinsics"] = tuple(t for t in tags if child(intr, t) is None)
        cam.lens_intrinsics_given = {
            t: float(v) for t, v in zip(tags, vals, strict=True) if v is not None
        }
        if all(v is not None for v in vals[:4]):
            fx, fy, cx, cy = (float(v) for v in vals[:4])  # type: ignore[arg-type]
            cam.lens_intrinsics = (fx, fy, cx, cy, float(vals[4] or 0.0))
    proj = child(child(el, "lens"), "projection")
    if proj is not None:
        cam.lens_left_out["projection"] = tuple(
            t for t in ("p_fx", "p_fy", "p_cx", "p_cy", "tx", "ty") if child(proj, t) is None
        )
        for tag, key in (
            ("p_fx", "fx"),
            ("p_fy", "fy"),
            ("p_cx", "cx"),
            ("p_cy", "cy"),
            ("tx", "tx"),
            ("ty", "ty"),
        ):
            v = _num(text_of(proj, tag), f"lens projection {tag}", p)
            if v is not None:
                cam.lens_projection[key] = v
    dist = child(el, "distortion")
    if dist is not None:
        for k in ("k1", "k2", "k3", "p1", "p2"):
            v = _num(text_of(dist, k), f"distortion {k}", p)
            if v is not None:
                cam.distortion[k] = v
    cam.noise = read_noise(child(el, "noise"), locate)
    pose_el = child(el, "pose")
    if pose_el is not None:
        cam.pose = _sdf_pose(pose_el, locate)
    cam.optical_frame_id = text_of(el, "optical_frame_id")
    cam.camera_info_topic = text_of(el, "camera_info_topic")
    return cam


def read_lidar(el: etree._Element, locate: Locate) -> LidarSpec:
    src = locate(el)
    spec = LidarSpec(element=el, source=src)
    p = spec.problems
    h = child(child(el, "scan"), "horizontal")
    v = child(child(el, "scan"), "vertical")
    spec.raw = {
        "samples": text_of(h, "samples"),
        "min_angle": text_of(h, "min_angle"),
        "max_angle": text_of(h, "max_angle"),
        "resolution": text_of(h, "resolution"),
        "range_min": text_of(el, "range", "min"),
        "range_max": text_of(el, "range", "max"),
    }
    spec.samples = _int(spec.raw["samples"], "horizontal samples", p)
    spec.resolution = _num(spec.raw["resolution"], "horizontal resolution", p)
    spec.min_angle = _num(spec.raw["min_angle"], "horizontal min_angle", p)
    spec.max_angle = _num(spec.raw["max_angle"], "horizontal max_angle", p)
    if v is not None:
        spec.has_vertical = True
        spec.raw["v_samples"] = text_of(v, "samples")
        spec.v_samples = _int(spec.raw["v_samples"], "vertical samples", p)
        spec.v_resolution = _num(text_of(v, "resolution"), "vertical resolution", p)
        spec.v_min_angle = _num(text_of(v, "min_angle"), "vertical min_angle", p)
        spec.v_max_angle = _num(text_of(v, "max_angle"), "vertical max_angle", p)
    spec.range_min = _num(spec.raw["range_min"], "range min", p)
    spec.range_max = _num(spec.raw["range_max"], "range max", p)
    spec.range_resolution = _num(text_of(el, "range", "resolution"), "range resolution", p)
    spec.noise = read_noise(child(el, "noise"), locate)
    return spec


def _sdf_pose(el: etree._Element, locate: Locate) -> Origin:
    """An SDF ``<pose>x y z r p y</pose>`` as an Origin."""
    src = locate(el)
    out = Origin(source=src)
    text = (el.text or "").strip()
    if not text:
        return out
    vals, why = parse_vec(text, 6)
    if why or vals is None:
        out.problems = (f"pose {why}",)
        return out
    out.xyz = (vals[0], vals[1], vals[2])
    out.rpy = (vals[3], vals[4], vals[5])
    out.rpy_text = " ".join(text.split()[3:])
    return out


FRAME_TAGS = ("gz_frame_id", "ignition_frame_id", "frame_id")


def read_sensor(
    el: etree._Element, block: etree._Element, reference: str | None, locate: Locate
) -> Sensor:
    stype = el.get("type", "")
    if stype in CAMERA_TYPES:
        kind = CAMERA_TYPES[stype]
    elif stype in LIDAR_TYPES:
        kind = "lidar"
    elif stype == "imu":
        kind = "imu"
    else:
        kind = "other"
    pose_el = child(el, "pose")
    sensor = Sensor(
        name=el.get("name", ""),
        type=stype,
        kind=kind,
        reference=reference,
        element=el,
        block=block,
        source=locate(el),
        pose=_sdf_pose(pose_el, locate) if pose_el is not None else Origin(source=locate(el)),
    )
    sensor.update_rate_text = text_of(el, "update_rate")
    sensor.update_rate = _num(sensor.update_rate_text, "update_rate", sensor.problems)
    sensor.always_on = text_of(el, "always_on")
    sensor.topic = text_of(el, "topic")
    for tag in FRAME_TAGS:
        value = text_of(el, tag)
        if value is not None:
            sensor.frame_tags[tag] = value
    for cam_el in children(el, "camera"):
        sensor.cameras.append(read_camera(cam_el, locate))
        for tag in FRAME_TAGS:
            for bad in children(cam_el, tag):
                sensor.misplaced_frame_tags.append((tag, (bad.text or "").strip(), bad))
    lidar_el = child(el, "lidar") if child(el, "lidar") is not None else child(el, "ray")
    if kind == "lidar" and lidar_el is not None:
        sensor.lidar = read_lidar(lidar_el, locate)
    if kind == "imu":
        imu_el = child(el, "imu")
        if imu_el is not None:
            for noise_el in imu_el.iter("{*}noise", "noise"):
                n = read_noise(noise_el, locate)
                if n is not None:
                    sensor.imu_noise.append(n)
    for pl in children(el, "plugin"):
        plugin = Plugin(pl.get("filename", ""), pl.get("name", ""), pl, locate(pl), sensor)
        sensor.plugins.append(plugin)
    return sensor

