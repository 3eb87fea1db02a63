"""The integrator registry (``lagsolve.problem.methods``) is what the reader, the schema, the integrator,
the sweeps and the CLI use."""

from __future__ import annotations

import click

from lagsolve import cli, schemas
from lagsolve.numeric import integrate
from lagsolve.problem.methods import DEFAULT, EXPLICIT, METHODS
from lagsolve.sweep import rk


def _choices(command: click.Command, option: str) -> list[str]:
    (param,) = [p for p in command.params if p.name == option]
    assert isinstance(param.type, click.Choice)
    return list(param.type.choices)


def test_every_user_of_the_methods_reads_the_registry() -> None:
    """The CLI's --method choices, the JSON Schema enum, the integrator and the batched sweeps agree."""
    assert METHODS == ("DOP853", "RK45", "RK23", "Radau", "BDF", "LSODA")
    assert EXPLICIT == ("DOP853", "RK45", "RK23") and DEFAULT == "DOP853"
    assert _choices(cli.simulate, "method") == list(METHODS)
    assert _choices(cli.sweep, "method") == list(METHODS)
    simulation = schemas.input_schema()["properties"]["simulation"]["properties"]
    assert simulation["method"] == {"enum": list(METHODS)}
    assert integrate.METHODS == METHODS and integrate.EXPLICIT == EXPLICIT
    assert rk.METHODS == EXPLICIT
