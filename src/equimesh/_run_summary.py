"""What ``equimesh mesh`` prints about the mesh it wrote: the one-screen summary, and notes.

The summary's rows are those of :func:`equimesh.metrics.summary_rows`, which the
HTML report shows too.  One note answers a mesh with an angle below
:data:`~equimesh.tolerance.JOINT_ANGLE` under an objective that does not keep
the joints sound with the objectives that do (docs/decisions.md, "Sound
joints"); another says when the optimisation ended at its work bound, at the
best point its objective kept (docs/decisions.md, "A work bound for the optimisation").
"""

from .metrics import fabrication_summary, rows_of_summary
from .surface.optimize import OBJECTIVES
from .tolerance import JOINT_ANGLE


def summary(mesh, objective, tolerance, catalogue=None):
    """``(text, notes)``: the summary of ``mesh``, made under ``objective``, at the fabrication ``tolerance`` (and a
    stock ``catalogue``), a row a line, and the notes it calls for (:func:`joints_note`, :func:`work_note`)."""
    figures = fabrication_summary(mesh.edge_lengths(), mesh.length, tolerance, mesh.points, mesh.triangles, catalogue)
    rows = rows_of_summary(figures, mesh.length, tolerance, mesh.deviation(), catalogue)
    width = max(len(label) for label, _ in rows) + 2
    notes = (joints_note(figures["sharp_share"], objective), work_note(mesh))
    return "\n".join(f"{label:<{width}}{value}" for label, value in rows), [note for note in notes if note]


def joints_note(sharp, objective):
    """The note for a mesh made under ``objective`` with a share ``sharp`` of triangles with a joint too sharp to
    build (:func:`~equimesh.metrics.sharp_share`), naming the objectives that keep every joint sound; None if it has
    none or its objective keeps them."""
    sound = [name for name, record in OBJECTIVES.items() if record.sound_joints]
    if objective in sound or not sharp > 0:
        return None
    return (
        f"--optimize {' or '.join(sound)} keeps every triangle angle at least {JOINT_ANGLE:g} degrees, or a sharper "
        "input corner's own (joints that can be built)"
    )


def work_note(mesh):
    """The note for a ``mesh`` whose optimisation ended at its work bound, at the best point its objective kept
    (:attr:`~equimesh.surface.optimize.driver.UVOptimization.work_bound_reached`); None otherwise."""
    result = mesh.stages.optimization  # None without an optimisation
    if result is None or not result.work_bound_reached:
        return None
    return f"the optimisation ended at {result.message}, not converged"
