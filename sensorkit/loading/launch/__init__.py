"""Read a robot's launch files, never run them (issue 24): see
sensorkit.loading.launch_facts for what is read, and each module for its sources."""

from sensorkit.loading.launch.discover import find_launch_files
from sensorkit.loading.launch.reader import read_launch

__all__ = ["find_launch_files", "read_launch"]
