"""Problem 1 (Section 2 of the paper): Algorithm INCREMENT on convex polygons.

Uses only equimesh's public API (``equimesh.increment``,
``equimesh.node_lower_bound``).
"""

import equimesh

from .common import POLYGON_AREAS, SHAPES, L, polygon


class Increment:
    """``equimesh.increment(vertices, l, engine="reference")``: the reference engine, as since the first commit.

    (The default engine is "fast" (docs/decisions.md, "Two engines, one algorithm"); this suite keeps the
    reference engine so that its history stays comparable.  Both engines by
    size: ``bench_engines.py``.)

    Data sizes: l = 1 and a frozen polygon (see ``common.polygon``) of area
    25, 100 or 400 l^2 -- a square, a long thin 8:1 rectangle, or a seeded
    random convex 7-gon with every inner angle >= 90 degrees.  The output node
    count grows linearly with the area; ``track_node_count`` records it.
    """

    params = [list(SHAPES), list(POLYGON_AREAS)]
    param_names = ["shape", "area"]
    # The largest case takes a fraction of a second per call: a few samples
    # per process are plenty and keep `make bench` short.
    repeat = (1, 5, 10.0)
    timeout = 120.0

    def setup(self, shape, area):
        self.vertices = polygon(shape, area)

    def time_increment(self, shape, area):
        """Wall time of Steps 1-5 (validation, boundary, insertion, Delaunay)."""
        equimesh.increment(self.vertices, L, engine="reference")

    def peakmem_increment(self, shape, area):
        """Peak resident memory of one call."""
        equimesh.increment(self.vertices, L, engine="reference")

    def track_node_count(self, shape, area):
        """n', the number of nodes of the output mesh."""
        return len(equimesh.increment(self.vertices, L, engine="reference").points)

    track_node_count.unit = "nodes"

    def track_ratio_to_lower_bound(self, shape, area):
        """n' / node_lower_bound: Theorem 2 says it is at most 16/3."""
        n = len(equimesh.increment(self.vertices, L, engine="reference").points)
        return n / equimesh.node_lower_bound(self.vertices, L)

    track_ratio_to_lower_bound.unit = "n'/LB"
