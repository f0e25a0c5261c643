"""Figs 14/15 (rule fe_punch_mesh_figure): the quarter punch on the foundation as the engine
meshes its deck (roughcontact.examples.punch.punch_mesh), with supports, load and the interface."""

from roughcontact import io
from roughcontact.examples.punch import PunchSpec, punch_mesh, summary
from roughcontact.examples.punch_geometry import PunchGeometry, figure_annotations
from roughcontact.examples.section9 import MESH_CAPTIONS
from roughcontact.paper import drawings, plots


def run(geometry, out, log):
    with io.log_to(log):
        g = PunchGeometry(**geometry)
        mesh = punch_mesh(PunchSpec(geometry=g))
        s = summary(mesh)
        fig = drawings.mesh_figure(mesh, title=f"{MESH_CAPTIONS[g.family]} ({s['contact_points']} contact points, "
                                               f"{s['nodes']} nodes; quarter model)", **figure_annotations(g))
        plots.save(fig, out)


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.geometry, sm.output.png, sm.log[0])
