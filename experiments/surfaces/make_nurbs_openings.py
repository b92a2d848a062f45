"""Write nurbs_roof_openings.json: the NURBS roof of nurbs_roof.json with two openings (an example input).

A skylight (a rectangle in (u, v)) and a triangular opening over a support,
given as ``"holes"``: closed polylines in parameter space.
Run ``python experiments/surfaces/make_nurbs_openings.py``; the JSON beside
this script is its output.
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from make_nurbs_roof import roof, write  # noqa: E402

#: The openings, in (u, v) on the roof's domain [0, 1]^2.
HOLES = [
    [[0.3, 0.35], [0.45, 0.35], [0.45, 0.65], [0.3, 0.65]],
    [[0.62, 0.3], [0.85, 0.45], [0.65, 0.7]],
]


def roof_with_openings():
    d = roof()
    d["description"] = "The NURBS roof of nurbs_roof.json with a skylight and a triangular opening (holes in (u, v))."
    d["holes"] = HOLES
    return d


def main(argv=None):
    return write("nurbs_roof_openings.json", roof_with_openings())


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
