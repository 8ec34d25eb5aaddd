"""The launch reader (issue 24): Python launch files read as an AST, XML and YAML ones as
data, nothing run. Each extraction has a trigger and a near miss; what cannot be resolved
stays unknown, never guessed.

The cases are small launch files written for these tests, modelled on
gazebosim/ros_gz_project_template@main:ros_gz_example_bringup/launch/diff_drive.launch.py
(robot_state_publisher, a parameter_bridge with a config_file from os.path.join of
get_package_share_directory, lines 55-79) unless a test says otherwise.
"""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

from sensorkit.loading.launch import find_launch_files, read_launch
from sensorkit.loading.launch.extract import parse_bridge_arg
from sensorkit.loading.launch_facts import LaunchFacts

PKG_XML = "<package format='3'><name>{}</name></package>\n"


def ws(tmp: Path, files: dict[str, str]) -> Path:
    """A colcon src/ with packages (a folder holding ``package.xml``) and their files."""
    for rel, text in files.items():
        path = tmp / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(textwrap.dedent(text))
        pkg = path.parent.parent if path.parent.name in ("launch", "config", "urdf") else None
        if pkg is not None and not (pkg / "package.xml").exists():
            (pkg / "package.xml").write_text(PKG_XML.format(pkg.name))
    return tmp


def read(tmp: Path, rel: str) -> LaunchFacts:
    return read_launch([tmp / rel], roots=[tmp])


PY_BRIDGE = """
    from launch import LaunchDescription
    from launch.actions import DeclareLaunchArgument
    from launch.substitutions import LaunchConfiguration
    from launch_ros.actions import Node

    def generate_launch_description():
        robot = LaunchConfiguration('robot')
        lidar = [robot, '/rplidar_link/rplidar']
        return LaunchDescription([
            DeclareLaunchArgument('robot', default_value='bot'),
            Node(package='ros_gz_bridge', executable='parameter_bridge',
                 arguments=['/scan@sensor_msgs/msg/LaserScan[gz.msgs.LaserScan',
                            f'/model/{ROBOT}/cmd_vel@geometry_msgs/msg/Twist]gz.msgs.Twist',
                            '/clock@rosgraph_msgs/msg/Clock@gz.msgs.Clock',
                            '/world/default/control@ros_gz_interfaces/srv/ControlWorld'],
                 remappings=[('/scan', '/robot/scan')]),
            Node(package='ros_gz_image', executable='image_bridge', arguments=['/camera/image']),
            Node(package='tf2_ros', executable='static_transform_publisher',
                 arguments=['0', '0', '0', '0', '0', '0', 'base_link', lidar]),
        ])
    ROBOT = 'bot'
"""


def test_python_bridge_arguments_directions_and_remaps(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)  # files are shown relative to the working folder
    # parameter_bridge.cpp@humble:87-89,101-102,110/123/126: '[' gz->ROS, ']' ROS->gz, '@' both;
    # a /srv/ type is a service, not a topic (:132).
    facts = read(ws(tmp_path, {"bot_gazebo/launch/sim.launch.py": PY_BRIDGE}), "bot_gazebo/launch/sim.launch.py")
    got = {(b.gz, b.ros, b.direction) for b in facts.bridges}
    assert ("/scan", "/robot/scan", "GZ_TO_ROS") in got  # the ROS name after remapping
    assert ("/model/bot/cmd_vel", "/model/bot/cmd_vel", "ROS_TO_GZ") in got
    assert ("/clock", "/clock", "BIDIRECTIONAL") in got
    assert ("/camera/image", "/camera/image", "GZ_TO_ROS") in got  # image_bridge.cpp@humble:40,42
    assert not any("control" in b.gz for b in facts.bridges)
    assert not facts.bridge_unknown
    scan = next(b for b in facts.bridges if b.gz == "/scan")
    assert scan.file == "bot_gazebo/launch/sim.launch.py" and scan.line == 13  # the argument's own line
    # a list of substitutions is their concatenation
    assert [(t.parent, t.child) for t in facts.static_transforms] == [("base_link", "bot/rplidar_link/rplidar")]
    assert [(r.src, r.dst) for r in facts.remaps] == [("/scan", "/robot/scan")]


def test_bridge_argument_with_wrong_gz_topic_is_just_read(tmp_path: Path) -> None:
    """The reader reads what is written: the rule decides whether the gz topic is right."""
    text = """
        from launch_ros.actions import Node
        def generate_launch_description():
            return LaunchDescription([Node(package='ros_gz_bridge', executable='parameter_bridge',
                arguments=['/lidar_wrong@sensor_msgs/msg/LaserScan[gz.msgs.LaserScan'])])
    """
    facts = read(ws(tmp_path, {"b_sim/launch/a.launch.py": text}), "b_sim/launch/a.launch.py")
    assert [b.gz for b in facts.bridges] == ["/lidar_wrong"]


def test_bridge_argument_parsing_follows_parameter_bridge() -> None:
    # parameter_bridge.cpp@humble:94-130; galactic ros_ign_bridge :91,:114,:116 the same delimiters
    assert parse_bridge_arg("/a@sensor_msgs/msg/Image[gz.msgs.Image") == ("/a", "sensor_msgs/msg/Image", "GZ_TO_ROS")
    assert parse_bridge_arg("/a@std_msgs/msg/String]gz.msgs.StringMsg") == ("/a", "std_msgs/msg/String", "ROS_TO_GZ")
    assert parse_bridge_arg("/a@std_msgs/msg/String@gz.msgs.StringMsg") == ("/a", "std_msgs/msg/String", "BIDIRECTIONAL")
    assert parse_bridge_arg("@std_msgs/msg/String@x") is None  # usage, exit (:95-97)
    assert parse_bridge_arg("/a") is None
    assert parse_bridge_arg("/s@ros_gz_interfaces/srv/ControlWorld") == "service"


def test_unresolvable_bridge_argument_is_unknown_not_guessed(tmp_path: Path) -> None:
    text = """
        import os
        from launch_ros.actions import Node
        def generate_launch_description():
            topic = os.environ['TOPIC']
            return LaunchDescription([
                Node(package='ros_gz_bridge', executable='parameter_bridge',
                     arguments=[topic + '@sensor_msgs/msg/Imu[gz.msgs.IMU',
                                LaunchConfiguration('undeclared')]),
                Node(package='robot_state_publisher', executable='robot_state_publisher',
                     parameters=[{'frame_prefix': PythonExpression(['"a"'])}]),
                Node(package='tf2_ros', executable='static_transform_publisher',
                     arguments=['--frame-id', 'base_link', '--child-frame-id', LaunchConfiguration('x')]),
            ])
    """
    facts = read(ws(tmp_path, {"b_sim/launch/a.launch.py": text}), "b_sim/launch/a.launch.py")
    assert facts.bridges == [] and facts.bridge_unknown
    assert facts.frame_prefix is None and facts.frame_prefix_unknown
    assert facts.static_transforms == [] and facts.static_transform_unknown


def test_config_file_and_frame_prefix_python(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)  # files are shown relative to the working folder
    # ros_gz_bridge.cpp@humble:34,48-54 config_file; diff_drive.launch.py:75-79 os.path.join form
    text = """
        import os
        from ament_index_python.packages import get_package_share_directory
        from launch_ros.actions import Node
        pkg = get_package_share_directory('bot_bringup')
        def generate_launch_description():
            return LaunchDescription([
                Node(package='ros_gz_bridge', executable='parameter_bridge',
                     parameters=[{'config_file': os.path.join(pkg, 'config', 'bridge.yaml')}]),
                Node(package='robot_state_publisher', executable='robot_state_publisher',
                     parameters=[{'frame_prefix': 'bot/', 'use_sim_time': True}]),
            ])
    """
    bridge = """
        - ros_topic_name: "scan"
          gz_topic_name: "/lidar"
          ros_type_name: "sensor_msgs/msg/LaserScan"
          gz_type_name: "gz.msgs.LaserScan"
          direction: GZ_TO_ROS
    """
    tmp = ws(tmp_path, {"bot_bringup/launch/a.launch.py": text, "bot_bringup/config/bridge.yaml": bridge})
    facts = read(tmp, "bot_bringup/launch/a.launch.py")
    assert [(b.gz, b.ros, b.direction) for b in facts.bridges] == [("/lidar", "scan", "GZ_TO_ROS")]
    assert (facts.bridges[0].file, facts.bridges[0].line) == ("bot_bringup/config/bridge.yaml", 2)
    assert facts.frame_prefix == "bot/" and not facts.frame_prefix_unknown


def test_near_misses_give_nothing(tmp_path: Path) -> None:
    """Nodes that look alike but are not bridges, TF publishers or spawners."""
    text = """
        from launch_ros.actions import Node
        def generate_launch_description():
            return LaunchDescription([
                Node(package='my_bridge', executable='parameter_bridge', arguments=['/a@b/msg/C[d']),
                Node(package='tf2_ros', executable='tf2_echo', arguments=['a', 'b']),
                Node(package='ros_gz_sim', executable='gz_sim', arguments=['-name', 'x']),
            ])
    """
    facts = read(ws(tmp_path, {"b_sim/launch/a.launch.py": text}), "b_sim/launch/a.launch.py")
    assert not facts.bridges and not facts.static_transforms and not facts.spawns
    assert facts.frame_prefix is None and not facts.frame_prefix_unknown and not facts.bridge_unknown


def test_spawn_python_create_and_spawn_entity(tmp_path: Path) -> None:
    # create.cpp@humble:34,37,38 -file -topic -name; spawn_entity.py@ros2:57,59,65
    text = """
        from launch_ros.actions import Node
        def generate_launch_description():
            return LaunchDescription([
                Node(package='ros_gz_sim', executable='create',
                     arguments=['-name', 'bot', '-topic', 'robot_description']),
                Node(package='gazebo_ros', executable='spawn_entity.py',
                     arguments=['-entity', 'bot', '-file', '/x.urdf']),
            ])
    """
    facts = read(ws(tmp_path, {"b_sim/launch/a.launch.py": text}), "b_sim/launch/a.launch.py")
    assert [(s.tool, s.name, s.topic, s.file) for s in facts.spawns] == [
        ("ros_gz_sim create", "bot", "robot_description", None),
        ("spawn_entity.py", "bot", None, "/x.urdf"),
    ]
    assert facts.spawn_name() == "bot"


def test_spawn_name_unresolved_is_none(tmp_path: Path) -> None:
    text = """
        from launch_ros.actions import Node
        def generate_launch_description():
            return LaunchDescription([Node(package='ros_gz_sim', executable='create',
                arguments=['-name', LaunchConfiguration('robot_name'), '-topic', 'robot_description'])])
    """
    facts = read(ws(tmp_path, {"b_sim/launch/a.launch.py": text}), "b_sim/launch/a.launch.py")
    assert [s.name for s in facts.spawns] == [None] and facts.spawn_name() is None


def test_include_followed_with_launch_arguments(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)  # files are shown relative to the working folder
    """Modelled on turtlebot4_simulator's ros_gz_bringup including a spawn file with arguments."""
    top = """
        from launch.actions import IncludeLaunchDescription
        from launch.launch_description_sources import PythonLaunchDescriptionSource
        from launch.substitutions import PathJoinSubstitution
        from launch_ros.substitutions import FindPackageShare
        def generate_launch_description():
            spawn = IncludeLaunchDescription(
                PythonLaunchDescriptionSource([PathJoinSubstitution(
                    [FindPackageShare('bot_gazebo'), 'launch', 'spawn.launch.py'])]),
                launch_arguments={'name': 'rover'}.items())
            gz = IncludeLaunchDescription(PythonLaunchDescriptionSource(PathJoinSubstitution(
                [FindPackageShare('ros_gz_sim'), 'launch', 'gz_sim.launch.py'])))
            return LaunchDescription([spawn, gz])
    """
    spawn = """
        from launch_ros.actions import Node
        def generate_launch_description():
            return LaunchDescription([
                DeclareLaunchArgument('name', default_value='bot'),
                Node(package='ros_gz_sim', executable='create',
                     arguments=['-name', LaunchConfiguration('name')])])
    """
    tmp = ws(tmp_path, {"bot_bringup/launch/top.launch.py": top, "bot_gazebo/launch/spawn.launch.py": spawn})
    facts = read(tmp, "bot_bringup/launch/top.launch.py")
    assert facts.files == ["bot_bringup/launch/top.launch.py", "bot_gazebo/launch/spawn.launch.py"]
    assert facts.spawn_name() == "rover"  # the include's argument overrides the default
    assert not facts.problems  # ros_gz_sim's own launch file is outside: not read, no problem
    alone = read(tmp, "bot_gazebo/launch/spawn.launch.py")
    assert alone.spawn_name() == "bot"


def test_include_cycle_is_a_problem_not_a_hang(tmp_path: Path) -> None:
    a = """
        <launch><include file="$(find-pkg-share c_sim)/launch/b.launch.xml"/></launch>
    """
    b = """
        <launch><include file="$(find-pkg-share c_sim)/launch/a.launch.xml"/></launch>
    """
    tmp = ws(tmp_path, {"c_sim/launch/a.launch.xml": a, "c_sim/launch/b.launch.xml": b})
    facts = read(tmp, "c_sim/launch/a.launch.xml")
    assert any("cycle" in p.message for p in facts.problems)


def test_file_that_does_not_parse(tmp_path: Path) -> None:
    tmp = ws(tmp_path, {"c_sim/launch/a.launch.py": "def f(:\n", "c_sim/launch/b.launch.xml": "<launch>",
                        "c_sim/launch/c.launch.yaml": "launch: [\n", "c_sim/launch/d.launch.py": "x = " + "(" * 300 + ")" * 300})
    for name in ("a.launch.py", "b.launch.xml", "c.launch.yaml", "d.launch.py"):
        facts = read(tmp, f"c_sim/launch/{name}")
        assert facts.problems and facts.problems[0].message.startswith("could not read"), name
        assert facts.bridge_unknown  # a file not read may start a bridge


def test_big_file_is_a_problem(tmp_path: Path) -> None:
    tmp = ws(tmp_path, {"c_sim/launch/a.launch.py": "# " + "x" * (1 << 20)})
    assert "larger than 1 MiB" in read(tmp, "c_sim/launch/a.launch.py").problems[0].message


XML = """
    <launch>
      <arg name="robot" default="bot"/>
      <node pkg="ros_gz_bridge" exec="parameter_bridge"
            args="/model/$(var robot)/scan@sensor_msgs/msg/LaserScan[gz.msgs.LaserScan $(var nothing)">
        <remap from="/model/$(var robot)/scan" to="/scan"/>
      </node>
      <node pkg="tf2_ros" exec="static_transform_publisher"
            args="--x 0 --frame-id base_link --child-frame-id $(var robot)/imu"/>
      <node pkg="robot_state_publisher" exec="robot_state_publisher">
        <param name="frame_prefix" value="$(var robot)/"/>
      </node>
      <node pkg="ros_gz_sim" exec="create" args="-name $(var robot) -topic robot_description"/>
      <node pkg="tf2_ros" exec="tf2_monitor" args="a b"/>
    </launch>
"""


def test_xml_launch(tmp_path: Path) -> None:
    # launch_ros node.py@humble:310-342 (pkg exec args name namespace, param, remap);
    # static_transform_broadcaster_program.cpp@humble:217-218 the flags
    facts = read(ws(tmp_path, {"b_sim/launch/a.launch.xml": XML}), "b_sim/launch/a.launch.xml")
    assert [(b.gz, b.ros) for b in facts.bridges] == [("/model/bot/scan", "/scan")]
    assert facts.bridges[0].line == 5
    assert facts.bridge_unknown  # $(var nothing) is not declared: unknown
    assert [(t.parent, t.child) for t in facts.static_transforms] == [("base_link", "bot/imu")]
    assert facts.frame_prefix == "bot/"
    assert facts.spawn_name() == "bot"


YAML = """
    launch:
    - arg:
        name: robot
        default: bot
    - node:
        pkg: ros_gz_bridge
        exec: parameter_bridge
        args: /imu@sensor_msgs/msg/Imu[gz.msgs.IMU
        remap:
        - from: /imu
          to: /bot/imu
    - node:
        pkg: tf2_ros
        exec: static_transform_publisher
        args: 0 0 0 0 0 0 1 base_link $(var robot)/camera
    - node:
        pkg: robot_state_publisher
        exec: robot_state_publisher
    - node:
        pkg: ros_gz_sim
        exec: create
        args: -name $(var robot)
    - include:
        file: $(find-pkg-share b_sim)/launch/more.launch.yaml
        arg:
        - name: robot
          value: other
"""
MORE = """
    launch:
    - arg: {name: robot, default: bot}
    - node: {pkg: ros_gz_image, exec: image_bridge, args: /$(var robot)/image}
"""


def test_yaml_launch_and_include(tmp_path: Path) -> None:
    # quaternion form: 9 positional arguments, frames last (static_transform_broadcaster_program.cpp@humble:312-313)
    tmp = ws(tmp_path, {"b_sim/launch/a.launch.yaml": YAML, "b_sim/launch/more.launch.yaml": MORE})
    facts = read(tmp, "b_sim/launch/a.launch.yaml")
    assert [(b.gz, b.ros) for b in facts.bridges] == [("/imu", "/bot/imu"), ("/other/image", "/other/image")]
    assert [(t.parent, t.child) for t in facts.static_transforms] == [("base_link", "bot/camera")]
    assert facts.frame_prefix == ""  # a robot_state_publisher without frame_prefix
    assert facts.spawn_name() == "bot"
    assert not facts.bridge_unknown and not facts.problems


def test_ros_gz_bridge_action_xml(tmp_path: Path) -> None:
    # ros_gz@jazzy:ros_gz_bridge/ros_gz_bridge/actions/ros_gz_bridge.py:30,81-83
    text = """
        <launch>
          <ros_gz_bridge bridge_name="b" config_file="$(find-pkg-share b_sim)/config/b.yaml"/>
        </launch>
    """
    tmp = ws(tmp_path, {"b_sim/launch/a.launch.xml": text,
                        "b_sim/config/b.yaml": "- topic_name: /imu\n  ros_type_name: sensor_msgs/msg/Imu\n"})
    facts = read(tmp, "b_sim/launch/a.launch.xml")
    assert [(b.gz, b.ros, b.direction) for b in facts.bridges] == [("/imu", "/imu", "BIDIRECTIONAL")]


def test_namespace_pushed_makes_relative_names_unknown(tmp_path: Path) -> None:
    text = """
        <launch><group><push-ros-namespace namespace="$(var ns)"/>
          <node pkg="ros_gz_bridge" exec="parameter_bridge" args="scan@sensor_msgs/msg/LaserScan[gz.msgs.LaserScan"/>
        </group></launch>
    """
    facts = read(ws(tmp_path, {"b_sim/launch/a.launch.xml": text}), "b_sim/launch/a.launch.xml")
    assert [b.gz for b in facts.bridges] == ["scan"] and facts.bridge_unknown


def test_find_launch_files(tmp_path: Path) -> None:
    tmp = ws(tmp_path, {
        "bot_description/urdf/bot.urdf": "<robot name='bot'/>",
        "bot_description/launch/display.launch.py": "",
        "bot_gazebo/launch/sim.launch.xml": "<launch/>",
        "bot_bringup/launch/robot_launch.py": "",
        "bot_navigation/launch/nav.launch.py": "",  # not a simulation or bringup package
        "other_sim/launch/x.launch.py": "",  # another robot's
    })
    found = [p.relative_to(tmp).as_posix() for p in find_launch_files(tmp / "bot_description/urdf/bot.urdf", [tmp])]
    assert found == ["bot_description/launch/display.launch.py", "bot_bringup/launch/robot_launch.py",
                     "bot_gazebo/launch/sim.launch.xml"]


def test_find_package_share_find_is_the_share_folder(tmp_path: Path) -> None:
    # Modelled on blackcoffeerobotics/bcr_arm@93f4f61:bcr_arm_gazebo/launch/
    # bringup.gazebo.launch.py:37-41 (``FindPackageShare(package=p).find(p)``) and :141-144
    # (an include of os.path.join(that, 'launch', ...)); find() returns the share folder of
    # its own argument (ros2/launch_ros@humble:launch_ros/launch_ros/substitutions/
    # find_package.py:110-112).
    top = """
        import os
        from launch_ros.substitutions import FindPackageShare
        def generate_launch_description():
            pkg_sim = FindPackageShare(package='bot_gazebo').find('bot_gazebo')
            spawn = IncludeLaunchDescription(PythonLaunchDescriptionSource([
                os.path.join(pkg_sim, 'launch', 'spawn.launch.py')]))
            return LaunchDescription([spawn])
    """
    spawn = """
        from launch_ros.actions import Node
        def generate_launch_description():
            return LaunchDescription([Node(package='ros_gz_sim', executable='create',
                                           arguments=['-name', 'arm', '-topic', 'robot_description'])])
    """
    tmp = ws(tmp_path, {"bot_bringup/launch/top.launch.py": top, "bot_gazebo/launch/spawn.launch.py": spawn})
    facts = read(tmp, "bot_bringup/launch/top.launch.py")
    assert facts.spawn_name() == "arm" and not facts.problems
    # Near miss: find() of a package not in the workspace is outside: nothing read, no guess.
    (tmp / "bot_bringup/launch/top.launch.py").write_text(textwrap.dedent(top).replace(".find('bot_gazebo')", ".find('other')"))
    facts = read(tmp, "bot_bringup/launch/top.launch.py")
    assert facts.spawn_name() is None


def test_get_namespaced_name_and_perform_substitution(tmp_path: Path) -> None:
    # Modelled on turtlebot/turtlebot4_simulator@a238c94:turtlebot4_ignition_bringup/launch/
    # turtlebot4_spawn.launch.py:106,112,145-148,205-212: robot_name =
    # GetNamespacedName(namespace, 'turtlebot4') (create3_sim@6a8bc44:irobot_create_common/
    # irobot_create_common_bringup/irobot_create_common_bringup/namespace.py:29-32: name, or
    # namespace/name) names the spawned model and the lidar's static transform; and on
    # husarion/rosbot_xl_ros@2356b5f:rosbot_xl_gazebo/launch/spawn.launch.py:33-34, an
    # OpaqueFunction reads a configuration with context.perform_substitution
    # (ros2/launch@humble:launch/launch/launch_context.py:238-240).
    text = """
        from irobot_create_common_bringup.namespace import GetNamespacedName
        def bridge(context, *args, **kwargs):
            model = context.perform_substitution(LaunchConfiguration('model'))
            return [Node(package='ros_gz_bridge', executable='parameter_bridge',
                         arguments=['/' + model + '/scan@sensor_msgs/msg/LaserScan[gz.msgs.LaserScan'])]
        def generate_launch_description():
            namespace = LaunchConfiguration('namespace')
            robot_name = GetNamespacedName(namespace, 'bot')
            return LaunchDescription([
                DeclareLaunchArgument('namespace', default_value=''),
                DeclareLaunchArgument('model', default_value='lidar'),
                Node(package='ros_gz_sim', executable='create', arguments=['-name', robot_name]),
                Node(package='tf2_ros', executable='static_transform_publisher',
                     arguments=['0', '0', '0', '0', '0', '0.0', 'rplidar_link', [robot_name, '/rplidar_link/rplidar']]),
                OpaqueFunction(function=bridge)])
    """
    tmp = ws(tmp_path, {"bot_gazebo/launch/spawn.launch.py": text})
    facts = read(tmp, "bot_gazebo/launch/spawn.launch.py")
    assert facts.spawn_name() == "bot"
    assert [(t.parent, t.child) for t in facts.static_transforms] == [("rplidar_link", "bot/rplidar_link/rplidar")]
    assert [b.gz for b in facts.bridges] == ["/lidar/scan"] and not facts.bridge_unknown
    # Near miss: under a namespace the name is namespace/name (namespace.py:32).
    (tmp / "bot_gazebo/launch/spawn.launch.py").write_text(
        textwrap.dedent(text).replace("'namespace', default_value=''", "'namespace', default_value='r1'"))
    assert read(tmp, "bot_gazebo/launch/spawn.launch.py").spawn_name() == "r1/bot"
