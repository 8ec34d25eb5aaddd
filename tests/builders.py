"""Small URDF builders for rule tests: a clean robot, then one change per case."""

from __future__ import annotations

INERTIAL = (
    '<inertial><mass value="{m}"/>'
    '<inertia ixx="{i}" ixy="0" ixz="0" iyy="{i}" iyz="0" izz="{i}"/></inertial>'
)
OPTICAL = "-1.5707963267948966 0 -1.5707963267948966"


def inertial(m: float = 0.1, i: float = 1e-4) -> str:
    return INERTIAL.format(m=m, i=i)


def link(name: str, body: str | None = None) -> str:
    return f'<link name="{name}">{inertial() if body is None else body}</link>'


def joint(name: str, parent: str, child: str, xyz: str = "0 0 0", rpy: str = "0 0 0", type: str = "fixed", extra: str = "") -> str:
    return (
        f'<joint name="{name}" type="{type}"><parent link="{parent}"/><child link="{child}"/>'
        f'<origin xyz="{xyz}" rpy="{rpy}"/>{extra}</joint>'
    )


def camera_sensor(
    name: str = "front_camera",
    *,
    stype: str = "camera",
    plugin: str = "libgazebo_ros_camera.so",
    plugin_name: str | None = None,
    params: str = "<frame_name>camera_optical_frame</frame_name>",
    camera: str | None = None,
    extra: str = "<update_rate>30</update_rate>",
) -> str:
    cam = camera if camera is not None else (
        '<camera><horizontal_fov>1.3962634</horizontal_fov>'
        '<image><width>640</width><height>480</height><format>R8G8B8</format></image>'
        '<clip><near>0.05</near><far>50</far></clip></camera>'
    )
    plug = "" if plugin == "" else f'<plugin name="{plugin_name or name + "_controller"}" filename="{plugin}">{params}</plugin>'
    return f'<sensor name="{name}" type="{stype}">{extra}{cam}{plug}</sensor>'


def lidar_sensor(
    name: str = "laser",
    *,
    stype: str = "ray",
    samples: str = "360",
    resolution: str = "1",
    min_angle: str = "-3.14159",
    max_angle: str = "3.14159",
    rmin: str = "0.12",
    rmax: str = "12",
    vertical: str = "",
    plugin: str = "libgazebo_ros_ray_sensor.so",
    params: str = "<ros><remapping>~/out:=scan</remapping></ros><output_type>sensor_msgs/LaserScan</output_type><frame_name>laser_link</frame_name>",
    noise: str = "",
    tag: str = "ray",
) -> str:
    plug = "" if plugin == "" else f'<plugin name="{name}_controller" filename="{plugin}">{params}</plugin>'
    return (
        f'<sensor name="{name}" type="{stype}"><update_rate>10</update_rate><{tag}><scan><horizontal>'
        f"<samples>{samples}</samples><resolution>{resolution}</resolution>"
        f"<min_angle>{min_angle}</min_angle><max_angle>{max_angle}</max_angle></horizontal>{vertical}</scan>"
        f"<range><min>{rmin}</min><max>{rmax}</max><resolution>0.01</resolution></range>{noise}</{tag}>{plug}</sensor>"
    )


def robot(
    *,
    camera: str | None = None,
    lidar: str | None = None,
    optical_rpy: str = OPTICAL,
    optical_xyz: str = "0 0 0",
    camera_joint_type: str = "fixed",
    camera_body: str | None = None,
    extra: str = "",
    name: str = "rover",
) -> str:
    """A clean two-sensor robot: base_footprint -> base_link -> camera_link/laser_link."""
    cam_extra = '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>' if camera_joint_type == "revolute" else ""
    parts = [
        '<link name="base_footprint"/>',
        joint("base_joint", "base_footprint", "base_link", "0 0 0.1"),
        link("base_link", inertial(5.0, 0.1)),
        link("camera_link", camera_body),
        joint("camera_joint", "base_link", "camera_link", "0.25 0 0.1", type=camera_joint_type, extra=cam_extra),
        '<link name="camera_optical_frame"/>',
        joint("camera_optical_joint", "camera_link", "camera_optical_frame", optical_xyz, optical_rpy),
        link("laser_link"),
        joint("laser_joint", "base_link", "laser_link", "0 0 0.2"),
        f'<gazebo reference="camera_link">{camera if camera is not None else camera_sensor()}</gazebo>',
        f'<gazebo reference="laser_link">{lidar if lidar is not None else lidar_sensor()}</gazebo>',
        extra,
    ]
    return f'<?xml version="1.0"?>\n<robot name="{name}">\n' + "\n".join(p for p in parts if p) + "\n</robot>\n"


def gz_robot(*, camera_tags: str | None = None, lidar_tags: str | None = None, camera_type: str = "camera", extra: str = "") -> str:
    """A clean Gazebo Sim (Harmonic) robot."""
    cam_tags = camera_tags if camera_tags is not None else "<topic>front_camera/image_raw</topic><gz_frame_id>camera_optical_frame</gz_frame_id>"
    lid_tags = lidar_tags if lidar_tags is not None else "<topic>scan</topic><gz_frame_id>laser_link</gz_frame_id>"
    cam = (
        f'<sensor name="front_camera" type="{camera_type}"><update_rate>30</update_rate>{cam_tags}'
        '<camera><horizontal_fov>1.3962634</horizontal_fov><image><width>640</width><height>480</height>'
        "<format>R8G8B8</format></image><clip><near>0.05</near><far>50</far></clip></camera></sensor>"
    )
    lid = (
        f'<sensor name="laser" type="gpu_lidar"><update_rate>10</update_rate>{lid_tags}<lidar><scan><horizontal>'
        "<samples>360</samples><resolution>1</resolution><min_angle>-3.14159</min_angle><max_angle>3.14159</max_angle>"
        "</horizontal></scan><range><min>0.12</min><max>12</max></range></lidar></sensor>"
    )
    plugin = '<gazebo><plugin filename="gz-sim-sensors-system" name="gz::sim::systems::Sensors"/></gazebo>'
    return robot(camera=cam, lidar=lid, extra=plugin + extra)


def bridge_entry(gz: str, ros_type: str, gz_type: str) -> str:
    """One ros_gz_bridge YAML entry carrying gz topic ``gz`` to ROS (the ROS name without
    its leading slash)."""
    return (
        f"- ros_topic_name: {gz.strip('/')}\n  gz_topic_name: {gz}\n  ros_type_name: {ros_type}\n"
        f"  gz_type_name: {gz_type}\n  direction: GZ_TO_ROS\n"
    )
