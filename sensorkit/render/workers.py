"""Running a preview's jobs: here, or split over forked processes of about equal work.

``render_all`` renders every planned camera and casts every lidar (``run_job``), in this
process or, with ``workers`` > 1 on Linux, in children forked once the world is built,
so that each renders from the same state; a child sends its results back pickled, and
a child that fails has its jobs rendered here instead. Results are the same either way.
"""

from __future__ import annotations

import os
import sys
import time

from sensorkit.render.camera_job import render_camera_job
from sensorkit.render.lidar_job import render_lidar_job
from sensorkit.render.plan import Job
from sensorkit.render.result import SensorPreview
from sensorkit.render.session import JobResult, Progress, Session, say

__all__ = ["render_all", "run_job"]


def run_job(
    run: Session, job: Job, progress: Progress | None, deadline: float | None = None
) -> JobResult:
    """Render ``job``; past ``deadline`` (time.monotonic, the preview's total seconds)
    leave it out instead, saying so."""
    if deadline is not None and time.monotonic() > deadline:
        from sensorkit.render.plan import left_out

        return left_out(job.sensor, "seconds (--max-seconds)"), None
    if job.cam is not None:
        return render_camera_job(run, job, progress)
    return render_lidar_job(run, job, progress)


# Costs of a job in units of one camera pixel rendered: a lidar ray costs about 12 of
# them, and the checks and files of any sensor some 80,000.
_JOB_OVERHEAD = 80_000
_RAY_COST = 12


def _cost(job: Job) -> int:
    """Rough CPU a job takes, in units of one TinyRenderer pixel."""
    from sensorkit.describe.published import camera_size

    if job.cam is not None:
        w, h, _ = camera_size(job.cam, [])
        return _JOB_OVERHEAD + w * h
    lidar = job.sensor.lidar
    rays = 1 if lidar is None else max(lidar.samples or 1, 1) * max(lidar.v_samples or 1, 1)
    return _JOB_OVERHEAD + _RAY_COST * rays


def _groups(jobs: list[Job], workers: int) -> list[list[Job]]:
    """Jobs split into at most ``workers`` groups of about equal cost, each in document
    order: largest first, each to the lightest group, and of equal ones to the last.
    Group 0 stays in this process, which has the overview and validate to do after."""
    loads = [0] * max(1, min(workers, len(jobs)))
    groups: list[list[Job]] = [[] for _ in loads]
    for job in sorted(jobs, key=_cost, reverse=True):
        g = max(range(len(loads)), key=lambda k: (-loads[k], k))
        groups[g].append(job)
        loads[g] += _cost(job)
    order = {id(j): k for k, j in enumerate(jobs)}
    return [sorted(group, key=lambda j: order[id(j)]) for group in groups]


def _preload(jobs: list[Job], target: str) -> None:
    """Import here, before forking, what rendering the jobs imports, so that the forked
    processes inherit it instead of each importing it again."""
    import importlib
    import pickle  # noqa: F401 (the children send their results with it)

    from sensorkit.model.targets import is_gz

    names = [
        "sensorkit.base.atomic",
        "sensorkit.exporters",
        "sensorkit.describe.intrinsics",
        "sensorkit.model.frames",
        "sensorkit.render._files",
        "sensorkit.render.overview",
        "sensorkit.render.png",
        "sensorkit.render.raster",
        "sensorkit.render.rviz",
        "sensorkit.describe.sensorinfo",
    ]
    if any(j.cam is not None for j in jobs):
        names.append("sensorkit.render.camera")
    if any(j.cam is None for j in jobs):
        names.append("sensorkit.render.lidar")
    if is_gz(target):
        names.append("sensorkit.describe.bridge")  # the topics of a gz sensor
    for name in names:
        importlib.import_module(name)


def render_all(
    run: Session,
    plan: list[Job | SensorPreview],
    progress: Progress | None,
    workers: int,
    deadline: float | None = None,
) -> list[JobResult]:
    """Render every job; with ``workers`` > 1 on Linux, split the jobs, cameras and lidars
    alike, over forked processes of about equal work. Every fork happens before anything
    is rendered or cast here (rayTestBatch starts threads, which must not exist when
    forking). A child that fails has its jobs rendered here instead."""
    jobs = [j for j in plan if isinstance(j, Job)]
    if workers <= 1 or not sys.platform.startswith("linux") or not hasattr(os, "fork"):
        workers = 1
    groups = _groups(jobs, workers)
    done: dict[int, JobResult] = {}
    children: list[tuple[int, int, list[Job]]] = []
    if len(groups) > 1:
        _preload(jobs, run.target)
    for group in groups[1:]:
        for job in group:
            what = "rendering" if job.cam is not None else "casting"
            say(progress, f"{what} {job.name} (in another process)")
        child = _fork(run, group, deadline)
        if child is not None:
            children.append((*child, group))
        else:
            groups[0] += group
    for job in groups[0]:
        done[id(job)] = run_job(run, job, progress, deadline)
    for pid, fd, group in children:
        results = _collect(pid, fd)
        if results is None or len(results) != len(group):
            results = [run_job(run, job, progress, deadline) for job in group]
        for job, result in zip(group, results, strict=True):
            done[id(job)] = result
    return [done[id(j)] if isinstance(j, Job) else (j, None) for j in plan]


def _fork(run: Session, group: list[Job], deadline: float | None = None) -> tuple[int, int] | None:
    """Render ``group`` in a forked child; (pid, read end of its pipe), or None."""
    import pickle

    for stream in (sys.stdout, sys.stderr):
        stream.flush()
    from sensorkit.base import confine

    confine.preload()
    read, write = os.pipe()
    parent = os.getpid()
    try:
        pid = os.fork()
    except OSError:
        os.close(read)
        os.close(write)
        return None
    if pid == 0:  # the child: render, send the results, leave without cleanup
        code = 0
        try:
            confine.die_with_parent(parent)  # a killed preview leaves nothing running
            os.close(read)
            run.world.quiet.forget_sink()
            payload = pickle.dumps([run_job(run, job, None, deadline) for job in group])
        except BaseException:
            payload, code = b"", 1
        try:
            with os.fdopen(write, "wb") as pipe:
                pipe.write(payload)
        finally:
            os._exit(code)
    os.close(write)
    return pid, read


def _collect(pid: int, fd: int) -> list[JobResult] | None:
    import pickle

    with os.fdopen(fd, "rb") as pipe:
        payload = pipe.read()
    _, status = os.waitpid(pid, 0)
    if status != 0 or not payload:
        return None
    try:
        results: list[JobResult] = pickle.loads(payload)
    except Exception:
        return None
    return results
