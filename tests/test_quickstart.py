"""`examples/quickstart.ipynb` runs from top to bottom in a Jupyter kernel and shows rich results."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOK = ROOT / "examples" / "quickstart.ipynb"
KERNEL = "lagsolve-test"


def _kernelspec(folder: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A kernel that runs this very Python (the one with lagsolve installed), found before any other."""
    spec = folder / "kernels" / KERNEL
    spec.mkdir(parents=True)
    (spec / "kernel.json").write_text(json.dumps({
        "argv": [sys.executable, "-m", "ipykernel_launcher", "-f", "{connection_file}"],
        "display_name": "lagsolve test", "language": "python"}))
    monkeypatch.setenv("JUPYTER_PATH", str(folder))


def _kernel_starts() -> str:
    """"" when the test kernel starts here, else why not."""
    from jupyter_client.manager import start_new_kernel

    try:
        manager, client = start_new_kernel(kernel_name=KERNEL, startup_timeout=120)
    except Exception as exc:  # noqa: BLE001 - any failure to start means the test cannot run here
        return f"{type(exc).__name__}: {exc}"
    client.stop_channels()
    manager.shutdown_kernel(now=True)
    return ""


@pytest.mark.slow
def test_quickstart_notebook_executes(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Every cell runs without error; the derivation shows as LaTeX, Markdown and HTML, the run as HTML."""
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    pytest.importorskip("ipykernel")
    _kernelspec(tmp_path, monkeypatch)
    reason = _kernel_starts()
    if reason:
        pytest.skip(f"a Jupyter kernel ({sys.executable}) could not start here, so the notebook was not run: {reason}")
    notebook = nbformat.read(NOTEBOOK, as_version=4)
    client = nbclient.NotebookClient(notebook, timeout=600, kernel_name=KERNEL,
                                     resources={"metadata": {"path": str(NOTEBOOK.parent)}})
    client.execute()
    code = [cell for cell in notebook.cells if cell.cell_type == "code"]
    shown = [set(out.get("data", {})) for cell in code for out in cell.outputs if out.output_type == "execute_result"]
    assert {"text/latex", "text/markdown", "text/html"} <= shown[0]  # the derivation
    assert any("text/html" in kinds and "text/latex" not in kinds for kinds in shown[3:])  # the trajectory
    assert any("image/png" in kinds for kinds in shown)  # a figure shows inline (lagsolve picks no backend)
    errors = [out for cell in code for out in cell.outputs if out.output_type == "error"]
    assert errors == []
