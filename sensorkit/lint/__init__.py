"""The lint layer: run the rules on a robot model and report what they find.

The rules, one module per family (:mod:`.rules`); the engine that loads, models, checks,
filters, suppresses and sorts (:mod:`.engine`); many files and worker processes
(:mod:`.fleet`); inline suppressions (:mod:`.suppress`); settings files (:mod:`.config`);
the formats (:mod:`.report`) and ``sensorkit rules ID`` (:mod:`.explain`).
"""
