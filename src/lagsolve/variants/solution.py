"""Each variant's worked solution (Markdown): its numbers, its key and its run, then the derivation's report,
which does not depend on the numbers and is rendered once for the whole set."""

from __future__ import annotations

from lagsolve.variants.key import Key


def _number(value: float) -> str:
    return f"{value:.6g}"


def _regime_lines(key: Key) -> list[str]:
    lines = []
    for contact, regime in key.regime.items():
        ratio = next((a.value for a in key.answers if a.name == f"least_static_{contact}"), None)
        why = f" (it needs a static coefficient of at least {_number(ratio)})" if ratio is not None else ""
        lines.append(f"- Contact `{contact}` {'is held' if regime == 'stick' else 'slides'} at t = 0{why}.")
    if key.released:
        lines.append("- A unilateral constraint lets go during the run (see the key).")
    return lines


def variant_markdown(name: str, index: int, count: int, values: dict[str, float], initial: dict[str, float],
                     key: Key, summary: str, report: str, figures: tuple[str, ...] = ()) -> str:
    """The solution page of variant ``index`` of ``count``."""
    lines = [f"# {name}: variant {index} of {count}", "", "## The numbers of this variant", "",
             "| quantity | value |", "|---|---|"]
    lines += [f"| `{k}` | {_number(v)} |" for k, v in values.items()]
    lines += [f"| `{k}` (t = 0) | {_number(v)} |" for k, v in initial.items()]
    lines += ["", "## Key", "", "| answer | value | what | verified by |", "|---|---|---|---|"]
    lines += [f"| `{a.name}` | {_number(a.value)} | {a.what} | {a.checked} |" for a in key.answers]
    regime = _regime_lines(key)
    if regime:
        lines += ["", *regime]
    lines += ["", "## Simulation", "", "```text", summary.rstrip(), "```"]
    lines += [line for name in figures for line in ("", f"![{name}]({name}.png)")]
    lines += ["", "## Worked solution", "",
              "The derivation below holds for every variant; put in the numbers above.", "", "---", ""]
    return "\n".join(lines) + "\n" + report
