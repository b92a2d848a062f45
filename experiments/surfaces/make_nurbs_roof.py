"""Write nurbs_roof.json: a doubly curved NURBS roof with non-uniform knots and weights (an example input).

Run ``python experiments/surfaces/make_nurbs_roof.py``; the JSON beside this script is its output.
"""

import json
import sys
from pathlib import Path

import numpy as np


def roof():
    """A 60 x 40 roof, bicubic in u and biquadratic in v, rising 8 to 12 with a ridge pulled up by heavier weights."""
    knots_u = [0.0, 0.0, 0.0, 0.0, 0.3, 0.55, 1.0, 1.0, 1.0, 1.0]
    knots_v = [0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0]
    x = np.array([0.0, 8.0, 22.0, 36.0, 50.0, 60.0])
    y = np.array([0.0, 12.0, 28.0, 40.0])
    rise = np.outer(np.sin(np.pi * np.linspace(0, 1, 6)), np.sin(np.pi * np.linspace(0, 1, 4)))
    net = np.stack(np.broadcast_arrays(x[:, None], y[None, :], 4.0 + 10.0 * rise), axis=-1)
    weights = np.ones((6, 4))
    weights[2:4, 1:3] = [[1.6, 1.3], [1.3, 1.8]]
    return {
        "type": "nurbs",
        "description": "Doubly curved roof over 60 x 40: NURBS of degree (3, 2), non-uniform knots, weights up to 1.8.",
        "degree": [3, 2],
        "knots_u": knots_u,
        "knots_v": knots_v,
        "control_points": np.round(net, 6).tolist(),
        "weights": weights.tolist(),
    }


def write(name, description):
    """Write the JSON ``description`` as ``name`` beside this script."""
    out = Path(__file__).with_name(name)
    out.write_text(json.dumps(description, indent=1) + "\n")
    print(f"wrote {out}")
    return 0


def main(argv=None):
    return write("nurbs_roof.json", roof())


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
