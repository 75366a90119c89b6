"""The sharded jobs' local executor: a killed job leaves no worker running; a worker killed in the
middle of a shard ends the job with an error instead of a hang."""

import contextlib
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

from lerobot_activearena.sharding import _alive

JOB = textwrap.dedent(
    """
    import os, sys, time
    from pathlib import Path
    from datatrove.pipeline.base import PipelineStep
    from lerobot_activearena.sharding import run_local

    class Sleep(PipelineStep):
        name, type = "sleep", "TEST"

        def run(self, data=None, rank=0, world_size=1):
            Path(sys.argv[1], f"worker{rank}.pid").write_text(str(os.getpid()))
            time.sleep(120)
            return iter(())

    if __name__ == "__main__":
        run_local(Sleep(), 2, 2, Path(sys.argv[1]) / "logs")
    """
)


def _wait(condition, timeout_s: float) -> bool:
    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        if condition():
            return True
        time.sleep(0.2)
    return condition()


def test_killing_a_job_ends_its_workers(tmp_path):
    """Killing the main process of a two-worker job (as a user stops a build or an evaluation) ends
    the pool's workers too; left running, they would go on writing into the job's folder."""
    script = tmp_path / "job.py"
    script.write_text(JOB)
    main = subprocess.Popen(
        [sys.executable, str(script), str(tmp_path)], stderr=subprocess.DEVNULL, start_new_session=True
    )
    try:
        assert _wait(lambda: len(list(tmp_path.glob("worker*.pid"))) == 2, 120), "the workers never started"
        pids = [int(p.read_text()) for p in tmp_path.glob("worker*.pid")]
        assert all(_alive(p) and p != main.pid for p in pids)
        main.send_signal(signal.SIGTERM)
        main.wait(30)
        assert _wait(lambda: not any(_alive(p) for p in pids), 10), "workers outlived the killed job"
    finally:  # whatever is left of the job's process group (datatrove's idle queue manager outlives it)
        with contextlib.suppress(ProcessLookupError):
            os.killpg(main.pid, signal.SIGKILL)


def test_a_zombie_counts_as_gone():
    """A killed main process that its parent has not reaped yet is gone for the workers."""
    child = subprocess.Popen([sys.executable, "-c", "pass"])
    assert _wait(lambda: Path(f"/proc/{child.pid}/stat").read_text().rsplit(")", 1)[1].split()[0] == "Z", 30)
    assert not _alive(child.pid)
    child.wait()
    assert not _alive(child.pid) and _alive(os.getpid())


def _run_whole_group(cmd: list[str], timeout_s: float) -> subprocess.CompletedProcess:
    """Runs `cmd` in its own process group and kills what is left of that group afterwards, so a
    job that hangs past the timeout leaves no worker or queue manager behind."""
    proc = subprocess.Popen(
        cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True
    )
    try:
        out, err = proc.communicate(timeout=timeout_s)
    finally:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(proc.pid, signal.SIGKILL)
    return subprocess.CompletedProcess(cmd, proc.returncode, out, err)


DYING = textwrap.dedent(
    """
    import os, signal, sys, time
    from pathlib import Path
    from datatrove.pipeline.base import PipelineStep
    from lerobot_activearena.sharding import run_local

    class DieOnRankOne(PipelineStep):
        name, type = "die", "TEST"

        def run(self, data=None, rank=0, world_size=1):
            if rank == 1 and not Path(sys.argv[1], "died").exists():
                Path(sys.argv[1], "died").write_text(str(os.getpid()))
                os.kill(os.getpid(), signal.SIGKILL)  # as the kernel or a native crash ends a worker
            time.sleep(0.5)
            return iter(())

    if __name__ == "__main__":
        import faulthandler
        faulthandler.dump_traceback_later(120, exit=True)  # a hang ends with every thread's stack
        if "--sigint-ignored" in sys.argv:  # as in a job a script starts in the background (`cmd &`)
            signal.signal(signal.SIGINT, signal.SIG_IGN)
        if "--slow-cleanup" in sys.argv:  # as a loaded machine stretches the pool's and the manager's shutdown
            import multiprocess.managers, multiprocess.pool
            def after(seconds, f):
                def slow(*args, **kwargs):
                    time.sleep(seconds)
                    return f(*args, **kwargs)
                return slow
            pool, manager = multiprocess.pool.Pool, multiprocess.managers.BaseManager
            pool.terminate = after(3, pool.terminate)
            manager._finalize_manager = staticmethod(after(5, manager._finalize_manager))
        run_local(DieOnRankOne(), 3, 2, Path(sys.argv[1]) / "logs")
    """
)


def test_a_worker_killed_mid_shard_ends_the_job_with_an_error_and_a_rerun_finishes_it(tmp_path):
    """A pool worker that dies without a Python error (SIGKILL) used to leave the job waiting for its
    shard for ever; the job now stops with an error that names the shard, keeps the finished shards,
    and the same command run again completes only the missing one. The job ignores SIGINT, as one
    started in the background by a script does: the watch must not rely on KeyboardInterrupt."""
    script = tmp_path / "job.py"
    script.write_text(DYING)
    run = [sys.executable, str(script), str(tmp_path)]
    first = _run_whole_group([*run, "--sigint-ignored"], 180)
    assert first.returncode != 0
    assert "WorkerDiedError" in first.stderr and "shard 1 (pid" in first.stderr, first.stderr[-2000:]
    assert "run the same command again to resume" in first.stderr
    completions = tmp_path / "logs" / "completions"
    assert "00001" not in {p.name for p in completions.glob("*")}
    done_before = {p.name: p.stat().st_mtime_ns for p in completions.glob("*")}
    second = _run_whole_group(run, 180)
    assert second.returncode == 0, second.stderr[-2000:]
    assert sorted(p.name for p in completions.glob("*")) == ["00000", "00001", "00002"]
    assert all(completions.joinpath(n).stat().st_mtime_ns == t for n, t in done_before.items())


def test_a_dead_worker_ends_the_job_even_when_its_cleanup_is_slow(tmp_path):
    """The main thread is interrupted only while it waits on the pool: an interrupt that landed in the
    pool's or the queue manager's shutdown (seconds long on a loaded machine) left the manager process
    running, and the exiting job (and whoever reads its output) waited for it for ever."""
    script = tmp_path / "job.py"
    script.write_text(DYING)
    first = _run_whole_group([sys.executable, str(script), str(tmp_path), "--slow-cleanup"], 90)
    assert first.returncode != 0
    assert "WorkerDiedError" in first.stderr and "shard 1 (pid" in first.stderr, first.stderr[-2000:]
