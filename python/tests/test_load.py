"""oms.load() and the Mesh's arrays, against what the C++ library reports of the same file."""

import os

import numpy as np
import pytest

import openmeshskinned as oms
from conftest import MODELS, WUSON, cli, cli_error


def test_the_arrays_have_the_mesh_s_counts(wuson):
    n, f, j = wuson.n_vertices, wuson.n_faces, wuson.n_joints
    assert n > 0 and f > 0 and j > 1
    assert wuson.rest_positions.shape == (n, 3) and wuson.rest_positions.dtype == np.float64
    assert wuson.faces.shape == (f, 3)
    assert wuson.faces.min() >= 0 and wuson.faces.max() < n
    assert wuson.inverse_binds.shape == (j, 4, 4)
    assert len(wuson.joint_names) == j and wuson.joint_parents.shape == (j,)
    assert wuson.face_materials.shape == (f,)
    assert wuson.clip_names and len(wuson.clip_durations) == len(wuson.clip_names)


def test_every_vertex_s_weights_sum_to_one_on_real_joints(wuson):
    idx, w = wuson.joint_indices, wuson.joint_weights
    assert idx.shape == w.shape == (wuson.n_vertices, idx.shape[1])
    assert 1 <= idx.shape[1] <= 8
    np.testing.assert_allclose(w.sum(axis=1), 1.0, atol=1e-9)
    assert idx.min() >= -1 and (w[idx >= 0] >= 0).all()
    assert (w[idx < 0] == 0).all() and idx.max() < wuson.n_joints
    # Heaviest first, the library's order.
    assert (np.diff(w, axis=1) <= 0).all()


def test_the_skeleton_lists_parents_before_children(wuson):
    parents = wuson.joint_parents
    assert parents[0] == -1
    for i, p in enumerate(parents):
        assert -1 <= p < i
    assert len(set(wuson.joint_names)) == wuson.n_joints
    # An inverse bind is an invertible affine map.
    assert np.allclose(wuson.inverse_binds[:, 3, :], [0, 0, 0, 1])
    assert (np.abs(np.linalg.det(wuson.inverse_binds)) > 1e-12).all()


def test_arrays_are_copies(wuson):
    a = wuson.rest_positions
    a[:] = 0
    assert np.abs(wuson.rest_positions).max() > 0


@pytest.mark.parametrize("path", [WUSON, os.path.join(MODELS, "FBX", "huesitos.fbx")])
def test_warnings_are_the_command_line_s(path, tmp_path):
    m = oms.load(path)
    _, _, err = cli(path, "-o", tmp_path / "w.glb", "--ratio", "0.5", "--quiet", "--no-eval", "--no-refit")
    prefix = "skinned-decimate: warning: "
    printed = [line[len(prefix):] for line in err.splitlines() if line.startswith(prefix + path + ": ")]
    assert m.warnings == printed
    if path != WUSON:
        assert len(m.warnings) == 2 and "did not sum to 1" in m.warnings[1]


def test_a_corrupt_file_raises_the_command_line_s_one_line_message(tmp_path):
    bad = tmp_path / "broken.glb"
    bad.write_bytes(b"glTF\x02\x00\x00\x00" + os.urandom(64))
    status, message = cli_error(bad, "-o", tmp_path / "out.glb")
    assert status == 1
    with pytest.raises(oms.ReadError) as e:
        oms.load(bad)
    assert str(e.value) == message
    assert isinstance(e.value, OSError) and isinstance(e.value, oms.Error)
    assert "\n" not in str(e.value) and str(bad) in str(e.value)


def test_a_missing_file_raises_read_error(tmp_path):
    with pytest.raises(oms.ReadError, match="nothing.glb"):
        oms.load(tmp_path / "nothing.glb")


def test_a_frame_animation_reads_every_stored_frame():
    m = oms.load(os.path.join(MODELS, "MD2", "faerie.md2"))
    assert len(m.frame_times) == 198 and m.n_joints >= 1
    assert len(m.morph_target_names) == 197
    assert m.morph_deltas.shape == (197, m.n_vertices, 3)
    assert np.abs(m.morph_deltas).max() > 0
