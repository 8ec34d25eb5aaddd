"""Issue 23 on frames: each fact with a trigger and a near miss (inline robots)."""

from __future__ import annotations

from builders import joint, lidar_sensor, link
from conftest import rules_of

SENSORS = '<gazebo><plugin filename="gz-sim-sensors-system" name="gz::sim::systems::Sensors"/></gazebo>'


def _tree(*parts: str, name: str = "robot") -> str:
    return f'<?xml version="1.0"?><robot name="{name}">' + "".join(parts) + "</robot>"


# --- fact 8: a ROS 1 velodyne <frameName> that names no link -----------------------

VELODYNE_PARAMS = "<topicName>points</topicName><frameName>{frame}</frameName><gaussianNoise>0.008</gaussianNoise>"


def _velodyne(frame: str) -> str:
    sensor = lidar_sensor(
        "vlp16", plugin="libgazebo_ros_velodyne_laser.so", params=VELODYNE_PARAMS.format(frame=frame)
    )
    return _tree(
        '<link name="base_link"/>', link("vlp16_link"), joint("vlp16_joint", "base_link", "vlp16_link", "0 0 0.3"),
        f'<gazebo reference="vlp16_link">{sensor}</gazebo>',
    )


def test_ros1_velodyne_frame_name_that_names_no_link_is_sk501(check) -> None:
    # lmark1/velodyne_simulator@e08185a:velodyne_gazebo_plugins/src/GazeboRosVelodyneLaser.cpp:119-124
    # reads <frameName>, :172-178 passes it through tf::resolve(prefix, frame_name_) with
    # the tf_prefix parameter (or robotNamespace, when not "/") and :316 stamps it.
    # tf::resolve (ros/geometry@noetic-devel:tf/src/tf.cpp:159-191) keeps a name that does
    # not start with "/" as is when the prefix is empty: "robot/vlp16_link" is stamped, and
    # no link has that name. Validated as ROS 1 (3 ROS 1-only tags), not as the ROS 2
    # port, so no lumping finding about a frame this plugin does not use.
    r = check(_velodyne("robot/vlp16_link"))
    assert r.target == "ros1"
    sk501 = [f for f in r.findings if f.rule == "SK501"]
    assert [f.frame for f in sk501] == ["robot/vlp16_link"]
    assert sk501[0].fix == "did you mean 'vlp16_link'?"
    assert not {"SK303", "SK503"} & rules_of(r)


def test_ros1_velodyne_frame_name_with_leading_slash_is_the_link(check) -> None:
    # near miss: tf.cpp:162-165 strips one leading "/", so "/vlp16_link" stamps vlp16_link.
    r = check(_velodyne("/vlp16_link"))
    assert r.target == "ros1"
    assert "SK501" not in rules_of(r)
    assert "SK501" not in rules_of(check(_velodyne("vlp16_link")))

