"""Write examples/orbslam3_car/recordings/car_sim.mcap, the recording `sensorkit
check-recording`'s help and docs/check-recording.md check: the example car as Gazebo
Classic records it (tests/bags.py: its values from the simulators' source formulas), five
messages a topic, images of zeros, MCAP chunks compressed with zstd.

    python tests/tools/example_recording.py
"""

from __future__ import annotations

import shutil
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests"))

from bags import bare_mcap, car_scene, write_bag  # noqa: E402

OUT = ROOT / "examples" / "orbslam3_car" / "recordings" / "car_sim.mcap"


def main() -> None:
    scene = car_scene()
    for topic in scene.streams:
        scene = scene.with_stream(topic, count=5)
    with tempfile.TemporaryDirectory() as tmp:
        folder = write_bag(scene, Path(tmp) / "car_sim", "mcap", compress=True)
        OUT.parent.mkdir(parents=True, exist_ok=True)
        bare_mcap(folder, Path(tmp) / "car_sim.mcap")
        shutil.move(str(Path(tmp) / "car_sim.mcap"), OUT)
    print(f"{OUT.relative_to(ROOT)}: {OUT.stat().st_size} bytes")


if __name__ == "__main__":
    main()
