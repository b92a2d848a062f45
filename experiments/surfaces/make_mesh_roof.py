"""Write roof_mesh.obj: a vault over 30 x 20 with a round skylight, as a triangle mesh (an example input).

Run ``python experiments/surfaces/make_mesh_roof.py``; the .obj beside this script is its output.
The plan (a rectangle with a circular opening of radius 3 centred at (12, 10)) is triangulated by
Triangle with quality bounds, then lifted onto ``z = 4 sin(pi x / 30) sin(pi y / 20)``, as a
modeller would export a trimmed roof surface.
"""

import sys
from pathlib import Path

import numpy as np
import triangle

WIDTH, DEPTH, RISE = 30.0, 20.0, 4.0
CENTRE, RADIUS, RIM_POINTS = (12.0, 10.0), 3.0, 32


def roof(max_area=0.5):
    """(vertices, triangles) of the roof; the opening's rim has RIM_POINTS vertices."""
    corners = np.array([[0.0, 0.0], [WIDTH, 0.0], [WIDTH, DEPTH], [0.0, DEPTH]])
    angle = 2.0 * np.pi * np.arange(RIM_POINTS) / RIM_POINTS
    rim = np.column_stack([CENTRE[0] + RADIUS * np.cos(angle), CENTRE[1] + RADIUS * np.sin(angle)])
    ring = lambda start, n: np.column_stack([start + np.arange(n), start + (np.arange(n) + 1) % n])  # noqa: E731
    plan = {
        "vertices": np.vstack([corners, rim]),
        "segments": np.vstack([ring(0, 4), ring(4, RIM_POINTS)]),
        "holes": np.array([CENTRE]),
    }
    out = triangle.triangulate(plan, f"pq30a{max_area}Q")
    xy = out["vertices"]
    z = RISE * np.sin(np.pi * xy[:, 0] / WIDTH) * np.sin(np.pi * xy[:, 1] / DEPTH)
    return np.column_stack([xy, z]), np.asarray(out["triangles"], dtype=np.int64)


def write_obj(path, vertices, triangles):
    """The mesh as Wavefront OBJ text, shortest round-trip floats (not meshio, whose header carries the date)."""
    lines = [f"# {__doc__.splitlines()[0]}"]
    lines += [f"v {x!r} {y!r} {z!r}" for x, y, z in vertices.tolist()]
    lines += [f"f {a} {b} {c}" for a, b, c in (triangles + 1).tolist()]
    path.write_text("\n".join(lines) + "\n")


def main(argv=None):
    out = Path(__file__).with_name("roof_mesh.obj")
    vertices, triangles = roof()
    write_obj(out, vertices, triangles)
    print(f"wrote {out}: {len(vertices)} vertices, {len(triangles)} triangles")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
