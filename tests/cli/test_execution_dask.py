"""Dask back-end: the same bytes as a local run, for `batch` and `variants`.

One LocalCluster of two worker processes for the whole module (started by the same helper
as `--scheduler local`); the commands reach it through its tcp:// address, the route of
`--scheduler tcp://HOST:PORT`.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from typer.testing import CliRunner

from robosolve.cli import app

pytest.importorskip("distributed")

ROOT = Path(__file__).resolve().parents[2]
SMALL = ("one-link-arm.yaml", "planar-2r-rods.yaml", "rigid-displacements.yaml")
runner = CliRunner()


@pytest.fixture(scope="module")
def scheduler():
    from robosolve.run.execution import start_local_cluster

    cluster = start_local_cluster(2)
    try:
        assert len(cluster.workers) == 2
        yield cluster.scheduler_address
    finally:
        cluster.close()


def tree(folder: Path) -> dict:
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def test_batch_on_dask_writes_the_same_bytes_as_a_local_run(scheduler, tmp_path):
    src = tmp_path / "src"
    src.mkdir()
    for name in SMALL:
        shutil.copy(ROOT / "problems" / name, src / name)
    local, remote = tmp_path / "local", tmp_path / "dask"
    r1 = runner.invoke(app, ["batch", str(src), "--out", str(local), "--jobs", "1"])
    r2 = runner.invoke(app, ["batch", str(src), "--out", str(remote), "--scheduler", scheduler])
    assert r1.exit_code == 0 and r2.exit_code == 0, r2.output
    assert tree(local) == tree(remote)
    assert sorted(x.name for x in remote.iterdir()) == ["one-link-arm", "planar-2r-rods", "rigid-displacements"]
    assert "robosolve batch" in r2.output                      # the summary table
    # --check against the bundled golden files, solved on the cluster
    r3 = runner.invoke(app, ["batch", str(src), "--check", str(ROOT / "tests" / "golden"), "--scheduler", scheduler])
    assert r3.exit_code == 0 and "golden check: 3 problems identical" in r3.output


@pytest.mark.slow      # the batch test above covers the Dask route in the default run
def test_variants_on_dask_equal_the_local_pool(scheduler, tmp_path):
    from tests.workflows.test_variants import problem_file

    p = problem_file(tmp_path)
    local, remote = tmp_path / "local", tmp_path / "dask"
    r1 = runner.invoke(app, ["variants", str(p), "--count", "3", "--out", str(local), "--jobs", "2"])
    r2 = runner.invoke(app, ["variants", str(p), "--count", "3", "--out", str(remote), "--scheduler", scheduler])
    assert r1.exit_code == 0 and r2.exit_code == 0, r2.output
    assert tree(local) == tree(remote)


def test_an_unreachable_scheduler_is_a_usage_error(tmp_path, monkeypatch):
    from tests.workflows.test_variants import problem_file

    monkeypatch.setattr("robosolve.run.execution.CONNECT_TIMEOUT", "1s")    # nothing listens there
    p = problem_file(tmp_path)
    r = runner.invoke(app, ["variants", str(p), "--count", "2", "--out", str(tmp_path / "o"), "--no-solve",
                            "--scheduler", "tcp://127.0.0.1:9"])
    assert r.exit_code == 2 and "cannot reach the Dask scheduler at tcp://127.0.0.1:9" in r.output
    assert not (tmp_path / "o").exists()
