"""Shared datatrove plumbing of the sharded jobs (dataset builds, evaluations): shards as local
processes while a progress thread draws bars, or as a Slurm array job followed by a dependent
one-task merge job."""

from __future__ import annotations

import faulthandler
import os
import shutil
import signal
import sys
import threading
import time
from pathlib import Path

from datatrove.executor import LocalPipelineExecutor, SlurmPipelineExecutor
from datatrove.pipeline.base import PipelineStep
from loguru import logger

SLURM_ONLY_FOR_SHARDS = ("workers", "gpus_per_task")  # the merge job needs neither a GPU nor an array limit


def one_core() -> None:
    """For a worker that shares the machine one process per core: keep Mesa's rasteriser and
    torch's threads (when the worker uses torch) on its core, without importing torch here."""
    os.environ.setdefault("LP_NUM_THREADS", "1")
    os.environ.setdefault("OMP_NUM_THREADS", "1")
    torch = sys.modules.get("torch")
    if torch is not None:
        torch.set_num_threads(1)


class ProgressBars(threading.Thread):
    """Redraws progress bars about once a second, from files the workers write, until ``stop`` is
    set; subclasses implement ``refresh()`` (and ``close()`` for their bars)."""

    def __init__(self):
        super().__init__(daemon=True)
        self.stop = threading.Event()

    def run(self):
        while True:
            self.refresh()
            if self.stop.is_set():
                self.close()
                return
            self.stop.wait(1.0)

    def refresh(self) -> None:
        raise NotImplementedError

    def close(self) -> None:
        pass


def _console(level: str = "WARNING", logfile: Path | None = None) -> None:
    """datatrove's (loguru) output: warnings and errors on the terminal, everything else in ``logfile``."""
    logger.remove()
    logger.add(sys.stderr, level=level)
    if logfile is not None:
        logger.add(logfile, level="INFO")


_watched: set[int] = set()


def exit_with(main_pid: int, every_s: float = 0.5) -> None:
    """In a worker process: end it soon after the job's main process ``main_pid`` is gone. Killing
    the main process does not stop a process pool's workers; left running, they go on writing
    episodes into the job's folder, under a resumed or restarted run of it."""
    if main_pid in _watched:
        return
    _watched.add(main_pid)

    def watch():
        while _alive(main_pid):
            time.sleep(every_s)
        os._exit(1)  # a record is one append of a whole line; the resumed job replays the episode cut short

    threading.Thread(target=watch, name="exit-with-main", daemon=True).start()


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    try:  # a killed process its parent has not reaped yet is a zombie: gone all the same
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except (OSError, IndexError):
        return True


class WorkerDiedError(RuntimeError):
    """A pool worker ended in the middle of a shard without an error (killed, or a crash in native
    code): the process pool would wait for that shard for ever."""


class _DeadWorkerInterrupt(BaseException):
    """Raised in the main thread by the watch's signal: a BaseException, as KeyboardInterrupt, so
    that no ``except Exception`` on the way out of the pool's wait swallows it."""


def _interrupt(signum, frame):
    raise _DeadWorkerInterrupt


class DeadWorkerWatch(threading.Thread):
    """In the main process: every ``every_s``, the shards that workers have started
    (``running/<rank>`` holds the worker's pid) and not completed; when such a worker is gone, note
    which and interrupt the main thread (``INTERRUPT``, whose handler ``QuietLocalExecutor.run``
    installs; not SIGINT, which a shell's background job ignores), which ``run`` turns into
    ``WorkerDiedError``."""

    INTERRUPT = signal.SIGUSR1

    def __init__(self, executor: QuietLocalExecutor, every_s: float = 2.0):
        super().__init__(name="dead-worker-watch", daemon=True)
        self.executor, self.every_s = executor, every_s
        self.stop, self.dead = threading.Event(), None
        self.main_thread = threading.get_ident()  # built in the main thread

    def run(self):
        running = Path(self.executor.logging_dir.path) / "running"
        while not self.stop.wait(self.every_s):
            for path in sorted(running.glob("*")) if self.dead is None else ():
                rank, pid = int(path.name), int(path.read_text() or 0)
                if pid and not _alive(pid) and not self.executor.is_rank_completed(rank):
                    self.dead = (rank, pid)
            # only while the main thread waits on the pool: an interrupt landing in the pool's or the
            # queue manager's shutdown leaves the manager running, and the exiting job waits for it
            if self.dead is not None and _waiting_on_pool(self.main_thread):
                os.kill(os.getpid(), self.INTERRUPT)


def _waiting_on_pool(thread_id: int) -> bool:
    """Whether thread ``thread_id`` is blocked on a process pool's results (``Pool.imap*``)."""
    frame = sys._current_frames().get(thread_id)
    while frame is not None:
        if frame.f_code.co_qualname == "IMapIterator.next":
            return True
        frame = frame.f_back
    return False


class QuietLocalExecutor(LocalPipelineExecutor):
    """datatrove's local executor with its logs in the run folder only (``logs/task_*.log``,
    ``executor.log``): by default it echoes one worker's task logs and every task's stats block to
    the terminal, where our progress bars and summary are. Errors still reach the terminal. A worker
    that dies in the middle of a shard ends the job with ``WorkerDiedError`` instead of a hang."""

    def _run_for_rank(self, rank: int, local_rank: int = 0, node_rank: int = -1):
        main_pid = getattr(self, "main_pid", os.getpid())
        if os.getpid() != main_pid:  # a pool worker
            exit_with(main_pid)
            logs = Path(self.logging_dir.path)
            (logs / "running").mkdir(parents=True, exist_ok=True)
            (logs / "running" / f"{rank:05d}").write_text(str(os.getpid()))
            # a crash in native code (MuJoCo, the renderer, the video encoder) leaves its Python stack here
            faulthandler.enable(open(logs / "faults.log", "a"))  # noqa: SIM115 (open for the process's life)
        # local_rank only picks which worker echoes its task log (rank 0 does): none of them
        stats = super()._run_for_rank(rank, local_rank + 1, node_rank)
        _console()  # datatrove re-adds a verbose terminal logger after each task
        return stats

    def run(self):
        self.main_pid = os.getpid()  # pickled into the workers with the executor
        logs = Path(self.logging_dir.path)
        _console(logfile=logs / "executor.log")
        shutil.rmtree(logs / "running", ignore_errors=True)  # an earlier, stopped run's
        watch = DeadWorkerWatch(self)
        watched = self.workers != 1 and threading.current_thread() is threading.main_thread()
        if watched:  # a signal handler can only be set from the main thread
            previous = signal.signal(watch.INTERRUPT, _interrupt)
            watch.start()
        try:
            return super().run()
        except _DeadWorkerInterrupt:
            rank, pid = watch.dead
            raise WorkerDiedError(
                f"the worker running shard {rank} (pid {pid}) ended without an error: it was killed or "
                f"crashed in native code (a Python stack of a crash is in {logs / 'faults.log'}). The "
                "finished shards are kept: run the same command again to resume"
            ) from None
        finally:
            watch.stop.set()
            if watched:
                watch.join()  # no signal after the handler is gone: SIGUSR1's default ends the process
                signal.signal(watch.INTERRUPT, previous)
            logger.remove()
            logger.add(sys.stderr)  # loguru's default, as datatrove leaves it


def run_local(
    step: PipelineStep, tasks: int, workers: int, logging_dir: Path, progress: ProgressBars | None = None
) -> None:
    """Run ``tasks`` ranks of ``step`` in ``workers`` processes (datatrove skips completed ranks);
    datatrove's logs go to ``logging_dir``, not the terminal."""
    if progress is not None:
        progress.start()
    try:
        QuietLocalExecutor(pipeline=[step], tasks=tasks, workers=workers, logging_dir=str(logging_dir)).run()
    finally:
        if progress is not None:
            progress.stop.set()
            progress.join()


def submit_slurm(
    step: PipelineStep,
    tasks: int,
    merge: PipelineStep,
    logging_dir: Path,
    job_name: str,
    options: dict | None,
) -> None:
    """Submit ``tasks`` array tasks of ``step`` and a merge job that runs once they all succeeded."""
    opts = dict(options or {})
    shards = SlurmPipelineExecutor(
        pipeline=[step], tasks=tasks, logging_dir=str(logging_dir / "logs"), job_name=job_name, **opts
    )
    merge_job = SlurmPipelineExecutor(
        pipeline=[merge],
        tasks=1,
        logging_dir=str(logging_dir / "logs-merge"),
        job_name=f"{job_name}-merge",
        depends=shards,
        **{k: v for k, v in opts.items() if k not in SLURM_ONLY_FOR_SHARDS},
    )
    merge_job.run()
