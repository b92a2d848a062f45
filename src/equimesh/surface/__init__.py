"""Section 4 of the paper: a uniform triangle mesh of a parametric surface or of a triangle mesh.

Subpackages and modules, in the order of the pipeline:

* :mod:`.charts`       what a surface is: a parameter domain and the map X^s on it (Bezier,
                       NURBS, a chart with openings, a user's triangle mesh and its flattening);
* :mod:`.auxiliary`    step 1, the auxiliary triangulation of the chart's rectangle;
* :mod:`.regularity`   after step 1, the surface refused if non-finite, singular or folding;
* :mod:`.flatten`      step 2, eq. (1): flattening the auxiliary triangulation to the plane;
* :mod:`.ring`         Step 2 on any closed plane polyline with corners (sharp ones kept straight);
* :mod:`.outline`      step 3, the flattened boundary and holes resampled into the polygon of Problem 2;
* :mod:`.mesh_outline` steps 3-4 for a triangle mesh: boundary loops as the outer ring and openings,
                       boundary nodes placed back on the loops;
* :mod:`.remap`        step 4, eqs. (2)-(3): plane nodes to (u, v) and to the surface;
* :mod:`.optimize`     final step, the (u, v) of the nodes (one record per objective);
* :mod:`.messages`     Problem 2's refusals of the outline restated in the surface's terms;
* :mod:`.pipeline`     :func:`~.pipeline.mesh_surface`, the stages chained.

The public verbs are re-exported by :mod:`equimesh`.
"""
