"""Figs 14/15 (rule fe_punch_mesh_figure): the quarter punch on the foundation as the engine
meshes it (roughcontact.fe.punch_mesh), with supports, load and the interface."""

from roughcontact import io
from roughcontact.fe.punch_mesh import PunchGeometry, figure_annotations, punch_mesh, summary
from roughcontact.paper import drawings, plots

CAPTION = {"quadratic": "Fig. 14: punch on foundation with 21-node transition and 18-node interface elements",
           "cubic": "Fig. 15: punch on foundation with 28-node transition and 32-node interface elements"}


def run(geometry, out, log):
    with io.log_to(log):
        g = PunchGeometry(**geometry)
        mesh = punch_mesh(g)
        s = summary(mesh)
        fig = drawings.mesh_figure(mesh, title=f"{CAPTION[g.family]} ({s['contact_points']} contact points, "
                                               f"{s['nodes']} nodes; quarter model)", **figure_annotations(g))
        plots.save(fig, out)


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.geometry, sm.output.png, sm.log[0])
