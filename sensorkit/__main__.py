"""``python -m sensorkit``."""

from sensorkit.cli import main

main()
