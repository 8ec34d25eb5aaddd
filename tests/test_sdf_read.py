"""Reading SDF into the model (issue 28): every link's and sensor's pose agrees with
libsdformat's own (tests/tools/sdf_poses.cc, SemanticPose().Resolve) within 1e-9 m and
1e-9 rad, on every SDF file in tests/robots/sdf and on the corpus's turtlebot3 model.sdf
files; and what the reader keeps beside the poses."""

from __future__ import annotations

import math
import os
import re
import subprocess
from pathlib import Path

import pytest
from conftest import CORPUS, REALWORLD, sdformat_tool

from sensorkit.base.errors import InputError
from sensorkit.model import load_robot
from sensorkit.model.transforms import Pose, compose

HERE = Path(__file__).resolve().parent
SDF_DIR = HERE / "robots" / "sdf"
MODELS = SDF_DIR / "models"
TOOL_SOURCE = HERE / "tools" / "sdf_poses.cc"
# Every SDF robot of ../shared/corpus (its real-world set too, where the wanted SDF robots
# land): .sdf files and .sdf.xacro ones (expanded by xacro for libsdformat)
CORPUS_SDF = (
    sorted(p for p in CORPUS.rglob("*") if p.name.endswith((".sdf", ".sdf.xacro")) and p.is_file())
    if CORPUS.is_dir()
    else []
)
OWN_SDF = sorted(SDF_DIR.glob("*.sdf"))


def _resources(path: Path) -> str:
    """Where a file's includes are looked up (GZ_SIM_RESOURCE_PATH, SDF_PATH): the tests'
    models folder; for a corpus file, the folder of its model folder and its repository's
    root (a package:// include is PKG/REST there)."""
    if not path.is_relative_to(CORPUS):
        return str(MODELS)
    rel = path.relative_to(CORPUS).parts
    depth = 2 if rel[0] == REALWORLD.name else 1
    return os.pathsep.join([str(path.parent.parent), str(CORPUS.joinpath(*rel[:depth]))])

Key = tuple[str, str, str, str]  # (LINK|SENSOR, model, model|world, scoped name)


@pytest.fixture(scope="module")
def sdf_poses(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return sdformat_tool(tmp_path_factory, TOOL_SOURCE)


def _for_libsdformat12(path: Path, tmp: Path) -> Path:
    """``path``, or a copy declaring SDF 1.9 when it declares 1.10 or 1.11: libsdformat 12
    reads SDF up to 1.9, and what poses mean is the same in 1.10 and 1.11 (their
    pose.sdf, frame.sdf, link.sdf and model.sdf equal 1.9's, and 1_9.convert and
    1_10.convert change nothing: gazebosim/sdformat@sdformat14_14.9.0:sdf/1.11)."""
    if path.name.endswith(".sdf.xacro"):  # libsdformat reads the expansion
        import xacro

        expanded = tmp / path.name.removesuffix(".xacro")
        expanded.write_text(xacro.process_file(str(path)).toxml())
        path = expanded
    text = path.read_text()
    for newer in ('version="1.10"', 'version="1.11"'):
        if f"<sdf {newer}" in text:
            copy = tmp / path.name
            copy.write_text(text.replace(f"<sdf {newer}", '<sdf version="1.9"', 1))
            return copy
    return path


def _tool(exe: Path, path: Path, resources: Path | str = MODELS) -> dict[Key, Pose]:
    # gz-sim copies GZ_SIM_RESOURCE_PATH into SDF_PATH, where libsdformat looks up a bare
    # include URI such as <uri>sk_merge_mast</uri> (gazebosim/gz-sim@gz-sim8_8.9.0:
    # src/Util.cc:486-540; gazebosim/sdformat@sdformat12_12.8.0:src/SDF.cc:119-137)
    env = {**os.environ, "GZ_SIM_RESOURCE_PATH": str(resources), "SDF_PATH": str(resources)}
    res = subprocess.run(
        [str(exe), str(path)], capture_output=True, text=True, timeout=60, check=False, env=env
    )
    errors = [line for line in res.stdout.splitlines() if line.startswith("ERROR")]
    assert res.returncode == 0 and not errors, errors or res.stderr
    out: dict[Key, Pose] = {}
    for line in res.stdout.splitlines():
        if line.startswith("MASS"):
            continue
        kind, model, frame, name, *nums = line.split()
        v = [float(n) for n in nums]
        out[(kind, model, frame, name)] = (*v[3:12], v[0], v[1], v[2])  # type: ignore[assignment]
    return out


def _ours(path: Path, resources: str = str(MODELS)) -> dict[Key, Pose]:
    old = os.environ.get("GZ_SIM_RESOURCE_PATH")
    os.environ["GZ_SIM_RESOURCE_PATH"] = resources
    try:
        loaded = load_robot(path, sdf=True)
    finally:
        if old is None:
            del os.environ["GZ_SIM_RESOURCE_PATH"]
        else:
            os.environ["GZ_SIM_RESOURCE_PATH"] = old
    assert not loaded.findings, loaded.findings
    out: dict[Key, Pose] = {}
    for robot in loaded.robots:
        sm = robot.sdf
        assert sm is not None
        frames = (
            [("model", None)]
            if sm.world_pose is None
            else [("model", None), ("world", sm.world_pose)]
        )
        for frame, base in frames:
            for link in robot.links:
                p = sm.pose_of(link.name)
                assert p is not None, link.name
                out[("LINK", robot.name, frame, link.name)] = (
                    p if base is None else compose(base, p)
                )
            for s in robot.sensors:
                assert s.reference is not None
                lp = sm.pose_of(s.reference)
                assert lp is not None
                p = compose(lp, s.pose.pose())
                out[("SENSOR", robot.name, frame, f"{s.reference}::{s.name}")] = (
                    p if base is None else compose(base, p)
                )
    return out


def _skip_if_only_fuel(path: Path) -> None:
    """A corpus world whose models all come from Fuel (https://) has nothing either side
    can read offline (subt's worlds/example.sdf): libsdformat cannot find them, nor can we."""
    text = path.read_text()
    uris = re.findall(r"<uri>\s*([^<]*?)\s*</uri>", text)
    if "<model" not in text and uris and all(u.startswith("https://") for u in uris):
        pytest.skip(f"{path.name}: every model is a Fuel include, not read offline")


def _angle(a: Pose, b: Pose) -> float:
    """Angle of Ra^T Rb, accurate near zero (atan2 of its skew part and its trace)."""
    m = [[sum(a[3 * k + i] * b[3 * k + j] for k in range(3)) for j in range(3)] for i in range(3)]
    s = math.hypot(m[2][1] - m[1][2], m[0][2] - m[2][0], m[1][0] - m[0][1]) / 2.0
    c = (m[0][0] + m[1][1] + m[2][2] - 1.0) / 2.0
    return math.atan2(s, c)


@pytest.mark.parametrize("path", OWN_SDF + CORPUS_SDF, ids=lambda p: p.name)
def test_poses_agree_with_libsdformat(sdf_poses: Path, path: Path, tmp_path: Path) -> None:
    _skip_if_only_fuel(path)
    theirs = _tool(sdf_poses, _for_libsdformat12(path, tmp_path), _resources(path))
    ours = _ours(path, _resources(path))
    assert theirs, "libsdformat printed no pose"
    assert sorted(ours) == sorted(theirs)
    for key, p in theirs.items():
        q = ours[key]
        assert math.dist(p[9:], q[9:]) <= 1e-9, (key, p[9:], q[9:])
        assert _angle(p, q) <= 1e-9, (key, _angle(p, q))


def test_a_package_include_merged_in_a_world_agrees_with_libsdformat(sdf_poses: Path) -> None:
    # ros_gz_project_template's layout: a world's model merges package://PKG/models/NAME;
    # libsdformat finds it as FOLDER/PKG/models/NAME in SDF_PATH, we in the workspace
    ws = SDF_DIR / "input" / "ws"
    theirs = _tool(sdf_poses, ws / "sk_sdf_world" / "worlds" / "yard.sdf", ws)
    ours = _ours(ws / "sk_sdf_world" / "worlds" / "yard.sdf")
    assert sorted(ours) == sorted(theirs) and len(theirs) == 4
    for key, p in theirs.items():
        assert math.dist(p[9:], ours[key][9:]) <= 1e-9 and _angle(p, ours[key]) <= 1e-9


def test_the_suite_holds_the_cases_the_check_needs() -> None:
    names = {p.stem for p in OWN_SDF}
    assert {
        "plain_links",
        "v16_model",
        "relative_frame",
        "relative_link",
        "frame_chain",
        "nested",
        "joint_relative",
        "sensor_relative",
        "include",
        "merged",
        "world",
        "v111_model",
        "placement",
    } <= names


def _load(path: Path, monkeypatch: pytest.MonkeyPatch) -> list:  # type: ignore[type-arg]
    monkeypatch.setenv("GZ_SIM_RESOURCE_PATH", str(MODELS))
    loaded = load_robot(path, sdf=True)
    assert not loaded.findings
    return loaded.robots


def test_a_joint_origin_is_the_child_link_in_the_parent_link(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    (robot,) = _load(SDF_DIR / "joint_relative.sdf", monkeypatch)
    sm = robot.sdf
    for name in ("elbow", "wrist"):
        joint = robot.joint_map[name]
        want = compose(sm.pose_of(joint.parent), joint.origin.pose())
        assert math.dist(want[9:], sm.pose_of(joint.child)[9:]) < 1e-12
        assert _angle(want, sm.pose_of(joint.child)) < 1e-12
    # the Robot's world poses are in the root link's frame, composed from those origins
    hand = robot.world_pose("hand")
    want = compose(_inverse(sm.pose_of("base")), sm.pose_of("hand"))
    assert math.dist(hand[9:], want[9:]) < 1e-12
    # a joint whose parent is a frame hangs from the link the frame is attached to
    clip = robot.joint_map["clip_joint"]
    assert (clip.parent, clip.child) == ("hand", "clip")
    # the joint's own frame is kept beside: elbow is 0.2 0.1 0.4 from base
    elbow_in_base = compose(_inverse(sm.pose_of("base")), sm.pose_of("elbow"))
    assert elbow_in_base[9:] == pytest.approx((0.2, 0.1, 0.4))


def _inverse(p: Pose) -> Pose:
    from sensorkit.model.sdf_frames import inverse

    return inverse(p)


def test_axes_are_in_the_child_link_frame(monkeypatch: pytest.MonkeyPatch) -> None:
    (robot,) = _load(SDF_DIR / "relative_link.sdf", monkeypatch)
    # wheel is rolled -pi/2 from base; the axis is written as base's y: the wheel's z
    assert robot.joint_map["axle"].axis == pytest.approx((0.0, 0.0, 1.0))
    (old,) = _load(SDF_DIR / "v16_model.sdf", monkeypatch)
    # 1.6 use_parent_model_frame: y of the model, in head's frame (rolled, pitched, yawed)
    sm = old.sdf
    R = sm.pose_of("head")
    want = (R[3], R[4], R[5])  # the model's y seen from head: R^T e_y, row 1 of R
    assert old.joint_map["neck"].axis == pytest.approx(want)


def test_nested_names_are_scoped_and_sensors_keep_their_tags(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    (nested,) = _load(SDF_DIR / "nested.sdf", monkeypatch)
    assert [lk.name for lk in nested.links] == [
        "base",
        "inner::arm",
        "inner::deep::finger",
        "sensor_mount",
        "tipped",
    ]
    assert nested.joint_map["to_inner"].child == "inner::arm"
    assert set(nested.sdf.models) == {"inner", "inner::deep"}
    (robot,) = _load(SDF_DIR / "sensor_relative.sdf", monkeypatch)
    by_name = {s.name: s for s in robot.sensors}
    assert {s.reference for s in robot.sensors} == {"head"}
    cam = by_name["front_cam"]
    assert cam.kind == "camera" and cam.topic == "front/image"
    assert cam.camera is not None and cam.camera.optical_frame_id == "front_optical"
    assert by_name["lidar"].lidar is not None and by_name["lidar"].lidar.samples == 360
    assert by_name["imu"].kind == "imu" and by_name["gps"].type == "navsat"
    # plugins of the model and of its links are the model's; a sensor's are the sensor's
    assert [p.filename for p in robot.model_plugins] == [
        "sk-link-helper",
        "gz-sim-joint-state-publisher-system",
    ]
    assert [p.filename for p in by_name["imu"].plugins] == ["sk-imu-helper"]


def test_included_elements_are_located_in_their_own_file(monkeypatch: pytest.MonkeyPatch) -> None:
    (robot,) = _load(SDF_DIR / "include.sdf", monkeypatch)
    # model.config names the 1.8 file; its model is nested under each include's <name>
    assert [lk.name for lk in robot.links] == ["base", "head::head_link", "spare::head_link"]
    sensor = robot.sensors[0]
    assert sensor.source.file.endswith("models/sk_sensor_head/model_18.sdf")
    assert sensor.source.line == 6
    assert robot.link_map["base"].source.file.endswith("include.sdf")
    assert robot.link_map["base"].source.line == 4
    assert [inc.uri for inc in robot.sdf.includes] == ["model://sk_sensor_head"] * 2


def test_a_world_gives_each_model_with_its_world_pose(monkeypatch: pytest.MonkeyPatch) -> None:
    rover, mast = _load(SDF_DIR / "world.sdf", monkeypatch)
    assert (rover.name, mast.name) == ("rover", "mast")
    assert rover.sdf.world_pose is not None and mast.sdf.world_pose is not None
    # a joint to the world is no Robot joint: the model's root hangs from nothing
    assert rover.joints == [] and rover.roots() == ["chassis"]


def test_an_unresolved_include_is_kept_with_why(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.delenv("GZ_SIM_RESOURCE_PATH", raising=False)
    path = tmp_path / "m.sdf"
    path.write_text(
        '<sdf version="1.8"><model name="m"><link name="a"/>'
        "<include><uri>model://nowhere_model</uri></include></model></sdf>"
    )
    (robot,) = load_robot(path, sdf=True).robots
    (inc,) = robot.sdf.includes
    assert inc.path is None and "not found" in inc.why and inc.searched


def test_bad_sdf_is_a_finding_or_one_line(tmp_path: Path) -> None:
    broken = tmp_path / "broken.sdf"
    broken.write_text('<sdf version="1.9"><model name="m">\n<link name="a">\n</model></sdf>')
    loaded = load_robot(broken, sdf=True)
    assert loaded.robot is None and [f.rule for f in loaded.findings] == ["SK101"]
    assert loaded.findings[0].source.line == 3
    empty = tmp_path / "empty.sdf"
    empty.write_text('<sdf version="1.9"></sdf>')
    with pytest.raises(InputError, match="no <model> or <world>"):
        load_robot(empty, sdf=True)
    urdf = tmp_path / "robot.sdf"
    urdf.write_text('<robot name="r"/>')
    with pytest.raises(InputError, match="not <sdf>"):
        load_robot(urdf, sdf=True)


def test_without_sdf_the_loader_still_refuses_sdf() -> None:
    # The commands keep refusing SDF (one line naming <sdf>, exit 2) until their rules know it.
    with pytest.raises(InputError, match="<sdf>"):
        load_robot(SDF_DIR / "plain_links.sdf")


def test_untrusted_reads_no_include_outside_the_workspace(tmp_path: Path) -> None:
    from sensorkit.loading.untrusted import Untrusted

    outside = tmp_path / "elsewhere" / "model.sdf"
    outside.parent.mkdir()
    outside.write_text('<sdf version="1.8"><model name="x"><link name="secret"/></model></sdf>')
    ws = tmp_path / "ws" / "robot"
    ws.mkdir(parents=True)
    path = ws / "robot.sdf"
    path.write_text(
        f'<sdf version="1.8"><model name="m"><link name="a"/>'
        f"<include><uri>file://{outside}</uri></include></model></sdf>"
    )
    (trusted,) = load_robot(path, sdf=True).robots
    assert [lk.name for lk in trusted.links] == ["a", "x::secret"]
    (confined,) = load_robot(path, sdf=True, untrusted=Untrusted()).robots
    assert [lk.name for lk in confined.links] == ["a"]
    (inc,) = confined.sdf.includes
    assert inc.path is None and "--untrusted" in inc.why
    # nor does it say whether anything is there
    path.write_text(path.read_text().replace(str(outside), str(outside.parent / "nothing.sdf")))
    (missing,) = load_robot(path, sdf=True, untrusted=Untrusted()).robots
    assert missing.sdf.includes[0].why == inc.why


def test_broken_sdf_is_read_as_written_without_raising(monkeypatch: pytest.MonkeyPatch) -> None:
    # Mistakes libsdformat refuses (it stops at the first, the unreadable pose) are kept
    # as written for the rules: unreadable poses, frames that name nothing or loop,
    # placement frames naming nothing, includes that do not resolve or include
    # themselves, joints without a child.
    (robot,) = _load(SDF_DIR / "broken" / "bad.sdf", monkeypatch)
    sm = robot.sdf
    assert [p for p, _ in sm.pose_problems] == [
        "pose '1 2 x' is not 6 numbers",
        "placement_frame 'zzz' names no frame of the model",
        "placement_frame 'nowhere' names no frame",
    ]
    assert sm.pose_of("b") is None  # relative_to="ghost"
    assert sm.pose_of("c") is None  # f1 and f2 are attached to each other
    assert [v.name for v in sm.graph.duplicates] == ["c", ""]
    assert [(i.uri, i.why) for i in sm.includes] == [
        ("model://sk_selfie", ""),
        ("model://sk_selfie", "the include comes back to a file that includes it"),
        ("http://x/y", "only model://, package:// and file:// URIs and paths can be read"),
        ("", "the <include> has no <uri>"),
    ]
    joints = {j.name: j for j in robot.joints}
    assert (joints["j"].parent, joints["j"].child) == ("a", None)
    assert joints["k"].axis_problem == "axis expressed in a frame that does not resolve"
    assert [s.problems for s in robot.sensors] == [
        ["pose relative to a frame that does not resolve"]
    ] * 2


@pytest.mark.parametrize("path", OWN_SDF + CORPUS_SDF, ids=lambda p: p.name)
def test_masses_agree_with_libsdformat(sdf_poses: Path, path: Path, tmp_path: Path) -> None:
    # A link without <inertial> weighs what libsdformat's Link::Inertial() says (1 kg, unit
    # inertia: gazebosim/sdformat@sdformat12_12.8.0:src/Link.cc:66-69), not nothing.
    _skip_if_only_fuel(path)
    resources = _resources(path)
    env = {**os.environ, "GZ_SIM_RESOURCE_PATH": resources, "SDF_PATH": resources}
    res = subprocess.run(
        [str(sdf_poses), str(_for_libsdformat12(path, tmp_path))],
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
        env=env,
    )
    theirs = {
        tuple(line.split()[1:4:2]): [float(n) for n in line.split()[4:]]
        for line in res.stdout.splitlines()
        if line.startswith("MASS")
    }
    assert theirs
    old = os.environ.get("GZ_SIM_RESOURCE_PATH")
    os.environ["GZ_SIM_RESOURCE_PATH"] = resources
    try:
        robots = load_robot(path, sdf=True).robots
    finally:
        if old is None:
            del os.environ["GZ_SIM_RESOURCE_PATH"]
        else:
            os.environ["GZ_SIM_RESOURCE_PATH"] = old
    ours = {}
    for robot in robots:
        for link in robot.links:
            inertial = link.inertial
            assert inertial is not None, link.name
            keys = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
            ours[(robot.name, link.name)] = [inertial.mass, *(inertial.inertia[k] for k in keys)]
    assert ours == theirs


def test_merged_includes_join_the_including_model(monkeypatch: pytest.MonkeyPatch) -> None:
    (robot,) = _load(SDF_DIR / "merged.sdf", monkeypatch)
    # unscoped names, in document order, beside a proxy frame for each merged __model__
    # (gazebosim/sdformat@sdformat12_12.8.0:src/parser.cc:252-256, 2613-2616)
    assert [lk.name for lk in robot.links] == [
        "chassis", "shoulder", "upper", "tool", "finger::nail", "pole", "bumper",
    ]  # fmt: skip
    assert robot.sdf.models == {"finger": robot.sdf.models["finger"]}
    proxy = robot.sdf.graph.vertices["_merged__arm__model__"]
    assert (proxy.kind, proxy.attached_to) == ("frame", "upper")
    assert "_merged__mast__model__" in robot.sdf.graph.vertices
    # the include's plugin and the merged model's join the including model's plugins
    assert [p.filename for p in robot.model_plugins] == ["sk-arm-helper", "sk-include-helper"]
    assert robot.joint_map["arm_mount"].child == "shoulder"
    # the elbow's axis is written in the merged model's frame: the proxy's, not chassis's
    sm = robot.sdf
    R = sm.graph.in_frame("_merged__arm__model__", "upper")
    assert robot.joint_map["elbow"].axis == pytest.approx((R[1], R[4], R[7]))
    assert robot.sensors[0].source.file.endswith("models/sk_merge_arm/model.sdf")
