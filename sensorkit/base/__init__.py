"""The base layer: what every other layer stands on and that stands on nothing of sensorkit.

Errors (:mod:`.errors`), findings (:mod:`.findings`), atomic and locked writes
(:mod:`.atomic`), the shipped data folders (:mod:`.resources`) and "did you mean"
(:mod:`.suggest`).
"""
