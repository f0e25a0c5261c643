"""Drawings of the finite elements and meshes of section 9 (Buczkowski & Kleiber 2009, Figs 10–17).

Everything drawn comes from the engine's own definitions: node positions and numbers are
``element.nodes`` in local order (label = local index + ``numbering``, 1-based by default like the
paper's figures), edges are x(ξ) = Σ N_a(ξ) x_a evaluated with ``element.shape`` through the
element's own nodes, and the contact face is interpolated by ``element.face_element`` through the
nodes ``element.contact_face``. A wrong node order shows in the picture (a label in the wrong
place, a scrambled contact face) instead of being hidden by a hand-written table.

Functions return a ``matplotlib.figure.Figure`` on an Agg canvas (:func:`roughcontact.plots.style.new_figure`; laid out by hand: 3D axes placed by rectangle).
Reference coordinates are dimensionless; mesh coordinates are in mm. Artists a test may look
for carry a ``gid``: "node-label:<local index>", "contact-face", "pair:<i>", "integration-points",
"interface-face", "support:<node set>", "load:<k>".
"""

from __future__ import annotations

import numpy as np

from ..fe.element import LOBATTO4, QUAD9, QUAD16, Element
from ..fe.interface_element import InterfaceElement
from ..fe.mesh import CellBlock, InterfaceBlock, Mesh, local_face
from ..plots.style import new_figure, style

__all__ = [
    "KINDS", "node_kinds", "node_table", "label_positions", "edge_curves", "contact_outline",
    "element_figure", "interface_figure", "mesh_figure", "boundary_edges",
]

#: marker and colour of each node kind (by how many reference coordinates are ±1)
KINDS = {
    "corner": dict(marker="s", color="#1b4f72", s=34),
    "edge": dict(marker="o", color="#b03a2e", s=30),
    "face": dict(marker="D", color="#1e8449", s=26),
    "interior": dict(marker="*", color="#7d3c98", s=40),
}
_CONTACT_COLOR = "#f5b041"
_EDGE_COLOR = "0.25"
#: label distance from its node (reference units) by kind: corners further out, clear of the
#: edge nodes next to them; face nodes closer, clear of their neighbours on the same face
_LABEL_DISTANCE = {"corner": 0.27, "edge": 0.2, "face": 0.14, "interior": 0.14}


# ---------------------------------------------------------------------------------------------
# tables and geometry from the element definitions
# ---------------------------------------------------------------------------------------------
def node_kinds(nodes) -> list[str]:
    """Kind of each reference node (n, d): "corner" (all d coordinates ±1), "edge" (d − 1),
    "face" (d − 2; for a quadrilateral its interior), "interior"."""
    nodes = np.asarray(nodes, dtype=float)
    on = np.isclose(np.abs(nodes), 1.0, rtol=0.0, atol=1e-12).sum(axis=1)
    names = ("corner", "edge", "face", "interior")
    return [names[min(nodes.shape[1] - int(k), 3)] for k in on]


def node_table(element: Element | InterfaceElement, numbering: int = 1) -> list[dict]:
    """One row per node: label (local index + ``numbering``), local index, ξ, η, ζ (ζ = 0 for a
    face; an interface's side A and B share the reference positions) and kind; interface rows
    also give the side ("A" lower body / base, "B" upper body) and the label of the facing node."""
    if isinstance(element, InterfaceElement):
        n = element.face.n_nodes
        kinds = node_kinds(element.face.nodes) * 2
        rows = []
        for i, (xi, eta) in enumerate(element.nodes):
            facing = i + n if i < n else i - n
            rows.append(dict(label=i + numbering, index=i, side="AB"[i // n], xi=float(xi), eta=float(eta),
                             zeta=0.0, kind=kinds[i], facing=facing + numbering))
        return rows
    x = np.zeros((element.n_nodes, 3))
    x[:, :element.dim] = element.nodes
    kinds = node_kinds(element.nodes)
    return [dict(label=i + numbering, index=i, xi=float(p[0]), eta=float(p[1]), zeta=float(p[2]), kind=kinds[i])
            for i, p in enumerate(x)]


def label_positions(points, centre, distance) -> np.ndarray:
    """Label anchors (n, 3): each point moved by ``distance`` (a scalar or one per point, in the
    points' units) along the ray from ``centre`` through it, so labels sit outside the drawing."""
    points = np.asarray(points, dtype=float)
    d = points - np.asarray(centre, dtype=float)
    norm = np.linalg.norm(d, axis=1, keepdims=True)
    d = np.divide(d, norm, out=np.zeros_like(d), where=norm > 0)
    return points + np.asarray(distance, dtype=float).reshape(-1, 1) * d


def _cube_edges():
    """The 12 edges of [-1, 1]^3: (axis along the edge, {other axis: ±1})."""
    for axis in range(3):
        a, b = [k for k in range(3) if k != axis]
        for sa in (-1.0, 1.0):
            for sb in (-1.0, 1.0):
                yield axis, {a: sa, b: sb}


def _samples(abscissae, n: int) -> np.ndarray:
    """n equally spaced points of [-1, 1] plus the given abscissae (so nodes lie on the curve)."""
    return np.unique(np.concatenate([np.linspace(-1.0, 1.0, n), np.asarray(abscissae, dtype=float)]))


def edge_curves(element: Element, coords=None, samples: int = 33) -> list[np.ndarray]:
    """The 12 edges of a hexahedron as (m, 3) polylines x(ξ) = Σ N_a(ξ) x_a, with the element's
    shape functions and node coordinates ``coords`` (default: its reference nodes)."""
    coords = element.nodes if coords is None else np.asarray(coords, dtype=float)
    t = _samples(np.unique(element.nodes), samples)
    out = []
    for axis, fixed in _cube_edges():
        ref = np.zeros((t.size, 3))
        ref[:, axis] = t
        for k, s in fixed.items():
            ref[:, k] = s
        out.append(element.shape(ref) @ coords)
    return out


def _face_outline(face: Element, coords, samples: int = 17) -> np.ndarray:
    """Boundary (m, 3) of a quadrilateral ``face`` with node coordinates ``coords`` (n, 3): the
    face's interpolation along its reference square, corner 0 → 1 → 2 → 3; nodes lie on it."""
    t = _samples(np.unique(face.nodes), samples)
    corners = np.array([(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)])
    s = (t[:-1, None] + 1.0) / 2.0  # fraction along a side, its end corner excluded
    uv = np.vstack([(1.0 - s) * corners[k] + s * corners[(k + 1) % 4] for k in range(4)])
    return face.shape(uv) @ np.asarray(coords, dtype=float)


def contact_outline(element: Element, samples: int = 17) -> np.ndarray:
    """Boundary (m, 3) of the contact face ζ = −1, interpolated by ``element.face_element``
    through the element's nodes ``contact_face`` in that order (a wrong order scrambles it)."""
    return _face_outline(element.face_element, element.nodes[list(element.contact_face)], samples)


# ---------------------------------------------------------------------------------------------
# drawing helpers
# ---------------------------------------------------------------------------------------------
def _axes3d(fig, elev: float, azim: float, rect=(0.0, 0.17, 1.0, 0.78)):
    """3D axes in a parallel (oblique-looking) projection, without panes or ticks, over the
    upper part of the figure (the legend and notes go below); artists are drawn in the order of
    their zorder (labels always above lines)."""
    ax = fig.add_axes(rect, projection="3d")
    ax.set_proj_type("ortho")
    ax.view_init(elev=elev, azim=azim)
    ax.computed_zorder = False
    ax.set_axis_off()
    return ax


def _nodes(ax, points, kinds):
    """Node dots, one marker (and legend entry) per kind."""
    for kind, st in KINDS.items():
        sel = [i for i, k in enumerate(kinds) if k == kind]
        if sel:
            ax.scatter(*np.asarray(points)[sel].T, depthshade=False, zorder=4, edgecolors="white",
                       linewidths=0.5, label=f"{kind} node", **st)


def _labels(ax, positions, labels, *, fontsize: float = 8.0):
    """Node numbers at ``positions``; gid "node-label:<local index>"."""
    for i, (p, text) in enumerate(zip(positions, labels)):
        # a light backing keeps a number readable where a line passes behind it
        ax.text(*p, str(text), fontsize=fontsize, ha="center", va="center", zorder=6, gid=f"node-label:{i}",
                bbox=dict(boxstyle="square,pad=0.05", facecolor="white", edgecolor="none", alpha=0.75))


def _polygon(ax, verts, *, color, alpha, gid, zorder=1, label=None):
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    poly = Poly3DCollection(list(verts), facecolor=color, edgecolor="none", alpha=alpha, zorder=zorder, label=label)
    poly.set_gid(gid)
    ax.add_collection3d(poly)
    return poly


def _triad(ax, origin, length: float, names=("ξ", "η", "ζ")):
    """Arrows along the three reference axes from ``origin``, labelled beside their tips (η's
    label nudged towards −ξ: in the default view the front vertical edge passes its tip)."""
    nudge = np.array([(0.14, 0.0, 0.0), (-0.13, 0.08, 0.07), (0.0, 0.0, 0.13)])
    for k, name in enumerate(names):
        d = np.zeros(3)
        d[k] = length
        ax.quiver(*origin, *d, color="0.35", linewidth=1.0, arrow_length_ratio=0.22, zorder=3)
        ax.text(*(np.asarray(origin) + d + nudge[k]), name, fontsize=11, color="0.2", ha="center", va="center",
                zorder=6, gid="axis-label")


def _limits(ax, lo, hi, zoom: float = 1.15):
    """Data limits lo..hi per axis with the box aspect of the true proportions."""
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    for set_lim, a, b in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), lo, hi):
        set_lim(a, b)
    ax.set_box_aspect(tuple(hi - lo), zoom=zoom)


# ---------------------------------------------------------------------------------------------
# figures
# ---------------------------------------------------------------------------------------------
def element_figure(element: Element, *, title: str, numbering: int = 1, elev: float = 19.0, azim: float = -59.0):
    """A hexahedron in reference coordinates [-1, 1]^3: edges through its interpolation, every
    node a dot (marker by kind) labelled local index + ``numbering``, the contact face ζ = −1
    shaded, the ξ, η, ζ axes, and c = 1/√5 marked if nodes sit there (HEX28). The default view
    keeps every node of HEX20/21/28 off the projection of edges it does not lie on (at azim
    −64° the front vertical edge hides HEX21's node 11, at −70° HEX28's node 27)."""
    kinds = node_kinds(element.nodes)
    with style():
        fig = new_figure(figsize=(6.4, 7.0), layout=None)
        ax = _axes3d(fig, elev, azim)
        if element.contact_face:
            _polygon(ax, [contact_outline(element)], color=_CONTACT_COLOR, alpha=0.45, gid="contact-face",
                     label=f"contact face ζ = −1 ({len(element.contact_face)} nodes)")
        for curve in edge_curves(element):
            ax.plot(*curve.T, color=_EDGE_COLOR, linewidth=1.3, zorder=2)
        _triad(ax, (0.0, 0.0, 0.0), 0.55)
        _nodes(ax, element.nodes, kinds)
        distance = [_LABEL_DISTANCE[k] for k in kinds]
        _labels(ax, label_positions(element.nodes, (0.0, 0.0, 0.0), distance), np.arange(element.n_nodes) + numbering)
        if np.any(np.isclose(np.abs(element.nodes), LOBATTO4)):
            _mark_c(ax)
        _limits(ax, (-1.3,) * 3, (1.3,) * 3)
        fig.suptitle(title, y=0.97)
        fig.legend(loc="lower center", fontsize=8, ncol=2, bbox_to_anchor=(0.5, 0.07))
        fig.text(0.5, 0.02, f"label = local node index + {numbering}; element {element.name}, {element.n_nodes} nodes",
                 ha="center", fontsize=8, color="0.3")
    return fig


def _mark_c(ax):
    """A dimension line 0 → c = 1/√5 along ξ on the contact face, next to its front edge."""
    y, z = -0.72, -1.0
    ax.plot([0.0, LOBATTO4], [y, y], [z, z], color="0.15", linewidth=0.9, zorder=3)
    for x in (0.0, LOBATTO4):
        ax.plot([x, x], [y - 0.07, y + 0.07], [z, z], color="0.15", linewidth=0.9, zorder=3)
    ax.text(LOBATTO4 / 2, y + 0.12, z, "c", fontsize=10, ha="center", va="bottom", zorder=6, gid="c-label")
    ax.text2D(0.95, 0.08, "c = 1/√5 ≈ 0.447", transform=ax.transAxes, ha="right", fontsize=9, gid="c-note")


def interface_figure(interface_element: InterfaceElement, *, title: str, gap: float = 0.35, rule: str = "lobatto",
                     numbering: int = 1, elev: float = 24.0, azim: float = -59.0):
    """Exploded view of a zero-thickness interface element: side A's face (nodes 1..n, lower
    body / rigid base) below side B's (n+1..2n, upper body), lifted so that the two drawn faces
    are ``gap`` × the face's side apart on the page (the real thickness is zero), dashed lines
    joining facing nodes i ↔ n + i, and the points of the integration ``rule`` ("gauss" |
    "lobatto") marked on side A."""
    face = interface_element.face
    n = face.n_nodes
    # lift of side B: the face's own height on the page (a 2 × 2 square seen from elev, azim)
    # plus the visual gap, so that the two faces and their labels do not overlap
    e, a = np.radians(elev), np.radians(azim)
    h = (2.0 * np.sin(e) * (abs(np.cos(a)) + abs(np.sin(a))) + 2.0 * gap) / np.cos(e)
    xa = np.column_stack([face.nodes, np.zeros(n)])
    xb = xa + (0.0, 0.0, h)
    x = np.vstack([xa, xb])
    kinds = node_kinds(face.nodes) * 2
    points = interface_element.rule(rule).points
    with style():
        fig = new_figure(figsize=(6.4, 7.0), layout=None)
        ax = _axes3d(fig, elev, azim)
        sides = (("A", xa, "#85c1e9", f"side A: lower body / base, nodes {numbering}–{n - 1 + numbering}"),
                 ("B", xb, _CONTACT_COLOR, f"side B: upper body, nodes {n + numbering}–{2 * n - 1 + numbering}"))
        for side, coords, color, name in sides:
            outline = _face_outline(face, coords)
            _polygon(ax, [outline], color=color, alpha=0.4, gid=f"side:{side}", label=name)
            ax.plot(*np.vstack([outline, outline[:1]]).T, color=_EDGE_COLOR, linewidth=1.2, zorder=2)
        for i in range(n):
            ax.plot(*np.column_stack([xa[i], xb[i]]), color="0.45", linestyle=(0, (3, 2)), linewidth=0.8,
                    zorder=2, gid=f"pair:{i}")
        _nodes(ax, x, kinds)
        ip = np.column_stack([points, np.zeros(len(points))])
        on_nodes = bool(np.all(np.min(np.linalg.norm(ip[:, None, :2] - face.nodes[None], axis=2), axis=1) < 1e-12))
        ax.scatter(*ip.T, marker="o", s=110, facecolors="none", edgecolors="black", linewidths=1.0, zorder=5,
                   depthshade=False, gid="integration-points",
                   label=f"{rule} points ({len(points)})" + (" = nodes" if on_nodes else ""))
        distance = [_LABEL_DISTANCE[k] for k in kinds]
        _labels(ax, label_positions(x, (0.0, 0.0, h / 2), distance), np.arange(2 * n) + numbering)
        _limits(ax, (-1.3, -1.3, -0.4), (1.3, 1.3, h + 0.4))
        fig.suptitle(title, y=0.97)
        fig.legend(loc="lower center", fontsize=8, ncol=2, bbox_to_anchor=(0.5, 0.07))
        note = (f"real thickness zero: sides A and B occupy the same surface (drawn apart); "
                f"node i faces node {n} + i")
        if on_nodes:
            note += f"\n{rule} integration points = the nodes (nodal integration)"
        fig.text(0.5, 0.02, note, ha="center", fontsize=8, color="0.3")
    return fig


# ---------------------------------------------------------------------------------------------
# meshes
# ---------------------------------------------------------------------------------------------
def _side_paths(face: Element) -> list[np.ndarray]:
    """Local nodes of each side (corner k → k + 1) of a quadrilateral face element, in order."""
    corners = face.nodes[:4]
    out = []
    for k in range(4):
        a, b = corners[k], corners[(k + 1) % 4]
        t = (face.nodes - a) @ (b - a) / np.dot(b - a, b - a)
        on = np.flatnonzero(np.linalg.norm(face.nodes - (a + t[:, None] * (b - a)), axis=1) < 1e-9)
        on = on[(t[on] > -1e-9) & (t[on] < 1 + 1e-9)]
        out.append(on[np.argsort(t[on])])
    return out


def _boundary_faces(mesh: Mesh) -> list[tuple[Element, np.ndarray]]:
    """(face element, (m, n_face) global nodes) of the cell faces on the outer surface (faces
    no other cell shares, compared by their corner nodes), ordered with outward normals."""
    groups = []
    for block in mesh.blocks:
        for axis in range(3):
            for side in (-1, 1):
                face, idx = local_face(block.element, axis, side)
                groups.append((face, block.cells[:, list(idx)]))
    keys = np.vstack([np.sort(g[:, :4], axis=1) for _, g in groups])
    _, inverse, counts = np.unique(keys, axis=0, return_inverse=True, return_counts=True)
    once = counts[inverse.ravel()] == 1
    out, start = [], 0
    for face, g in groups:
        sel = once[start:start + len(g)]
        start += len(g)
        if sel.any():
            out.append((face, g[sel]))
    return out


def _view_vector(elev: float, azim: float) -> np.ndarray:
    """Unit vector from the scene towards matplotlib's camera at (elev, azim) [degrees]."""
    e, a = np.radians(elev), np.radians(azim)
    return np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])


def boundary_edges(mesh: Mesh, view=None, max_edges: int | None = None) -> list[np.ndarray]:
    """Polylines (node indices, corner to corner through the mid nodes) of the element edges on
    the outer surface, each once; with ``view`` (a vector towards the camera) only the edges of
    faces turned to it. Beyond ``max_edges`` edges, only the feature edges (where the surface
    bends by more than 20°, e.g. the box's own edges) are kept."""
    paths, keys, normals, visible = [], [], [], []
    for face, g in _boundary_faces(mesh):
        x = mesh.points[g[:, :4]]
        n = np.cross(x[:, 1] - x[:, 0], x[:, 3] - x[:, 0])
        n /= np.linalg.norm(n, axis=1, keepdims=True)
        seen = np.ones(len(g), bool) if view is None else n @ np.asarray(view, float) > 0
        for side in _side_paths(face):
            p = g[:, side]
            paths += list(p)
            keys.append(np.sort(p[:, [0, -1]], axis=1))
            normals.append(n)
            visible.append(seen)
    if not paths:
        return []
    keys, normals, visible = np.vstack(keys), np.vstack(normals), np.concatenate(visible)
    _, first, inverse = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    inverse = inverse.ravel()
    shown = np.zeros(first.size, bool)
    np.logical_or.at(shown, inverse, visible)
    if max_edges is not None and shown.sum() > max_edges:
        # feature edges: the normals of the faces meeting there differ (by the first face's)
        bend = np.einsum("ij,ij->i", normals, normals[first][inverse]) < np.cos(np.radians(20.0))
        feature = np.zeros(first.size, bool)
        np.logical_or.at(feature, inverse, bend)
        shown &= feature
    return [paths[i] for i in first[shown]]


def mesh_figure(mesh: Mesh, *, title: str, supports=(), loads=(), highlight_interface: bool = True,
                max_edges: int = 6000, elev: float = 20.0, azim: float = -60.0, figsize=(8.0, 6.0),
                zoom: float = 1.1, detail=None, lift: float = 0.0, show_transition: bool = False):
    """A mesh in its true proportions (mm): the element edges on the surface turned to the
    viewer, the interface faces shaded, ``supports`` [(node set or tuple of node sets, label)]
    as triangles at the sets' nodes (and a plate beside a planar set; a tuple shares one colour
    and one legend entry), ``loads`` [((x, y, z), (fx, fy, fz), label)] as arrows ending at the
    point. ``max_edges``: see :func:`boundary_edges`; ``zoom``: of the 3D box in its axes
    (matplotlib's; above ~1.1 a cube-like body is clipped).

    ``detail`` ((x0, y0, z0), (x1, y1, z1)) [mm]: a second panel, on the right, drawing only the
    cells inside that box at its own scale (a small body on a large one, e.g. a punch on its
    foundation), with the interface nodes marked and no supports; the box is outlined (dashed)
    on the left. ``lift`` [mm]: in the detail, the body on side B of the interfaces is drawn
    that much higher (an exploded view: the interface, of zero thickness, is seen between the
    bodies), dotted lines joining the outer corners of side A and side B. ``show_transition``:
    shade the visible sides of the transition elements (HEX21/HEX28), i.e. the layer's thickness."""
    panels = [(mesh, (0.0, 0.12, 1.0, 0.8))]
    if detail is not None:
        lo, hi = (np.asarray(v, dtype=float) for v in detail)
        panels = [(mesh, (0.0, 0.13, 0.52, 0.76)), (_clip(mesh, lo, hi, lift), (0.48, 0.13, 0.52, 0.76))]
    with style():
        fig = new_figure(figsize=figsize, layout=None)
        for k, (m, rect) in enumerate(panels):
            ax = _axes3d(fig, elev, azim, rect=rect)
            lifted = [(np.add(p, (0.0, 0.0, lift)), f, t) for p, f, t in loads] if k else loads
            _mesh_panel(ax, m, () if k else supports, lifted, highlight_interface, max_edges, elev, azim, zoom,
                        nodes=k > 0, transition=show_transition)
        if detail is not None:
            _box_outline(fig.axes[0], lo, hi)
            if lift:
                _pairs(fig.axes[1], panels[1][0], f"interface side A ↔ B (detail: B's body drawn {lift:g} mm higher)")
        fig.suptitle(title, y=0.97)
        handles = {}
        for ax in fig.axes:  # one legend entry per label over the panels
            for h, text in zip(*ax.get_legend_handles_labels()):
                handles.setdefault(text, h)
        if handles:
            fig.legend(list(handles.values()), list(handles), loc="lower center", fontsize=8, ncol=2,
                       bbox_to_anchor=(0.5, 0.02))
        fig.text(0.99, 0.005, f"{mesh.n_nodes} nodes, {sum(len(b.cells) for b in mesh.blocks)} cells; mm",
                 ha="right", va="bottom", fontsize=7, color="0.4")
    return fig


def _mesh_panel(ax, mesh: Mesh, supports, loads, highlight_interface, max_edges, elev, azim, zoom, *, nodes=False,
                transition=False):
    """One view of ``mesh`` (see :func:`mesh_figure`); ``nodes``: mark the interface nodes;
    ``transition``: shade the transition layer's sides."""
    from mpl_toolkits.mplot3d.art3d import Line3DCollection

    x = mesh.points
    used = np.unique(np.concatenate([b.cells.ravel() for b in mesh.blocks]))
    size = float(np.ptp(x[used], axis=0).max())
    view = _view_vector(elev, azim)
    lines = [x[p] for p in boundary_edges(mesh, view, max_edges)]
    ax.add_collection3d(Line3DCollection(lines, colors=_EDGE_COLOR, linewidths=0.6, zorder=2, gid="edges"))
    if transition:
        _transition_band(ax, mesh, view)
    for block in mesh.interfaces if highlight_interface else ():
        order = np.concatenate([p[:-1] for p in _side_paths(block.element.face)])
        _polygon(ax, x[block.side("A")[:, order]], color=_CONTACT_COLOR, alpha=0.55, zorder=1,
                 gid="interface-face", label=f"interface elements '{block.name}' ({len(block.cells)})")
        if nodes:
            on = np.unique(block.side("A"))
            ax.scatter(*x[on].T, marker="o", s=7, color="#7e5109", depthshade=False, zorder=3,
                       gid="interface-nodes", label=f"interface nodes ({on.size})")
    extent = [x[used]]
    for k, (names, label) in enumerate(supports):
        names = (names,) if isinstance(names, str) else tuple(names)
        color = ("#1b4f72", "#7d3c98", "#1e8449")[k % 3]
        for j, name in enumerate(names):  # one colour and one legend entry per support
            _support(ax, mesh, name, label if j == 0 else None, size, view, color=color, shown=", ".join(names))
    for k, (point, force, label) in enumerate(loads):
        extent.append(_load(ax, point, force, label, 0.2 * size, gid=f"load:{k}"))
    lo, hi = np.min(np.vstack(extent), axis=0), np.max(np.vstack(extent), axis=0)
    _limits(ax, lo - 0.04 * size, hi + 0.04 * size, zoom=zoom)


def _transition_band(ax, mesh: Mesh, view):
    """The outer lateral faces (normal ⟂ z, turned to ``view``) of the transition elements
    (a QUAD9/QUAD16 contact face: HEX21, HEX28), lightly shaded: the layer on the bodies' sides."""
    blocks = [b for b in mesh.blocks if b.element.face_element in (QUAD9, QUAD16) and len(b.cells)]
    if not blocks:
        return
    layer = np.unique(np.concatenate([b.cells.ravel() for b in blocks]))
    polygons = []
    for face, g in _boundary_faces(mesh):
        x = mesh.points[g[:, :4]]
        n = np.cross(x[:, 1] - x[:, 0], x[:, 3] - x[:, 0])
        n /= np.linalg.norm(n, axis=1, keepdims=True)
        sel = np.all(np.isin(g, layer), axis=1) & (np.abs(n[:, 2]) < 1e-9) & (n @ view > 0)
        order = np.concatenate([p[:-1] for p in _side_paths(face)])
        polygons += list(mesh.points[g[sel][:, order]])
    if polygons:
        names = "/".join(sorted({b.element.name for b in blocks}))
        _polygon(ax, polygons, color="#5dade2", alpha=0.35, zorder=1, gid="transition-layer",
                 label=f"transition elements ({names}), sides")


def _clip(mesh: Mesh, lo, hi, lift: float = 0.0) -> Mesh:
    """The cells and interface elements of ``mesh`` with every node inside the box lo..hi [mm]
    (node sets cut to the nodes of those cells; all points kept, so indices stay valid), the
    body on side B of the interfaces moved up by ``lift`` [mm] (a body: the blocks named
    "<body>.*" as :func:`.mesh.merge` names them)."""
    tol = 1e-9 * float(np.ptp(mesh.points, axis=0).max())
    inside = np.all((mesh.points >= lo - tol) & (mesh.points <= hi + tol), axis=1)
    blocks = [CellBlock(b.name, b.element, b.cells[inside[b.cells].all(axis=1)]) for b in mesh.blocks]
    interfaces = [InterfaceBlock(i.name, i.element, i.cells[inside[i.cells].all(axis=1)]) for i in mesh.interfaces]
    used = np.unique(np.concatenate([b.cells.ravel() for b in blocks]))
    if used.size == 0:
        raise ValueError(f"detail: no cell lies inside the box {lo.tolist()} .. {hi.tolist()} mm")
    node_sets = {k: np.intersect1d(v, used) for k, v in mesh.node_sets.items()}
    points = mesh.points.copy()
    if lift and interfaces:
        side_b = np.concatenate([i.side("B").ravel() for i in interfaces])
        bodies = {b.name.split(".")[0] for b in blocks if np.isin(b.cells, side_b).any()}
        upper = [b.cells.ravel() for b in blocks if b.name.split(".")[0] in bodies]
        points[np.unique(np.concatenate(upper + [side_b])), 2] += lift
    return Mesh(points, blocks, node_sets, {}, interfaces, mesh.name)


def _pairs(ax, mesh: Mesh, label: str):
    """Dotted lines from side A to side B at the four outer corners of each interface block;
    ``label`` on the first (the legend's note that the drawing, not the interface, has a gap)."""
    for block in mesh.interfaces:
        a, b = block.side("A").ravel(), block.side("B").ravel()
        x = mesh.points[a]
        for sx in (-1.0, 1.0):
            for sy in (-1.0, 1.0):
                k = int(np.argmax(sx * x[:, 0] + sy * x[:, 1]))
                ax.plot(*np.column_stack([mesh.points[a[k]], mesh.points[b[k]]]), color="0.35",
                        linestyle=(0, (1, 2)), linewidth=0.9, zorder=2, gid="pair", label=label)
                label = "_nolegend_"


def _box_outline(ax, lo, hi):
    """The 12 edges of the box lo..hi, dashed (gid "detail-box")."""
    for n, (axis, fixed) in enumerate(_cube_edges()):
        ends = np.empty((2, 3))
        ends[:, axis] = lo[axis], hi[axis]
        for k, s in fixed.items():
            ends[:, k] = lo[k] if s < 0 else hi[k]
        ax.plot(*ends.T, color="0.2", linestyle=(0, (4, 3)), linewidth=0.9, zorder=3, gid="detail-box",
                label="detail (right panel)" if n == 0 else "_nolegend_")


def _support(ax, mesh: Mesh, name: str, label: str | None, size: float, view, *, color, shown: str | None = None,
             max_markers: int = 30):
    """A planar node set turned away from the viewer (``view``: a vector towards the camera) as
    a thin plate just outside the body (triangles there would float in front of the body);
    otherwise triangles at (at most ``max_markers`` of) its nodes. The legend reads
    "label (shown)" (``shown`` defaults to the set's name); no entry if ``label`` is None."""
    pts = mesh.points[mesh.node_sets[name]]
    if not len(pts):
        return
    shown = name if shown is None else shown
    span = np.ptp(pts, axis=0)
    axis = int(np.argmin(span))
    side = np.sign(pts[0, axis] - mesh.points[:, axis].mean()) or -1.0  # away from the body's centre
    if span[axis] < 1e-9 * size and side * view[axis] <= 0:
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        u, v = [k for k in range(3) if k != axis]
        corners = np.empty((4, 3))
        corners[:, axis] = pts[0, axis] + side * 0.015 * size
        corners[:, u], corners[:, v] = (lo[u], hi[u], hi[u], lo[u]), (lo[v], lo[v], hi[v], hi[v])
        _polygon(ax, [corners], color=color, alpha=0.3, gid=f"plate:{name}", zorder=0,
                 label=f"{label} ({shown}, behind)" if label is not None else "_nolegend_")
        return
    shown_pts = pts[np.linspace(0, len(pts) - 1, min(len(pts), max_markers)).round().astype(int)]
    ax.scatter(*shown_pts.T, marker="^", s=16, color=color, depthshade=False, zorder=4,
               label=f"{label} ({shown})" if label is not None else "_nolegend_", gid=f"support:{name}")


def _load(ax, point, force, label: str, length: float, *, gid: str) -> np.ndarray:
    """An arrow of ``length`` [mm] along ``force`` ending at ``point``; returns its tail."""
    p = np.asarray(point, dtype=float)
    u = np.asarray(force, dtype=float) / np.linalg.norm(force)
    tail = p - length * u
    ax.quiver(*tail, *(length * u), color="#b03a2e", linewidth=2.0, arrow_length_ratio=0.25, zorder=5, gid=gid)
    ax.text(*(tail - 0.08 * length * u), label, fontsize=9, color="#b03a2e", ha="center", va="bottom", zorder=6)
    return tail
