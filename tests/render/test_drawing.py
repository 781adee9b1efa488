"""Figures drawn in a helper process (robosolve.render.drawing): the same PNGs as drawn inline,
the same note when a figure fails, inline drawing when the helper is gone, no process left.

The reference is robosolve's own inline drawing (what `batch` and the golden files use): these
tests check that moving the drawing to another process changes no byte, not the figures' content
(tests/render/test_reports.py looks at that)."""

from __future__ import annotations

import multiprocessing
import pickle
from pathlib import Path

import pytest

from robosolve.core.prose import Num, Text
from robosolve.load.loader import load_problem
from robosolve.run.pipeline import render_files, solve_problem
from robosolve.render.drawing import BackgroundFigures, InlineFigures, figure_drawer
from robosolve.solvers.base import FigureSpec

PROBLEMS = Path(__file__).resolve().parents[2] / "problems"


@pytest.fixture(autouse=True)
def _no_other_threads(monkeypatch):
    """Earlier tests of the session may leave a thread behind (a Dask client's event loop),
    and a helper is then not forked at all (robosolve.core.processes): these tests fork anyway."""
    import threading

    monkeypatch.setattr(threading, "active_count", lambda: 1)


@pytest.fixture(scope="module")
def reports():
    # a robot drawing (one-link-arm) and IK solutions labelled with Text/Num (ik-planar-3r)
    return [solve_problem(load_problem(PROBLEMS / name)) for name in ("one-link-arm.yaml", "ik-planar-3r.yaml")]


def _pngs(files):
    return {k: v for k, v in files.items() if k.endswith(".png")}


def test_prose_survives_pickling():
    text = Text("#1: ", Text("q1=", Num(0.5, digits=3)), " (rejected)")
    again = pickle.loads(pickle.dumps(text))
    assert again == text and type(again) is Text and type(again[1]) is Text


def test_background_pngs_are_the_inline_ones(reports):
    with BackgroundFigures() as figures:
        for report in reports:
            figures.submit([s for a in report.answers for s in a.figures])
        background = [render_files(r, figures=figures) for r in reports]
        assert figures._process is not None and not figures._lost      # drawn by the helper
        helper = figures._process
    inline = [render_files(r) for r in reports]
    for got, want in zip(background, inline):
        assert _pngs(want) and _pngs(got) == _pngs(want)
        assert got == want
    assert not helper.is_alive() and helper.exitcode is not None


def _broken_spec():
    return FigureSpec(name="broken", kind="robot", title="t", data={"drawings": "not a drawing"})


def test_a_failing_figure_gives_the_same_reason_both_ways():
    reasons = []
    for figures in (InlineFigures(), BackgroundFigures()):
        with figures:
            spec = _broken_spec()
            figures.submit([spec])
            with pytest.raises(Exception) as info:
                figures.png(spec)
            reasons.append((type(info.value).__name__, str(info.value)))
    assert reasons[0] == reasons[1] and reasons[0][0] == "FigureFailed"


def test_a_dead_helper_means_inline_drawing(reports):
    report = reports[0]
    specs = [s for a in report.answers for s in a.figures]
    with BackgroundFigures() as figures:
        figures._start()
        figures._process.kill()
        figures._process.join()
        figures.submit(specs)
        got = render_files(report, figures=figures)
    assert _pngs(got) == _pngs(render_files(report))


def test_no_helper_without_figures_or_cores(monkeypatch):
    with BackgroundFigures() as figures:
        figures.submit([])
        assert figures._process is None
    monkeypatch.setattr("robosolve.core.processes.usable_cores", lambda: 1)
    assert isinstance(figure_drawer(background=True), InlineFigures)
    assert not isinstance(figure_drawer(background=True), BackgroundFigures)
    assert not multiprocessing.active_children()


def test_the_helper_ends_with_its_parent(tmp_path):
    """A parent killed outright (no `finally`) leaves no helper behind."""
    import os
    import subprocess
    import sys
    import time

    script = (
        "import os, sys\n"
        "from robosolve.render.drawing import BackgroundFigures\n"
        "from robosolve.solvers.base import FigureSpec\n"
        "f = BackgroundFigures()\n"
        "f.submit([FigureSpec(name='r', kind='robot', title='t', data={'drawings': []})])\n"
        "print(f._process.pid, flush=True)\n"
        "os.kill(os.getpid(), 9)\n")
    out = tmp_path / "pid"           # a file, not a pipe: a helper left alive would hold a pipe open
    with open(out, "w") as stdout:
        subprocess.run([sys.executable, "-c", script], stdout=stdout, cwd=tmp_path)
    helper = int(out.read_text().split()[0])
    for _ in range(200):            # a liveness wait (up to 20 s), not a timing
        try:
            os.kill(helper, 0)
        except ProcessLookupError:
            break
        try:                        # a zombie reaped by init is gone as well
            if open(f"/proc/{helper}/stat").read().split()[2] == "Z":
                break
        except OSError:
            break
        time.sleep(0.1)
    else:
        os.kill(helper, 9)
        pytest.fail("the drawing helper outlived its parent")


def test_a_failing_figure_is_named_in_the_texts(reports):
    """results.json and report.md are printed before the PNGs are collected: when a figure
    fails they are printed again, with its note and without its path (as when printed after)."""
    import copy
    import json

    from robosolve.render.markdown import render_report
    from robosolve.render.results_json import render_results_json

    # a copy of the report whose answers' lists may change (the report holds the problem's
    # model, read-only mappings included, which need no copy)
    report = copy.copy(reports[0])
    report.answers = [copy.copy(a) for a in report.answers]
    for a in report.answers:
        a.figures, a.notes = list(a.figures), list(a.notes)
    answer = next(a for a in report.answers if a.figures)
    good = [s for s in answer.figures]
    answer.figures.append(_broken_spec())
    files = render_files(report)
    record = json.loads(files["results.json"])["answers"][answer.id]
    assert record["figures"] == [f"figures/{answer.id}-{s.name}.png" for s in good]
    assert any("figure broken could not be drawn" in n for n in answer.notes)
    assert "figure broken could not be drawn" in files["report.md"].decode()
    paths = {a.id: [f"figures/{a.id}-{s.name}.png" for s in a.figures if s.name != "broken"]
             for a in report.answers if a.figures}
    assert files["results.json"].decode() == render_results_json(report, paths)
    assert files["report.md"].decode() == render_report(report, paths)
    assert "figures/" + answer.id + "-broken.png" not in files
