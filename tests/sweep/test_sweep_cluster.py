"""Sweeps on a local Dask cluster: the same table as in one process, and no worker process left behind."""

from __future__ import annotations

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

    with LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None,
                      silence_logs=logging.ERROR) as cluster:
        out = tmp_path / "s.csv"
        result = CliRunner().invoke(main, ["sweep", str(DOUBLE), "--grid", "theta1=0.1:0.5:3", "--t-end", "0.5",
                                           "--scheduler", cluster.scheduler_address, "-o", str(out)])
        assert result.exit_code == 0, result.output
        assert cluster.status.name == "running"
    assert len(pandas.read_csv(out)) == 3
