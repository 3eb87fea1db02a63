"""Sweeps on a local Dask cluster: the same table as in one process, and no worker process left behind."""

from __future__ import annotations

import contextlib
import socket
import subprocess
import sys
import threading
from pathlib import Path

import pytest

pandas = pytest.importorskip("pandas")
pytest.importorskip("distributed")
psutil = pytest.importorskip("psutil")

from lagsolve.sweep.api import sweep  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
DOUBLE = ROOT / "problems" / "double_pendulum.yaml"
SPRING = ROOT / "problems" / "spring_on_rough_floor.yaml"


def _children() -> set[int]:
    """Child processes, without Python's multiprocessing resource tracker (one per interpreter, started on
    first use of multiprocessing and ended with it; it runs no task)."""
    found = set()
    for child in psutil.Process().children(recursive=True):
        try:
            if "multiprocessing.resource_tracker" not in " ".join(child.cmdline()):
                found.add(child.pid)
        except psutil.NoSuchProcess:
            pass
    return found


@pytest.mark.slow
def test_a_sweep_on_workers_starts_while_port_8787_is_taken() -> None:
    """Dask's usual dashboard port is taken (another sweep's cluster, a notebook's): the local cluster starts
    anyway, on a free port, with no warning (warnings are errors in the tests), and gives the in-process table.
    (With dashboard_address=None the scheduler still took 8787: two sweeps at once failed or warned.)"""
    import socket

    with socket.socket() as taken:
        try:
            taken.bind(("0.0.0.0", 8787))
        except OSError:
            pytest.skip("port 8787 is in use here already")
        taken.listen()
        options = {"grid": {"x": [0.1, 0.5]}, "t_end": 2.0}
        pandas.testing.assert_frame_equal(sweep(SPRING, **options), sweep(SPRING, workers=2, **options),
                                          check_exact=True)


def test_two_workers_give_the_table_of_one_process() -> None:
    """With 2 worker processes and small chunks, batched and per-run problems give identical tables,
    progress reaches every run, and the cluster's processes are gone afterwards."""
    before = _children()
    options = {"grid": {"theta1": "-2.5:2.5:3", "theta2": "0.3:2.7:3"}, "t_end": 2.0, "poincare": "theta1=0"}
    local = sweep(DOUBLE, **options)
    seen: list[tuple[int, int]] = []
    distributed = sweep(DOUBLE, workers=2, chunk_size=2, progress=lambda done, total: seen.append((done, total)),
                        **options)
    pandas.testing.assert_frame_equal(local, distributed, check_exact=True)
    assert seen[-1] == (9, 9) and len(seen) == 5
    friction = {"grid": {"x": [0.1, 0.5, 1.0]}, "t_end": 6.0}
    pandas.testing.assert_frame_equal(sweep(SPRING, **friction), sweep(SPRING, workers=2, chunk_size=1, **friction),
                                      check_exact=True)
    psutil.wait_procs([psutil.Process(pid) for pid in _children() - before if psutil.pid_exists(pid)], timeout=10)
    assert _children() - before == set()


@pytest.mark.slow
def test_an_existing_cluster_through_the_command_line(tmp_path: Path) -> None:
    """--scheduler ADDRESS runs the chunks on a cluster started elsewhere, and leaves it running."""
    import logging

    from click.testing import CliRunner
    from distributed import LocalCluster

    from lagsolve.cli import main

    with LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=":0",
                      silence_logs=logging.ERROR) as cluster:
        out = tmp_path / "s.csv"
        result = CliRunner().invoke(main, ["sweep", str(DOUBLE), "--grid", "theta1=0.1:0.5:3", "--t-end", "0.5",
                                           "--scheduler", cluster.scheduler_address, "-o", str(out)])
        assert result.exit_code == 0, result.output
        assert cluster.status.name == "running"
    assert len(pandas.read_csv(out)) == 3


def _serve(answer: bytes | None) -> tuple[socket.socket, threading.Event, threading.Thread]:
    """A local TCP server that accepts every connection and then sends ``answer`` (None: never answers)."""
    server = socket.create_server(("127.0.0.1", 0))
    stop = threading.Event()
    held: list[socket.socket] = []

    def loop() -> None:
        server.settimeout(0.2)
        while not stop.is_set():
            try:
                connection, _ = server.accept()
            except TimeoutError:
                continue
            except OSError:
                return
            held.append(connection)
            if answer is not None:
                with contextlib.suppress(OSError):
                    connection.sendall(answer)
        for connection in held:
            connection.close()

    thread = threading.Thread(target=loop, daemon=True)
    thread.start()
    return server, stop, thread


#: the command in a child process, with a 1-second scheduler time-out, so that a hang fails the test (timeout)
_SWEEP = ("import importlib, sys; importlib.import_module('lagsolve.sweep.cluster').CONNECT_TIMEOUT = 1.0; "
          "from lagsolve.cli import main; main(sys.argv[1:])")


@pytest.mark.parametrize(("answer", "said"), [
    (None, "accepts connections but sent nothing within 1 s"),
    (b"HTTP/1.0 400 Bad Request\r\nContent-Type: text/html\r\n\r\n<html></html>",
     "answers, but not as a Dask scheduler (it sent b'HTTP/1.0'"),
], ids=["silent", "http"])
def test_a_scheduler_address_that_is_no_scheduler_exits_2(tmp_path: Path, answer: bytes | None, said: str) -> None:
    """--scheduler to a server that accepts and never answers, or that answers HTTP, exits 2 with the address
    and the fix, instead of hanging or failing with a traceback (MemoryError reading the answer as a length)."""
    server, stop, thread = _serve(answer)
    address = f"tcp://127.0.0.1:{server.getsockname()[1]}"
    try:
        result = subprocess.run([sys.executable, "-c", _SWEEP, "sweep", str(DOUBLE), "--grid", "theta1=0.1:0.5:2",
                                 "--t-end", "0.1", "--scheduler", address, "-o", str(tmp_path / "s.csv")],
                                capture_output=True, text=True, timeout=120, check=False)
    finally:
        stop.set()
        thread.join(timeout=10)
        server.close()
    assert result.returncode == 2, result.stderr
    assert f"--scheduler: {address} {said}" in result.stderr
    assert "e.g. tcp://10.0.0.1:8786" in result.stderr and "Traceback" not in result.stderr
    assert not (tmp_path / "s.csv").exists()


def test_a_scheduler_address_that_refuses_or_is_not_tcp_exits_2() -> None:
    """Nothing listening, or a scheme other than tcp://, is a SpecError naming the address."""
    from lagsolve.errors import SpecError
    from lagsolve.sweep.cluster import check_scheduler

    with socket.create_server(("127.0.0.1", 0)) as closed:
        port = closed.getsockname()[1]
    with pytest.raises(SpecError, match=rf"cannot connect to tcp://127.0.0.1:{port} within 1 s"):
        check_scheduler(f"tcp://127.0.0.1:{port}", timeout=1.0)
    with pytest.raises(SpecError, match="only tcp:// addresses are supported, found ucx://"):
        check_scheduler("ucx://127.0.0.1:8786", timeout=1.0)


@pytest.mark.slow
def test_a_real_scheduler_passes_the_check_and_one_without_workers_is_refused(
        monkeypatch: pytest.MonkeyPatch) -> None:
    """A running Dask scheduler's own address passes the handshake check unchanged; a sweep on it while it has no
    worker (which would wait for ever) is a SpecError saying so."""
    import importlib
    import logging

    from distributed import LocalCluster

    from lagsolve.errors import SpecError

    cluster_module = importlib.import_module("lagsolve.sweep.cluster")
    monkeypatch.setattr(cluster_module, "CONNECT_TIMEOUT", 1.0)
    with LocalCluster(n_workers=0, processes=False, protocol="tcp", dashboard_address=":0",
                      silence_logs=logging.ERROR) as cluster:
        address = cluster.scheduler_address
        assert cluster_module.check_scheduler(address, timeout=5.0) == address
        with pytest.raises(SpecError, match=f"the Dask scheduler at {address} has no worker .*dask worker {address}"):
            sweep(DOUBLE, grid={"theta1": [0.1]}, t_end=0.1, scheduler=address)


def test_a_ctrl_c_while_workers_start_is_held_not_lost() -> None:
    """Inside interrupts_held SIGINT is ignored (what worker processes started there inherit) and blocked here;
    a Ctrl-C meanwhile raises KeyboardInterrupt as the block ends, and the handler is back afterwards. (The
    signal goes to this thread: pytest's process has other threads, such as BLAS's, that do not block it.)"""
    import signal

    from lagsolve.sweep.cluster import interrupts_held

    handler = signal.getsignal(signal.SIGINT)
    reached = []
    with pytest.raises(KeyboardInterrupt), interrupts_held():
        assert signal.getsignal(signal.SIGINT) == signal.SIG_IGN
        signal.pthread_kill(threading.main_thread().ident or 0, signal.SIGINT)
        reached.append("after the signal")
    assert reached == ["after the signal"]
    assert signal.getsignal(signal.SIGINT) == handler


@pytest.mark.slow
def test_ctrl_c_during_a_sweep_with_workers_exits_130_quietly(tmp_path: Path) -> None:
    """SIGINT to the command's whole process group (what Ctrl-C in a terminal does), once its two workers run:
    exit 130 with the one line "interrupted" (no traceback from the command or from a worker), no table
    written, and no process of it left."""
    import os
    import signal
    import time

    out = tmp_path / "s.csv"
    command = [sys.executable, "-m", "lagsolve", "sweep", str(DOUBLE), "--grid", "theta1=0.1:1.5:40", "--grid",
               "theta2=0.1:1.5:40", "--t-end", "50", "--workers", "2", "--engine", "numpy", "-o", str(out)]
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                               start_new_session=True)
    try:
        parent = psutil.Process(process.pid)
        workers: list[psutil.Process] = []
        deadline = time.monotonic() + 120
        while len(workers) < 2 and process.poll() is None and time.monotonic() < deadline:
            time.sleep(0.2)
            workers = [c for c in parent.children(recursive=True) if "spawn_main" in " ".join(c.cmdline())]
        assert len(workers) >= 2, "the workers did not start"
        family = parent.children(recursive=True)
        time.sleep(1.0)  # the workers are at work (or still connecting: the signal is then held, not lost)
        os.killpg(process.pid, signal.SIGINT)
        _, stderr = process.communicate(timeout=120)
    finally:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()
    assert process.returncode == 130, stderr
    assert stderr == "interrupted\n"
    assert not out.exists()
    _, alive = psutil.wait_procs(family, timeout=30)
    assert alive == []


@pytest.mark.slow
def test_ctrl_c_during_a_compiled_sweep_on_threads_exits_130_quietly(tmp_path: Path) -> None:
    """The compiled path's workers are threads of the command: Ctrl-C stops it with exit 130 and the one line
    "interrupted" (the chunks not started are cancelled), no table written, no process left."""
    import os
    import signal
    import time

    pytest.importorskip("numba")
    out = tmp_path / "s.csv"
    command = [sys.executable, "-m", "lagsolve", "sweep", str(DOUBLE), "--grid", "theta1=0.1:1.5:40", "--grid",
               "theta2=0.1:1.5:40", "--t-end", "500", "--workers", "2", "--engine", "compiled", "-o", str(out)]
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                               start_new_session=True)
    try:
        time.sleep(8.0)  # derived, compiled (or loaded), at work
        family = psutil.Process(process.pid).children(recursive=True)
        os.killpg(process.pid, signal.SIGINT)
        _, stderr = process.communicate(timeout=120)
    finally:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()
    assert process.returncode == 130, stderr
    assert stderr == "interrupted\n"
    assert not out.exists()
    _, alive = psutil.wait_procs(family, timeout=30)
    assert alive == []
