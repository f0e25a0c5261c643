"""CalculiX face labels S1-S4 of a tetrahedral box's face sets (roughcontact.fe.tetra.face_labels),
checked against the geometry: the face with label S of its cell is, by CalculiX's definition
(S1 = corners 1-2-3, S2 = 1-4-2, S3 = 2-4-3, S4 = 3-4-1, CalculiX manual, C3D10), the one
without the cell's corner 4, 3, 1, 2 respectively, and it lies on the box's plane."""

from __future__ import annotations

import numpy as np
import pytest

from roughcontact.fe.mesh import FaceSet
from roughcontact.fe.tetra import box_tets, face_labels

#: the corner (0-based) a face S1 ... S4 does not contain (CalculiX's corner lists above)
OPPOSITE = {1: 3, 2: 2, 3: 0, 4: 1}


@pytest.mark.parametrize("plane, axis, value", [("xmin", 0, 0.0), ("xmax", 0, 2.0), ("ymin", 1, 0.0),
                                                ("ymax", 1, 3.0), ("zmin", 2, -1.0), ("zmax", 2, 1.0)])
def test_labels_name_the_faces_on_the_plane(plane, axis, value):
    mesh = box_tets([0.0, 1.0, 2.0], [0.0, 1.5, 3.0], [-1.0, 0.0, 1.0])
    cells, fs = mesh.blocks[0].cells, mesh.face_sets[plane]
    labels = face_labels(cells, fs)
    assert len(labels) == 2 * 2 * 2  # 2 × 2 grid cells on the plane, two triangles each
    for c, s in zip(fs.cell_indices, labels):
        corners = cells[c, :4]
        on_plane = np.isclose(mesh.points[corners, axis], value)
        assert on_plane.sum() == 3 and not on_plane[OPPOSITE[int(s)]]


def test_a_face_of_no_cell_is_refused():
    mesh = box_tets([0.0, 1.0], [0.0, 1.0], [0.0, 1.0])
    fs = mesh.face_sets["zmax"]
    bad = FaceSet(fs.block_index, fs.cell_indices, fs.face_nodes[:, ::-1], fs.face_element)
    with pytest.raises(ValueError, match="face_labels: face 0"):
        face_labels(mesh.blocks[0].cells, bad)
