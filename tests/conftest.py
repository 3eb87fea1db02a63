"""Session-wide fixtures: each shipped problem is derived, and its reports rendered, once per test session.

A derivation is frozen and a :class:`~lagsolve.app.pipeline.Reports` is only read, so the tests that
merely read them share one copy (`make test` derived each problem four or more times before). A test
that derives with other options (a budget, ``analysis=False``) or checks the derivation itself still
derives on its own.
"""

from __future__ import annotations

import gc
import os
import tempfile
from collections.abc import Callable
from pathlib import Path

import pytest

# the compiled sweep's machine code, kept between the test processes (a user opts in the same way; unset, lagsolve
# writes nothing outside the output folder and compiles in memory)
os.environ.setdefault("LAGSOLVE_CACHE", str(Path(tempfile.gettempdir()) / f"lagsolve-test-cache-{os.getuid()}"))
# SymPy's caches as the command sizes them (lagsolve/cli.py), read when SymPy is first imported, after this: the
# tests derive as the command does, and a worker that derives hundreds of problems finds more in them
os.environ.setdefault("SYMPY_CACHE_SIZE", "50000")

import mechanics_support
from lagsolve.app.pipeline import Reports, reports_of
from lagsolve.cli import COLLECTOR
from lagsolve.mechanics import stages
from lagsolve.mechanics.derivation import Derivation
from mechanics_support import derived_file

# the collector as the command sets it (lagsolve/cli.py): the tests derive as the command does (5-8 % less CPU
# deriving 20 shipped problems in one process)
gc.set_threshold(*COLLECTOR)

PROBLEMS = Path(__file__).resolve().parents[1] / "problems"

#: the formats of the shared reports: those with golden files
FORMATS = ("md", "tex", "json")


@pytest.fixture(scope="session", autouse=True)
def _share_derivations(tmp_path_factory: pytest.TempPathFactory) -> None:
    """Under pytest-xdist, the workers share the shipped problems' derivations through a folder of the session's
    temporary folder (each problem is derived by one worker; pytest removes old sessions' folders)."""
    if os.environ.get("PYTEST_XDIST_WORKER"):
        folder = tmp_path_factory.getbasetemp().parent / "derivations"
        folder.mkdir(exist_ok=True)
        mechanics_support.SHARED[:] = [folder]


@pytest.fixture(scope="session")
def shipped_derivation() -> Callable[[str], Derivation]:
    """``derive`` of ``problems/<name>.yaml`` with the default budget, computed once per session."""
    return derived_file


@pytest.fixture(scope="session")
def shipped_reports() -> Callable[[str], Reports]:
    """What ``derive_file(problems/<name>.yaml, FORMATS)`` gives (what ``lagsolve derive`` writes), rendered once per
    session from the shared derivation (``derive_file`` itself derives again, in a child process; the command-line
    tests run it)."""
    cache: dict[str, Reports] = {}

    def reports(name: str) -> Reports:
        if name not in cache:
            cache[name] = reports_of(derived_file(name), PROBLEMS / f"{name}.yaml", FORMATS)
        return cache[name]

    return reports


#: the stages that spent their whole share of the budget and gave up, during the test running now
_SPENT: list[str] = []
_RUN = stages.Stages.run


def _watched_run(self: stages.Stages, stage: str, fn: Callable[..., object], *args: object,
                 **kwargs: object) -> object:
    """:meth:`Stages.run`, noting each stage that ran out of its share of the budget."""
    before = len(self.notes)
    result = _RUN(self, stage, fn, *args, **kwargs)  # type: ignore[arg-type]
    _SPENT.extend(f"{n.stage}: {n.reason}" for n in self.notes[before:] if n.reason.startswith("ran out"))
    return result


stages.Stages.run = _watched_run  # type: ignore[assignment,method-assign]


@pytest.fixture(autouse=True)
def no_stage_spends_its_share(request: pytest.FixtureRequest) -> object:
    """Every problem a test derives finishes each stage or declines it at once (issue 28): a stage that spends
    its whole share of the CPU budget and then gives up fails the test, unless the test is marked ``budget``
    (it gives a tiny budget on purpose)."""
    _SPENT.clear()
    yield
    if _SPENT and request.node.get_closest_marker("budget") is None:
        spent, _SPENT[:] = list(_SPENT), []
        pytest.fail("a stage ran out of its share of the CPU budget instead of declining at once: "
                    + "; ".join(spent), pytrace=False)


#: a test function run over at least this many shipped problems runs the whole problem library: it is marked
#: slow, so `make test-fast` leaves it out (`make test` runs it)
LIBRARY = 10


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """Mark ``slow`` every test function parametrized over the problem library (whatever its parameter is
    called): deriving every shipped problem is most of the suite's time."""
    names = {p.stem for p in PROBLEMS.glob("*.yaml")}
    over: dict[tuple[str, str], list[pytest.Item]] = {}
    for item in items:
        spec = getattr(item, "callspec", None)
        if spec is None:
            continue
        values = [v if isinstance(v, str) else getattr(v, "stem", None) for v in spec.params.values()]
        if any(isinstance(v, str) and (v in names or Path(v).stem in names) for v in values):
            over.setdefault((item.nodeid.split("::")[0], getattr(item, "originalname", item.name)), []).append(item)
    for group in over.values():
        if len(group) >= LIBRARY:
            for item in group:
                item.add_marker(pytest.mark.slow)
    items.sort(key=lambda item: getattr(item, "originalname", item.name) not in LONGEST)  # stable: the rest keep order


#: the tests that take longest (10-60 s each on the 2-core machine): run first, so that under pytest-xdist no
#: worker is left running one of them alone at the end (a scheduling hint only: a name not found changes nothing)
LONGEST = frozenset({
    "test_200_tube_variants_pass_their_keys_and_the_closed_form",
    "test_cartesian_pendulum_stays_on_its_rod_for_1000_periods",
    "test_animate_and_show", "test_tables_do_not_depend_on_hash_seed", "test_two_workers_give_the_table_of_one_process",
    "test_same_seed_same_bytes_whatever_the_hash_seed", "test_bench_simulate_reports_a_baseline_timeout",
    "test_several_coupled_contacts_state_the_system_they_solve", "test_small_pendulum_period",
    "test_frictionless_bead_conserves_energy_for_100_periods", "test_without_projection_the_rod_drifts",
    "test_a_large_chain_reads_as_a_textbook_writes_it", "test_summary_does_not_depend_on_hash_seed",
})
