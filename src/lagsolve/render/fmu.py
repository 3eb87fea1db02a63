"""The ``modelDescription.xml`` of the exported FMU (FMI 2.0, Model Exchange).

Variables in value-reference order: the states (``q``, ``q_dot``: local, continuous, start values the
file's initial state), their derivatives ``der(<state>)``, the parameters (fixed, the file's values), the
outputs (named as the CSV of ``lagsolve simulate``). Names are escaped for XML; a name holding a character
XML 1.0 cannot carry, or two variables of one name, is refused.
"""

from __future__ import annotations

import hashlib
import math
import re
import uuid
from collections.abc import Sequence
from xml.sax.saxutils import escape

from lagsolve.render.c_module import Layout

_NOT_XML = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\ufffe\uffff]")


def attribute(text: str) -> str:
    """``text`` for a double-quoted XML attribute.

    Raises
    ------
    ValueError
        ``text`` holds a control character XML 1.0 cannot carry.
    """
    if _NOT_XML.search(text):
        raise ValueError(f"the name {text!r} holds a character XML cannot carry")
    return escape(text, {'"': "&quot;", "\n": "&#10;", "\r": "&#13;", "\t": "&#9;"})


def guid(*texts: str) -> str:
    """A GUID that depends only on the texts (the same sources give the same FMU)."""
    digest = hashlib.sha256("\0".join(texts).encode("utf-8")).digest()
    return "{" + str(uuid.UUID(bytes=digest[:16], version=4)) + "}"


def _real(value: float) -> str:
    return repr(float(value)) if math.isfinite(value) else ("NaN" if math.isnan(value) else
                                                              ("INF" if value > 0 else "-INF"))


def variable_names(names: Layout) -> list[str]:
    """Every variable's name in value-reference order (states, derivatives, parameters, outputs).

    Raises
    ------
    ValueError
        Two variables share a name.
    """
    out = [*names.states, *(f"der({s})" for s in names.states), *names.parameters, *names.outputs]
    seen: set[str] = set()
    for name in out:
        if name in seen:
            raise ValueError(f"two variables of the FMU are named {name!r}")
        seen.add(name)
    return out


def model_description(names: Layout, prefix: str, model: str, version: str, identifier: str, start: Sequence[float],
                      stop: float | None) -> str:
    """The XML's text; ``identifier`` is the GUID, ``start`` the states' start values."""
    nx = len(names.states)
    variables = variable_names(names)
    rows = []
    for i, name in enumerate(variables):
        head = f'    <ScalarVariable name="{attribute(name)}" valueReference="{i}"'
        if i < nx:
            rows.append(f'{head} causality="local" variability="continuous" initial="exact">'
                        f'<Real start="{_real(start[i])}"/></ScalarVariable>')
        elif i < 2 * nx:
            rows.append(f'{head} causality="local" variability="continuous" initial="calculated">'
                        f'<Real derivative="{i - nx + 1}"/></ScalarVariable>')
        elif i < 2 * nx + len(names.parameters):
            value = names.defaults[i - 2 * nx]
            rows.append(f'{head} causality="parameter" variability="fixed">'
                        f'<Real start="{_real(value)}"/></ScalarVariable>')
        else:
            rows.append(f'{head} causality="output" variability="continuous" initial="calculated">'
                        "<Real/></ScalarVariable>")
    outputs = [i + 1 for i in range(2 * nx + len(names.parameters), len(variables))]
    derivatives = [i + 1 for i in range(nx, 2 * nx)]
    experiment = f'  <DefaultExperiment startTime="0.0" stopTime="{_real(stop)}"/>' if stop else ""
    return "\n".join([
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<fmiModelDescription fmiVersion="2.0" modelName="{attribute(model)}" guid="{identifier}"',
        f'  description="equations of motion of {attribute(model)}: M qdd = F + A^T lambda; event indicators: '
        f'{attribute(", ".join(names.events) or "none")}"',
        f'  generationTool="lagsolve {attribute(version)}" variableNamingConvention="flat"',
        f'  numberOfEventIndicators="{len(names.events)}">',
        f'  <ModelExchange modelIdentifier="{prefix}" canGetAndSetFMUstate="false"',
        '    canSerializeFMUstate="false" providesDirectionalDerivative="false">',
        '    <SourceFiles>', f'      <File name="{prefix}.c"/>', f'      <File name="fmi2_{prefix}.c"/>',
        '    </SourceFiles>', '  </ModelExchange>',
        *([experiment] if experiment else []),
        "  <ModelVariables>", *rows, "  </ModelVariables>",
        "  <ModelStructure>",
        *(["    <Outputs>", *(f'      <Unknown index="{i}"/>' for i in outputs), "    </Outputs>"] if outputs else []),
        "    <Derivatives>", *(f'      <Unknown index="{i}"/>' for i in derivatives), "    </Derivatives>",
        "    <InitialUnknowns>", *(f'      <Unknown index="{i}"/>' for i in sorted(derivatives + outputs)),
        "    </InitialUnknowns>",
        "  </ModelStructure>",
        "</fmiModelDescription>", "",
    ])
