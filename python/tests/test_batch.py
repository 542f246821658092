"""oms.batch(): the batch runner over a few assets, here and on a Dask LocalCluster of two worker processes."""

import filecmp
import json
import os
import shutil

import pytest

import openmeshskinned as oms
from conftest import MODELS, WUSON

OPTIONS = {"ratios": [0.5], "poses": 2, "threads": 1}


@pytest.fixture(scope="module")
def assets(tmp_path_factory):
    d = tmp_path_factory.mktemp("assets")
    shutil.copy(WUSON, d / "wuson.x")
    shutil.copy(os.path.join(MODELS, "FBX", "huesitos.fbx"), d / "bones.fbx")
    (d / "broken.glb").write_bytes(b"glTF\x02\x00\x00\x00" + b"\xff" * 64)
    return d


@pytest.fixture(scope="module")
def local_run(assets, tmp_path_factory):
    out = tmp_path_factory.mktemp("local")
    seen = []
    results = oms.batch(assets, out, progress=lambda done, total, r: seen.append((done, total)), **OPTIONS)
    return out, results, seen


def test_every_asset_has_a_result_and_a_bad_one_its_one_line_reason(assets, local_run):
    out, results, seen = local_run
    assert [r["name"] for r in results] == ["bones", "broken", "wuson"]
    assert [r["status"] for r in results] == ["ok", "failed", "ok"]
    with pytest.raises(oms.ReadError) as e:
        oms.load(assets / "broken.glb")
    assert results[1]["reason"] == str(e.value)
    for r in results[0], results[2]:
        assert r["triangles_in"] > 0 and len(r["lods"]) == 1
        lod = r["lods"][0]
        assert lod["ratio"] == 0.5 and lod["triangles"] > 0 and lod["heldout_hausdorff"] > 0
        assert os.path.isfile(lod["file"]) and lod["file"] == str(out / (r["name"] + ".glb"))
    summary = json.loads((out / "summary.json").read_text())
    assert "broken" in json.dumps(summary) and (out / "index.html").is_file()
    assert seen == [(1, 3), (2, 3), (3, 3)]


def test_a_lod_from_the_batch_is_make_lods_own(assets, local_run):
    out, results, _ = local_run
    lods = oms.make_lods(oms.load(assets / "wuson.x"), **OPTIONS)
    oms.save(lods, out.parent / "direct.glb")
    assert filecmp.cmp(out / "wuson.glb", out.parent / "direct.glb", shallow=False)


def test_a_second_run_skips_what_is_up_to_date(assets, local_run):
    out, first, _ = local_run
    again = oms.batch(assets, out, **OPTIONS)
    assert [r["status"] for r in again] == ["skipped", "failed", "skipped"]
    assert again[0]["lods"][0]["triangles"] == first[0]["lods"][0]["triangles"]
    changed = oms.batch(assets, out, **dict(OPTIONS, poses=3))
    assert [r["status"] for r in changed] == ["ok", "failed", "ok"]
    # Back to the first options' files for the other tests.
    oms.batch(assets, out, **OPTIONS)


def test_options_are_checked_before_anything_runs(assets, tmp_path):
    with pytest.raises(oms.OptionsError, match="max-influences"):
        oms.batch(assets, tmp_path / "out", max_influences=0)
    with pytest.raises(TypeError, match="per_vertex_error"):
        oms.batch(assets, tmp_path / "out", per_vertex_error=True)
    with pytest.raises(TypeError, match="unexpected keyword argument 'ratio'"):
        oms.batch(assets, tmp_path / "out", ratio=0.5)
    assert not (tmp_path / "out").exists()


@pytest.mark.filterwarnings("ignore::DeprecationWarning")  # Debian's tornado and distributed 2022.12
def test_a_dask_cluster_gives_the_local_run_s_files(assets, local_run, tmp_path):
    distributed = pytest.importorskip("distributed")
    out, local, _ = local_run
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        remote = oms.batch(assets, tmp_path / "dask", client=client, **OPTIONS)
        workers = {w["host"] + str(w["id"]) for w in client.scheduler_info()["workers"].values()}
    assert len(workers) == 2
    assert [r["status"] for r in remote] == [r["status"] for r in local]
    assert remote[1]["reason"] == local[1]["reason"]
    for a, b in zip(local, remote):
        for la, lb in zip(a["lods"], b["lods"]):
            assert os.path.basename(la["file"]) == os.path.basename(lb["file"])
            assert filecmp.cmp(la["file"], lb["file"], shallow=False)
    assert (tmp_path / "dask" / "summary.json").is_file() and (tmp_path / "dask" / "index.html").is_file()


def test_progress_can_stop_the_batch(assets, tmp_path):
    results = oms.batch(assets, tmp_path / "stopped", progress=lambda done, total, r: False, **OPTIONS)
    assert [r["status"] for r in results] == ["ok", "failed", "failed"]
    assert results[2]["reason"] == "cancelled"

    def fail(done, total, result):
        raise ZeroDivisionError("from the callback")

    with pytest.raises(ZeroDivisionError, match="from the callback"):
        oms.batch(assets, tmp_path / "raised", progress=fail, **OPTIONS)
