"""Section 4 of the paper: a uniform triangle mesh of a parametric surface.

Modules, in the order of the pipeline:

* :mod:`.chart`      a parameter rectangle with labelled sides plus the map X^s on it
                     (``evaluate``, ``derivatives``): what every stage reads;
* :mod:`.bezier`     the tensor-product Bezier surface, a chart on [0, 1]^2 (geometry only;
                     its JSON form is in :mod:`equimesh.io`);
* :mod:`.nurbs`      NURBS surfaces, a chart on the span of their knot vectors (exact rational
                     first and second derivatives);
* :mod:`.openings`   a chart with holes (closed polylines in (u, v)) cut out of its rectangle;
* :mod:`.triangulated` a user's triangle mesh, checked (connected, manifold, oriented, with a
                     boundary): the auxiliary triangulation given instead of built in step 1;
* :mod:`.auxiliary`  step 1, the auxiliary triangulation of the chart's rectangle;
* :mod:`.regularity` after step 1, the surface refused if non-finite, singular or folding;
* :mod:`.flatten`    step 2, eq. (1): flattening the auxiliary triangulation to the plane;
* :mod:`.ring`       Step 2 on any closed plane polyline with corners (sharp ones kept straight for Problem 2);
* :mod:`.outline`    step 3, the flattened boundary and holes resampled into the polygon of Problem 2;
* :mod:`.mesh_chart` for a triangle mesh: the chart on its flattening (eq. (2) as X^s) and the
                     Tutte start of eq. (1);
* :mod:`.mesh_outline` steps 3-4 for a triangle mesh: boundary loops as the outer ring and
                     openings, boundary nodes placed back on the loops;
* :mod:`.restate`    step 3, Problem 2's refusals of that polygon restated for the surface;
* :mod:`.remap`      step 4, eqs. (2)-(3): plane nodes to (u, v) and to the surface;
* :mod:`.optimize`   final step, the (u, v) of the inner nodes (objective table ``OBJECTIVES``);
* :mod:`.pipeline`   :func:`mesh_surface`, the stages chained;
* :mod:`._jacobian`  sparse least-squares helpers shared by flattening and optimisation;
* :mod:`._places`    sides, corners and points of the patch named for error messages.

The public verbs are re-exported by :mod:`equimesh`.
"""
