"""What ``equimesh mesh`` prints about the mesh it wrote: the one-screen summary, and notes.

The summary's rows are :func:`equimesh.metrics.summary_rows`, which the HTML
report shows too.  One note answers a mesh with an angle below
:data:`~equimesh.tolerance.JOINT_ANGLE` under an objective that does not keep
the joints sound with the objectives that do (docs/decisions.md, "Sound
joints"); another says when the optimisation ended at its work bound, at the
best point its objective kept (docs/decisions.md, "A work bound for the optimisation").
"""

from .metrics import sharp_share, summary_rows, triangle_angles
from .surface.optimize import OBJECTIVES
from .tolerance import JOINT_ANGLE


def summary(mesh, tolerance, catalogue=None):
    """The summary of ``mesh`` at the fabrication ``tolerance`` (and a stock ``catalogue``), a row a line."""
    rows = summary_rows(
        mesh.edge_lengths(), mesh.length, tolerance, mesh.points, mesh.triangles, mesh.deviation(), catalogue
    )
    width = max(len(label) for label, _ in rows) + 2
    return "\n".join(f"{label:<{width}}{value}" for label, value in rows)


def joints_note(mesh, objective):
    """The note for a ``mesh`` made under ``objective`` with a joint too sharp to build (:func:`sharp_share`), naming
    the objectives that keep every joint sound; None if it has none or its objective keeps them."""
    sound = [name for name, record in OBJECTIVES.items() if record.sound_joints]
    if objective in sound or not sharp_share(triangle_angles(mesh.points, mesh.triangles)) > 0:
        return None
    return (
        f"--optimize {', '.join(sound)} keeps every triangle angle at least {JOINT_ANGLE:g} degrees, or a sharper "
        "input corner's own (joints that can be built)"
    )


def work_note(mesh):
    """The note for a ``mesh`` whose optimisation ended at its work bound, at the best point its objective kept
    (:func:`~equimesh.surface.optimize.driver.optimize_uv`); None otherwise."""
    message = getattr(getattr(getattr(mesh, "stages", None), "optimization", None), "message", "")
    return f"the optimisation ended at {message}, not converged" if message.endswith("(its work bound)") else None
