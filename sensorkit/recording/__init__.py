"""The recording layer: a bag checked against what the description predicts.

Above ``describe``, whose predictions (topics, frames, camera_info, LaserScan geometry,
rates) it compares with what a recording holds: :mod:`.bag` reads a ROS 1 ``.bag``, a
rosbag2 folder (sqlite3 or MCAP) or a bare ``.mcap``/``.db3`` through rosbags (the
optional extra ````sensorkit-ros[recording]````; nothing else in sensorkit imports it), reading the
index and a bounded sample of each topic, never every image; :mod:`.tf` holds the recorded
transforms; :mod:`.expect` says what each recorded topic should be; :mod:`.frames` and
:mod:`.data` make the findings (rule ids SK8xx, declared in
``sensorkit.lint.rules.recording``) and :mod:`.check` runs them all.
"""
