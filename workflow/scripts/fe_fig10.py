"""Fig. 10 (rule fe_fig10): the beam model as the engine meshes it — the quarter beam with its
transition layer, the rigid-base interface, the symmetry supports and the load."""

from roughcontact import io
from roughcontact.examples.beam import BeamSpec, beam_mesh
from roughcontact.paper import drawings, plots


def run(spec, out, log):
    with io.log_to(log):
        spec = BeamSpec(**spec)
        mesh = beam_mesh(spec)
        fig = drawings.mesh_figure(
            mesh, title=f"Fig. 10: quarter of the beam on a rigid base ({spec.elements} transition layer, "
                        f"{mesh.summary()['nodes']} nodes)",
            supports=[("XSYMMETRY", "symmetry u_x = 0 (mid-length)"), ("YSYMMETRY", "symmetry u_y = 0 (mid-thickness)"),
                      ("BASENODES", "rigid base (every node held)")],
            loads=[((0.0, 0.0, spec.height), (0.0, 0.0, -30.0), "P/4 (line load at x = 0)")],
            azim=125.0, elev=18.0, figsize=(9.0, 6.0),  # seen from the outer face y = b/2 and the mid-length end
        )
        plots.save(fig, out)


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    run(sm.params.spec, sm.output.png, sm.log[0])
