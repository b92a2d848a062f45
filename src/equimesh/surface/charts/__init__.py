"""Charts: a parameter domain and a map X^s on it, kept apart from the meshes built on it (Section 4, step 1).

* :mod:`.chart`         the :class:`~.chart.Domain` rectangle with labelled sides and the
                        :class:`~.chart.Chart` protocol (``evaluate``, ``derivatives``);
* :mod:`.bezier`        the tensor-product Bezier surface of the paper, on [0, 1]^2;
* :mod:`.nurbs`         NURBS surfaces, on the span of their knot vectors;
* :mod:`.openings`      a chart with holes cut out of its rectangle;
* :mod:`.triangulated`  a user's triangle mesh, checked and oriented (the auxiliary
                        triangulation given instead of built);
* :mod:`.mesh_chart`    a triangle mesh's flattening as a chart (eq. (2) as X^s).
"""
