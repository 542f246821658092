"""oms.make_lods(), its reports, evaluate() and save(), against the command line's results."""

import filecmp
import os
import shutil
import subprocess

import numpy as np
import pytest

import openmeshskinned as oms
from conftest import WUSON, cli, cli_error


def test_each_report_counts_its_mesh(wuson, wuson_lods):
    assert len(wuson_lods) == 2 and wuson_lods.method == "skinned"
    for lod, ratio in zip(wuson_lods, [0.5, 0.25]):
        r, mesh = lod.report, lod.mesh
        assert r.ratio == ratio and r.target == round(ratio * wuson.n_faces)
        assert r.faces == mesh.n_faces == mesh.faces.shape[0]
        assert r.vertices == mesh.n_vertices == mesh.rest_positions.shape[0]
        assert r.joints == mesh.n_joints == wuson.n_joints
        assert r.max_influences == mesh.joint_indices.shape[1] <= 4
        np.testing.assert_allclose(mesh.joint_weights.sum(axis=1), 1.0, atol=1e-9)
        assert r.evaluated and 0 < r.rms <= r.hausdorff
        assert r.to_dict()["faces"] == r.faces and r.to_dict()["hausdorff"] == r.hausdorff
    assert wuson_lods[0].report.faces > wuson_lods[1].report.faces
    assert wuson_lods[-1].report.faces == wuson_lods[1].report.faces
    with pytest.raises(IndexError):
        wuson_lods[2]


def test_frames_are_named_by_clip(wuson, wuson_lods):
    for frames in (wuson_lods.example_frames, wuson_lods.heldout_frames):
        assert frames
        for clip, t in frames:
            assert clip in wuson.clip_names and t >= 0.0
    assert len(wuson_lods.example_frames) == 3
    assert any("example poses" in line for line in wuson_lods.messages)


def test_evaluate_gives_what_make_lods_reported(wuson, wuson_lods):
    lod = wuson_lods[1]
    given = oms.evaluate(wuson, lod.mesh, wuson_lods.heldout_frames)
    assert (given.rms, given.hausdorff) == (lod.report.rms, lod.report.hausdorff)
    chosen = oms.evaluate(wuson, lod.mesh, poses=3)
    assert (chosen.rms, chosen.hausdorff) == (lod.report.rms, lod.report.hausdorff)
    per_vertex = oms.evaluate(wuson, lod.mesh, wuson_lods.heldout_frames[:1], per_vertex_error=True)
    assert per_vertex.vertex_error.shape == (lod.mesh.n_vertices,)
    assert per_vertex.hausdorff <= lod.report.hausdorff
    by_index = oms.evaluate(wuson, lod.mesh, [(wuson.clip_names.index(c), t) for c, t in wuson_lods.heldout_frames[:1]])
    assert by_index.rms == per_vertex.rms
    with pytest.raises(oms.OptionsError, match="no clip named"):
        oms.evaluate(wuson, lod.mesh, [("no such clip", 0.0)])


def test_a_lod_saved_from_python_is_the_command_line_s_byte_for_byte(wuson, tmp_path):
    status, _, err = cli(WUSON, "-o", tmp_path / "cli.glb", "--ratio", "0.5", "--poses", "3", "--quiet")
    assert status == 0, err
    lods = oms.make_lods(wuson, ratios=[0.5], poses=3)
    assert oms.save(lods, tmp_path / "py.glb") == [str(tmp_path / "py.glb")]
    assert filecmp.cmp(tmp_path / "cli.glb", tmp_path / "py.glb", shallow=False)
    validator = os.environ.get("OMSK_VALIDATOR")
    if validator and shutil.which("node"):
        r = subprocess.run(["node", validator, tmp_path / "py.glb"], capture_output=True, text=True)
        assert r.returncode == 0, r.stdout + r.stderr


def test_the_pricing_words_are_the_area_exponent_s_values(wuson, tmp_path):
    # per-area is the exponent 1; a batch hands the tool the keywords as its own options.
    args = ["--ratio", "0.5", "--poses", "3", "--error", "per-area", "--area-floor", "0", "--quiet"]
    status, _, err = cli(WUSON, "-o", tmp_path / "cli.glb", *args)
    assert status == 0, err
    oms.save(oms.make_lods(wuson, ratios=[0.5], poses=3, area_exponent=1.0, area_floor=0.0), tmp_path / "py.glb")
    assert filecmp.cmp(tmp_path / "cli.glb", tmp_path / "py.glb", shallow=False)
    assert oms._core._tool_arguments(area_exponent=1.0, area_floor=0.0) == ["--error", "1.0", "--area-floor", "0.0"]
    oms.save(oms.make_lods(wuson, ratios=[0.5], poses=3), tmp_path / "default.glb")
    assert not filecmp.cmp(tmp_path / "cli.glb", tmp_path / "default.glb", shallow=False)


def test_poses_spread_over_the_motion_are_the_command_line_s(wuson, tmp_path):
    args = ["--ratio", "0.5", "--poses", "3", "--pose-select", "spread"]
    status, out, err = cli(WUSON, "-o", tmp_path / "cli.glb", *args)
    assert status == 0, err
    assert "example poses (spread over the motion) at" in out + err
    oms.save(oms.make_lods(wuson, ratios=[0.5], poses=3, pose_select="spread"), tmp_path / "py.glb")
    assert filecmp.cmp(tmp_path / "cli.glb", tmp_path / "py.glb", shallow=False)
    even = oms.make_lods(wuson, ratios=[0.5], poses=3, pose_clip="Wuson_Walk").example_frames
    for how, label in (("spread", "spread over the motion"), ("motion", "evenly over the motion")):
        chain = oms.make_lods(wuson, ratios=[0.5], poses=3, pose_select=how, pose_clip="Wuson_Walk")
        walk = chain.example_frames
        assert len(walk) == 3 and all(clip == "Wuson_Walk" for clip, _ in walk)
        assert any(f"example poses ({label}) at" in line for line in chain.messages)
        # The walk moves evenly: spaced over its motion, its poses are even times'; spread's are not.
        assert (walk != even) == (how == "spread")
    with pytest.raises(oms.OptionsError, match='--pose-select must be even, motion, spread or ga, got "best"'):
        oms.make_lods(wuson, pose_select="best")


def test_the_default_pose_count_follows_the_clips(wuson):
    # Testwuson is small and two of its clips move (the run and the walk): 8 poses each; one clip chosen: 8.
    assert len(oms.make_lods(wuson, ratios=[0.5], evaluate=False).example_frames) == 16
    walk = oms.make_lods(wuson, ratios=[0.5], evaluate=False, pose_clip="Wuson_Walk").example_frames
    assert len(walk) == 8 and all(clip == "Wuson_Walk" for clip, _ in walk)
    assert len(oms.make_lods(wuson, ratios=[0.5], evaluate=False, poses=5).example_frames) == 5
    assert "8 per clip that moves joints, at most 16" in oms.make_lods.__doc__


def test_a_chain_is_saved_as_numbered_files_and_a_mesh_as_one(wuson_lods, tmp_path):
    paths = oms.save(wuson_lods, tmp_path / "hero.glb")
    assert paths == [str(tmp_path / "hero_lod1.glb"), str(tmp_path / "hero_lod2.glb")]
    assert all(os.path.getsize(p) > 0 for p in paths) and not (tmp_path / "hero.glb").exists()
    assert oms.save(wuson_lods[1].mesh, tmp_path / "one.glb") == [str(tmp_path / "one.glb")]
    again = oms.load(tmp_path / "one.glb", isolate=False)
    assert again.n_faces == wuson_lods[1].report.faces


def test_save_refuses_its_input_and_a_bad_extension_with_nothing_written(wuson_lods, tmp_path):
    oms.save(wuson_lods[1].mesh, tmp_path / "in.glb")
    m = oms.load(tmp_path / "in.glb")
    before = (tmp_path / "in.glb").read_bytes()
    with pytest.raises(oms.WriteError, match="in.glb"):
        oms.save(m, tmp_path / "in.glb")
    assert (tmp_path / "in.glb").read_bytes() == before
    with pytest.raises(oms.WriteError) as e:
        oms.save(wuson_lods, tmp_path / "out.obj")
    assert str(e.value) == str(tmp_path / "out.obj") + ": output must end in .glb or .gltf"
    assert sorted(os.listdir(tmp_path)) == ["in.glb"]
    with pytest.raises(TypeError):
        oms.save("not a mesh", tmp_path / "x.glb")


@pytest.mark.parametrize(
    "cli_args, options",
    [
        (["--max-influences", "9"], {"max_influences": 9}),
        (["--lods", "1.5"], {"ratios": [1.5]}),
        (["--faces", "100000000"], {"faces": [100000000]}),
        (["--poses", "-1"], {"poses": -1}),
        (["--pose-clip", "nope"], {"pose_clip": "nope"}),
        (["--error", "1.5"], {"area_exponent": 1.5}),
        (["--area-floor", "-1"], {"area_floor": -1.0}),
    ],
)
def test_bad_options_raise_the_command_line_s_message(wuson, tmp_path, cli_args, options):
    status, message = cli_error(WUSON, "-o", tmp_path / "x.glb", *cli_args)
    assert status == 2
    with pytest.raises(oms.OptionsError) as e:
        oms.make_lods(wuson, **options)
    assert str(e.value) == message
    assert isinstance(e.value, ValueError)
    assert not os.listdir(tmp_path)


def test_unknown_or_mistyped_keywords_are_type_errors(wuson):
    with pytest.raises(TypeError, match="unexpected keyword argument 'ratio'"):
        oms.make_lods(wuson, ratio=0.5)
    with pytest.raises(TypeError, match="poses must be int"):
        oms.make_lods(wuson, poses="three")
    with pytest.raises(TypeError, match="unexpected keyword argument 'ratios'"):
        oms.evaluate(wuson, wuson, ratios=[0.5])


def test_every_keyword_has_the_c_plus_plus_default_in_the_docstring():
    defaults = oms.default_options()
    assert defaults["ratios"] == [0.5] and defaults["max_influences"] == 4 and defaults["poses"] == 0
    for name, value in defaults.items():
        assert f"    {name} (" in oms.make_lods.__doc__ and f"default {value!r})" in oms.make_lods.__doc__
    assert "skinned" in oms.lod_methods()
