"""How a sweep is cut into chunks by default (lagsolve.sweep.api.default_chunk_size)."""

from __future__ import annotations

import math

import pytest

from lagsolve.sweep.api import default_chunk_size


@pytest.mark.parametrize("total", [1, 63, 512, 1000, 10_000, 100_000, 1_000_000])
@pytest.mark.parametrize("workers", [0, 1, 2, 8])
def test_threads_get_about_sixteen_chunks_each_of_at_least_64_runs(total: int, workers: int) -> None:
    size = default_chunk_size(total, workers, threads=True)
    chunks = math.ceil(total / size)
    assert 64 <= size <= 1024
    assert chunks <= 16 * max(1, workers) or size == 1024
    if total >= 16 * 64 * max(1, workers) and size < 1024:
        assert chunks >= 16 * max(1, workers) - 1  # the runs are spread over at least that many chunks


@pytest.mark.parametrize("total", [1, 7, 1000, 10_000, 1_000_000])
def test_processes_get_about_four_chunks_each(total: int) -> None:
    size = default_chunk_size(total, 2, threads=False)
    assert 1 <= size <= 1024
    assert math.ceil(total / size) <= 8 or size == 1024
    assert default_chunk_size(10_000, 2, threads=True) == 313  # 32 chunks for 10⁴ runs on two threads
