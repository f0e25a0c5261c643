"""The C3D20 box meshes of roughcontact.fe.deck_writer (the examples', the CalculiX scene's and
the FE benchmark's decks are written with them): node and element counts, the CalculiX/Abaqus
node order of C3D20, the numbering (x fastest, then y, then z; ids from first_node), the named
faces, and the keyword blocks."""

import numpy as np
import pytest

from roughcontact.fe.deck_writer import box_part, element_lines, id_lines, node_lines


def test_counts_and_the_c3d20_node_order():
    x, y, z = [0.0, 1.0, 2.0], [0.0, 1.0], [0.0, 1.0, 3.0]
    part = box_part(x, y, z)
    # corners 3*2*3 + mid-edges along x 2*2*3, along y 3*1*3, along z 3*2*2 (no face or body centres)
    assert len(part.node_ids) == len(part.coords) == 18 + 12 + 9 + 12
    assert part.connectivity.shape == (4, 20)
    assert set(part.connectivity.ravel()) == set(part.node_ids.tolist())  # every node in an element
    c = part.coords
    for e in part.connectivity:
        p = c[e - 1]
        # corners 1-4 at the bottom counter-clockwise, 5-8 above; 9-12 and 13-16 the mid-edges of
        # those squares, 17-20 of the vertical edges (CalculiX/Abaqus C3D20)
        np.testing.assert_allclose(p[8:12], 0.5 * (p[0:4] + p[[1, 2, 3, 0]]))
        np.testing.assert_allclose(p[12:16], 0.5 * (p[4:8] + p[[5, 6, 7, 4]]))
        np.testing.assert_allclose(p[16:20], 0.5 * (p[0:4] + p[4:8]))
        assert p[1, 0] > p[0, 0] and p[3, 1] > p[0, 1] and p[4, 2] > p[0, 2]  # right-handed
    # x fastest, then y, then z
    order = np.lexsort((c[:, 0], c[:, 1], c[:, 2]))
    np.testing.assert_array_equal(order, np.arange(len(c)))


def test_numbering_faces_and_blocks():
    part = box_part([0.0, 2.0], [0.0, 1.0, 2.0], [-1.0, 0.0], first_node=101, first_element=7)
    assert part.node_ids[0] == 101 and part.element_ids.tolist() == [7, 8]
    np.testing.assert_array_equal(part.coords[np.isin(part.node_ids, part.face_nodes["ZMAX"]), 2], 0.0)
    assert part.face_elements["YMIN"].tolist() == [7] and part.face_elements["YMAX"].tolist() == [8]
    assert part.face_label("ZMIN") == 1 and part.face_label("ZMAX") == 2
    lines = node_lines(part, "N", digits=3)
    assert lines[0] == "*NODE, NSET=N" and lines[1] == "101, 0, 0, -1"
    assert element_lines(part, "B")[0] == "*ELEMENT, TYPE=C3D20, ELSET=B" and len(element_lines(part, "B")) == 5
    assert id_lines("*NSET, NSET=S", range(1, 18)) == ["*NSET, NSET=S", ", ".join(map(str, range(1, 17))), "17"]
    with pytest.raises(ValueError, match="strictly increasing"):
        box_part([0.0, 0.0], [0.0, 1.0], [0.0, 1.0])
