"""Where Gazebo Classic (Gazebo 11) finds the model an SDF ``<include>`` names, and what it
does when it finds none; Gazebo Sim's search path beside it (SK107, issue 35 item 6).

Every fact cites the source it was read from.
"""

from __future__ import annotations

from typing import Final

GAZEBO11 = "elysia-best/gazebo-classic@upstream/11.10.2+dfsg b64af319"

# The models Gazebo 11 installs with itself, into share/gazebo-11/models: "The set of
# built-in models should be very small" (models/CMakeLists.txt:1-12, dirs ground_plane and
# sun). That folder is GAZEBO_MODEL_PATH's compile-time default (CMakeLists.txt:187), which
# setup.sh puts on GAZEBO_MODEL_PATH (cmake/setup.sh.in:18): model://sun and
# model://ground_plane resolve on any Gazebo 11.
CLASSIC_INSTALLED_MODELS: Final = frozenset({"ground_plane", "sun"})
CLASSIC_INSTALLED_SOURCE: Final = f"{GAZEBO11}:models/CMakeLists.txt:4-12"

# Gazebo 11 adds each folder of GAZEBO_MODEL_PATH (else the compile-time default) and
# ~/.gazebo/models as model:// paths (gazebo/common/SystemPaths.cc:195-215, :85-91).
CLASSIC_SEARCH_PATH: Final = "GAZEBO_MODEL_PATH"
CLASSIC_SEARCH_SOURCE: Final = f"{GAZEBO11}:gazebo/common/SystemPaths.cc:195-215"

# libsdformat 9 (Gazebo 11's) reports URI_LOOKUP for an include it cannot find and skips it
# (src/parser.cc:863-885 resolveFileNameFromUri; :976-980 `continue`): the world loads
# without that model.
CLASSIC_SKIPS_SOURCE: Final = "gazebosim/sdformat@sdformat9_9.10.2 9ee2d4f3:src/parser.cc:976-980"

# Gazebo Sim searches GZ_SIM_RESOURCE_PATH (gazebosim/gz-sim@gz-sim8_8.9.0:include/gz/sim/
# Util.hh:327 kResourcePathEnv, src/Util.cc:474); GAZEBO_MODEL_PATH occurs nowhere in its
# src/ or include/ at that tag: a model found only through it is not found by Gazebo Sim.
GZ_SEARCH_PATH: Final = "GZ_SIM_RESOURCE_PATH"
GZ_SEARCH_SOURCE: Final = "gazebosim/gz-sim@gz-sim8_8.9.0:include/gz/sim/Util.hh:327, src/Util.cc:474"


def search_path(target: str | None) -> str:
    """The environment variable the target searches for ``model://`` includes."""
    return CLASSIC_SEARCH_PATH if target in ("classic", "ros1") else GZ_SEARCH_PATH
