"""The two insertion engines against the size of the output.

Uses only equimesh's public API (``equimesh.increment``,
``equimesh.uniform_triangulation``, ``equimesh.node_lower_bound``).  The
reference engine grows about as n^2.5: its cases above
``common.REFERENCE_MAX_NODES`` / ``common.REFERENCE_MAX_AREA`` are skipped
(``NotImplementedError`` in ``setup``, asv's way of skipping a combination).
"""

import equimesh

from .common import (
    ENGINES,
    NODE_COUNTS,
    PROBLEM2_AREAS,
    REFERENCE_MAX_AREA,
    REFERENCE_MAX_NODES,
    SHAPES,
    L,
    polygon,
    square_for_nodes,
)


class IncrementBySize:
    """Problem 1 on a square sized for about 10^3, 10^4, 10^5 output nodes (l = 1), both engines."""

    params = [list(ENGINES), list(NODE_COUNTS)]
    param_names = ["engine", "nodes"]
    repeat = (1, 3, 30.0)
    timeout = 300.0

    def setup(self, engine, nodes):
        if engine == "reference" and nodes > REFERENCE_MAX_NODES:
            raise NotImplementedError("the reference engine is benchmarked up to REFERENCE_MAX_NODES")
        self.vertices = square_for_nodes(nodes)

    def _run(self, engine):
        return equimesh.increment(self.vertices, L, engine=engine, max_nodes=None)

    def time_increment(self, engine, nodes):
        """Wall time of the whole call (validation, Step 2, insertion, Theorem 1 check)."""
        self._run(engine)

    def peakmem_increment(self, engine, nodes):
        """Peak resident memory of one call."""
        self._run(engine)

    def track_ratio_to_lower_bound(self, engine, nodes):
        """n' / node_lower_bound (Theorem 2: at most 16/3)."""
        return self._run(engine).n_nodes / equimesh.node_lower_bound(self.vertices, L)

    track_ratio_to_lower_bound.unit = "n'/LB"


class UniformTriangulationBySize:
    """Problem 2 on the frozen polygons of area 10^2, 10^3, 10^4 l^2 (l = 1), both engines."""

    params = [list(ENGINES), list(SHAPES), list(PROBLEM2_AREAS)]
    param_names = ["engine", "shape", "area"]
    repeat = (1, 3, 30.0)
    timeout = 300.0

    def setup(self, engine, shape, area):
        if engine == "reference" and area > REFERENCE_MAX_AREA:
            raise NotImplementedError("the reference engine is benchmarked up to REFERENCE_MAX_AREA")
        self.vertices = polygon(shape, area)

    def _run(self, engine):
        return equimesh.uniform_triangulation(self.vertices, L, engine=engine, max_nodes=None)

    def time_uniform_triangulation(self, engine, shape, area):
        """Wall time of the whole call (lattice part, strip insertion, Theorem 3 check)."""
        self._run(engine)

    def peakmem_uniform_triangulation(self, engine, shape, area):
        """Peak resident memory of one call."""
        self._run(engine)

    def track_g1_share(self, engine, shape, area):
        """Share of the edges in G1 (exactly l long), the quantity Problem 2 maximises."""
        return float(self._run(engine).g1_mask.mean())

    track_g1_share.unit = "G1 edges / edges"
