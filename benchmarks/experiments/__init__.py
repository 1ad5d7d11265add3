"""Experiments other issues add to ``make bench``: each module of this folder is one section of
``docs/performance.md`` (see README.md in this folder for the contract).

``discover()`` lists the modules (``*.py`` not starting with ``_``, in name order); ``run_all(quick)``
imports and runs each, and returns one record per module: ``name``, ``title``, ``seconds`` and either
``rows`` + ``summary`` or ``error`` (a module that fails to import, raises, or returns something else
than the contract is skipped with a note; the rest of the benchmark goes on).
"""

from __future__ import annotations

import importlib
import sys
import time
import traceback
from pathlib import Path

FOLDER = Path(__file__).resolve().parent


def discover() -> list[str]:
    """Module names of the experiments, in file-name order."""
    return sorted(p.stem for p in FOLDER.glob("*.py") if not p.name.startswith("_"))


def _checked(result) -> tuple[list[dict], str]:
    if not isinstance(result, dict) or not isinstance(result.get("rows"), list):
        raise TypeError("run() must return a dict with 'rows' (a list of dicts) and 'summary' (a str)")
    rows = result["rows"]
    if not all(isinstance(r, dict) for r in rows):
        raise TypeError("every row must be a dict (column name -> value)")
    summary = result.get("summary", "")
    if not isinstance(summary, str):
        raise TypeError("'summary' must be a str")
    return rows, summary


def run_one(name: str, quick: bool) -> dict:
    """Import ``benchmarks.experiments.<name>`` and run it; never raises."""
    record = dict(name=name, title=name)
    start = time.perf_counter()
    try:
        module = importlib.import_module(f"{__name__}.{name}")
        record["title"] = str(getattr(module, "TITLE", name))
        if not callable(getattr(module, "run", None)):
            raise TypeError("the module defines no run(quick) function")
        record["rows"], record["summary"] = _checked(module.run(quick=quick))
    except Exception as exc:  # noqa: BLE001 - one experiment's failure is reported, not fatal
        frames = traceback.extract_tb(exc.__traceback__)
        where = f" ({Path(frames[-1].filename).name}:{frames[-1].lineno})" if frames else ""
        record["error"] = f"{type(exc).__name__}: {exc}{where}"
        record.pop("rows", None)
    record["seconds"] = time.perf_counter() - start
    return record


def run_all(quick: bool, log=print) -> list[dict]:
    records = []
    for name in discover():
        log(f"experiment {name}")
        record = run_one(name, quick)
        if "error" in record:
            log(f"  skipped: {record['error']}")
        records.append(record)
    return records


def print_run(run, quick: bool | None = None) -> None:
    """An experiment's ``python -m`` entry: ``run(quick)`` (``--quick`` on the command line unless ``quick`` is
    given), then its rows, one per line, and its summary."""
    result = run("--quick" in sys.argv if quick is None else quick)
    for row in result["rows"]:
        print(row)
    print(result["summary"])
