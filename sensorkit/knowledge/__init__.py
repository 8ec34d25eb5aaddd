"""What sensorkit knows about simulators and plugins, as plain data with sources.

Rules, macros, bridge generation and exporters consult these tables instead of keeping
their own conditionals. Every entry cites the code it was read from (repo@path:line).
"""
