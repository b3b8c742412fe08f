"""Executes a notebook cell by cell in a fresh kernel (nbclient), headless, and fails on the first
cell that raises: so the teaching notebook cannot go stale. The notebook file is not changed.
    run_notebook.py NOTEBOOK [TIMEOUT_SECONDS]"""
import os
import sys
import time

import nbformat
from nbclient import NotebookClient
from nbclient.exceptions import CellExecutionError

path = sys.argv[1]
timeout = int(sys.argv[2]) if len(sys.argv) > 2 else 120
os.environ.setdefault("MPLBACKEND", "Agg")
os.environ.setdefault("PYDEVD_DISABLE_FILE_VALIDATION", "1")  # ipykernel's debugger notes on frozen modules
# The kernel starts in the notebook's folder: PYTHONPATH's entries are made absolute first.
os.environ["PYTHONPATH"] = os.pathsep.join(os.path.abspath(p) for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p)
# The kernel is this interpreter (the one that has NumPy and the module), whatever `python3` is.
os.environ["PATH"] = os.path.dirname(sys.executable) + os.pathsep + os.environ.get("PATH", "")
notebook = nbformat.read(path, as_version=4)
client = NotebookClient(notebook, timeout=timeout, kernel_name="python3",
                        resources={"metadata": {"path": os.path.dirname(os.path.abspath(path))}})
start = time.monotonic()
try:
    client.execute()
except CellExecutionError as error:
    print(error, file=sys.stderr)
    sys.exit(1)
cells = sum(1 for c in notebook.cells if c.cell_type == "code")
print(f"{path}: {cells} code cells ran without error in {time.monotonic() - start:.1f} s")
