"""The variables of the final optimisation: which parameters of which nodes move, and how far they may.

A free node's two parameters are variables, kept in the chart's domain by
bounds (:func:`parameter_box`); a node sliding along a closed polyline in
(u, v) has one variable, its arc position (:mod:`~equimesh.surface.optimize.slide`),
its Jacobian column the chain rule through ``d uv / d s``.  With a surface
tolerance ``D > 0`` every node that moves also has an offset ``h`` in
``[-D, D]`` along the surface's unit normal: its point is
``X^s(u, v) + h N(u, v)`` (docs/decisions.md, "Nodes off the surface within a tolerance").
"""

import threading
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np
import scipy.optimize
import scipy.sparse

from ..._checks import index_rows
from ..._jit import compiled
from ...errors import EquimeshError
from ..charts.chart import domain_of
from ..regularity import derivatives, evaluate
from .joints import Joints


@dataclass(frozen=True)
class UVProblem:
    """The data every objective builder sees.

    Attributes
    ----------
    surface : Chart
    uv : (N, 2) float array
        Start parameters of all nodes (after remapping, step 4).
    edges : (E, 2) int array
    edge_groups : (E,) int array
        :data:`~equimesh.mesh.G1` or :data:`~equimesh.mesh.OTHER` per edge.
    length : float
        The target length l.
    free : (N,) bool array
        True for the nodes whose two parameters are variables.
    slides : tuple of :class:`~equimesh.surface.optimize.slide.Slide`
        Nodes that slide along a closed polyline by their arc position (their
        ``free`` entries False): one variable each, after the free parameters.
    joints : :class:`~equimesh.surface.optimize.joints.Joints` or None
        The angle bounds the optimisation keeps (objectives with sound joints), or None.
    surface_tolerance : float
        ``D``: how far a node may leave the surface along its normal (0: on the surface).
    tolerance : float
        The fabrication tolerance of a length class, relative to l (:mod:`equimesh.classes`).
    catalogue : (k,) float array or None
        Stock lengths in units of l, in [1, 2]: the only nominal lengths of the classes, or None.
    """

    surface: object
    uv: np.ndarray
    edges: np.ndarray
    edge_groups: np.ndarray
    length: float
    free: np.ndarray
    slides: tuple = ()
    joints: object = None
    surface_tolerance: float = 0.0
    tolerance: float = 0.005
    catalogue: np.ndarray = None

    def with_joints(self, triangles, bounds):
        """This problem keeping the angle ``bounds`` (radians, one per corner) of ``triangles``: its :attr:`joints`
        a :class:`~equimesh.surface.optimize.joints.Joints` on the new problem itself, so that the members and the
        angles at an ``x`` share one evaluation of the surface (:meth:`at`)."""
        problem = replace(self, joints=None)
        object.__setattr__(problem, "joints", Joints(problem, triangles, bounds))
        return problem

    def sound(self, x):
        """Every triangle angle at ``x`` at least its bound (:attr:`joints`; True without bounds)."""
        return self.joints is None or self.joints.sound(x)

    @property
    def variables(self):
        """(2N,) bool mask of the entries of ``uv.ravel()`` that are variables themselves."""
        return np.repeat(np.asarray(self.free, dtype=bool), 2)

    @property
    def moving(self):
        """(2N,) bool mask of the entries of ``uv.ravel()`` that depend on the variables (the Jacobians' columns)."""
        moving = self.variables.copy()
        for slide in self.slides:
            moving[2 * slide.nodes] = moving[2 * slide.nodes + 1] = True
        return moving

    @cached_property
    def offset_nodes(self):
        """The nodes with an offset along the normal: every node that moves, if :attr:`surface_tolerance` > 0."""
        if self.surface_tolerance <= 0:
            return np.zeros(0, dtype=np.int64)
        sliding = [np.asarray(slide.nodes, dtype=np.int64) for slide in self.slides]
        return np.union1d(np.flatnonzero(self.free), np.concatenate([np.zeros(0, dtype=np.int64), *sliding]))

    @property
    def sliding_variables(self):
        """Bool mask of the variables that move boundary nodes: the arc positions."""
        n = int(np.count_nonzero(self.free))
        return np.concatenate(
            [
                np.zeros(2 * n, dtype=bool),
                *(np.ones(len(slide.nodes), dtype=bool) for slide in self.slides),
                np.zeros(len(self.offset_nodes), dtype=bool),
            ]
        )

    @property
    def x0(self):
        """The start as a variable vector: ``(u_0, v_0, u_1, v_1, ...)`` over free nodes, then the arc positions,
        then the offsets (zero)."""
        return np.concatenate(
            [self.uv.ravel()[self.variables], *(slide.s for slide in self.slides), np.zeros(len(self.offset_nodes))]
        )

    def __post_init__(self):
        # The quantities computed at the last x asked for (at), one record per thread: the driver solves a stage
        # beside the others (Stage.beside), each thread at its own x.
        object.__setattr__(self, "_last", threading.local())

    def at(self, x, name, compute):
        """``compute(x)``, once per ``x`` and thread: the residuals, the Jacobian, the guards and the rounds of one
        iteration ask for the nodes' (u, v), points and tangents (and the joints for the angles) at the same ``x``.
        Read-only, since shared."""
        last = self._last.__dict__
        if "x" not in last or not np.array_equal(last["x"], x):
            last.clear()
            last["x"] = np.array(x)
        if name not in last:
            value = compute(x)
            for array in value if isinstance(value, tuple) else (value,):
                array.flags.writeable = False
            last[name] = value
        return last[name]

    def uv_of(self, x):
        """All nodes' (u, v) with the free ones taken from the variable vector ``x`` (read-only)."""
        return self.at(x, "uv", self._uv_of)

    def _uv_of(self, x):
        variables = self.variables
        full = self.uv.ravel().copy()
        n = int(variables.sum())
        full[variables] = x[:n]
        full = full.reshape(-1, 2)
        for slide in self.slides:
            full[slide.nodes] = slide.uv(x[n : n + len(slide.nodes)])
            n += len(slide.nodes)
        return full

    def offsets_of(self, x):
        """(N,) every node's offset along the normal (zero for the nodes without one)."""
        offsets = np.zeros(len(self.uv))
        k = len(self.offset_nodes)
        if k:
            offsets[self.offset_nodes] = x[len(x) - k :]
        return offsets

    def points_of(self, x):
        """(N, 3) the nodes' points: ``X^s(u, v)``, plus ``h N(u, v)`` with a surface tolerance (read-only)."""
        return self.at(x, "points", self._points_of)

    def _points_of(self, x):
        return offset_points(self.surface, self.uv_of(x), self.offsets_of(x) if len(self.offset_nodes) else None)

    def tangents(self, x):
        """``(d p / du, d p / dv)`` of every node's point at ``x``, each (N, 3): ``X^s_u + h N_u`` and likewise in v.

        ``N_u = (n_u - N (N . n_u)) / |n|`` for ``n = X^s_u x X^s_v``,
        ``n_u = X^s_uu x X^s_v + X^s_u x X^s_uv``; a chart without
        ``second_derivatives`` (a triangle mesh's, piecewise linear) has ``N_u = 0``.  Read-only.
        """
        return self.at(x, "tangents", self._tangents)

    def _tangents(self, x):
        uv = self.uv_of(x)
        su, sv = derivatives(self.surface, uv)
        if not len(self.offset_nodes) or not hasattr(self.surface, "second_derivatives"):
            return su, sv
        normal, size = unit_normals(self.surface, uv)
        suu, suv, svv = (np.asarray(d, dtype=float).reshape(-1, 3) for d in self.surface.second_derivatives(*uv.T))
        h = self.offsets_of(x)[:, None]
        out = []
        for tangent, dn in ((su, np.cross(suu, sv) + np.cross(su, suv)), (sv, np.cross(suv, sv) + np.cross(su, svv))):
            dn = (dn - normal * np.sum(normal * dn, axis=1, keepdims=True)) / size[:, None]
            out.append(tangent + h * dn)
        return tuple(out)

    def offset_columns(self, elements, grads, x):
        """A Jacobian over the variables whose only entries are the offsets' columns: ``grads[j, c] . N`` for the
        node ``elements[j, c]`` (``grads`` (E, k, 3): the derivatives of residual j by the points of its nodes)."""
        elements = np.asarray(elements, dtype=np.int64)
        n, k = len(x), len(self.offset_nodes)
        column = np.full(len(self.uv), -1, dtype=np.int64)
        column[self.offset_nodes] = np.arange(n - k, n)
        normal = unit_normals(self.surface, self.uv_of(x))[0]
        values = np.einsum("jcd,jcd->jc", grads, normal[elements])
        cols = column[elements]
        keep = cols >= 0
        rows = np.repeat(np.arange(len(elements)), elements.shape[1]).reshape(elements.shape)
        return scipy.sparse.csr_matrix((values[keep], (rows[keep], cols[keep])), shape=(len(elements), n))

    def chain(self, jacobian, x):
        """``jacobian`` over the :attr:`moving` entries as one over the variables ``x`` (chain rule), on its structure.

        A free node's two columns are its two variables'; a sliding node's
        column pair ``(d/du, d/dv)`` becomes its one column, the two entries
        scaled by the loop's direction ``d uv / d s`` at its ``s`` and kept
        side by side in the row, to be summed (as every product with the
        matrix sums them).  So the result has the Jacobian's structure
        whatever the values: the product with the matrix ``d uv / d x``
        dropped the sums that came out exactly zero, a new structure whenever
        a barrier triangle woke or slept, and the normal equations were
        analysed anew at nearly every iteration
        (docs/decisions.md, "One pattern for the normal matrix, three factorisations").
        """
        offsets = len(self.offset_nodes)  # their columns come last, zero here
        if not self.slides:
            if not offsets:
                return jacobian
            return scipy.sparse.hstack([jacobian, scipy.sparse.csr_matrix((jacobian.shape[0], offsets))], format="csr")
        column, along, n = self._chain_maps
        starts = self._slide_starts
        directions = np.concatenate(
            [slide.direction(x[start : start + len(slide.nodes)]) for slide, start in zip(self.slides, starts)]
        ).ravel()
        jacobian = jacobian.tocsr()
        data, indices = _chain_entries(jacobian.data, jacobian.indices, column, along, directions)
        return scipy.sparse.csr_matrix((data, indices, jacobian.indptr), shape=(jacobian.shape[0], n + offsets))

    @cached_property
    def _slide_starts(self):
        """Each slide's first variable (its arc positions follow the free parameters, slide by slide)."""
        return np.cumsum([int(self.variables.sum())] + [len(slide.nodes) for slide in self.slides])[:-1]

    @cached_property
    def _chain_maps(self):
        """For :meth:`chain`, per column of a Jacobian over the :attr:`moving` entries: its variable's column, and
        the entry of the sliding nodes' flattened directions ``d uv / d s`` that scales it (-1: none); and the number
        of parameter variables."""
        moving, variables = self.moving, self.variables
        n = int(variables.sum())
        entry = np.cumsum(moving) - 1  # column of each moving entry in a Jacobian over them
        column = np.empty(int(moving.sum()), dtype=np.int32 if len(moving) < np.iinfo(np.int32).max else np.int64)
        along = np.full(int(moving.sum()), -1, dtype=np.int64)
        column[entry[variables]] = np.arange(n)
        done = 0
        for slide in self.slides:
            k = len(slide.nodes)
            for axis in (0, 1):
                column[entry[2 * slide.nodes + axis]] = np.arange(n, n + k)
                along[entry[2 * slide.nodes + axis]] = 2 * np.arange(done, done + k) + axis
            n, done = n + k, done + k
        return column, along, n

    def step_limit(self, radius):
        """A trust region per node: ``direction -> step`` with every node's move on the surface at most ``radius``.

        A node's move is taken to first order at its start (the tangent
        lengths ``|X_u|``, ``|X_v|`` at :attr:`uv` times its steps in u and v,
        or ``max(|X_u|, |X_v|)`` times its step along its loop, which is in
        (u, v) arc length), and the steps of a node that would move further
        are scaled down together (its direction in (u, v) is kept).
        """
        su, sv = derivatives(self.surface, self.uv)
        tangent = np.column_stack([np.linalg.norm(su, axis=1), np.linalg.norm(sv, axis=1)])
        variables = self.variables
        offsets = self.offset_nodes
        node = np.concatenate(
            [np.repeat(np.arange(len(self.uv)), 2)[variables], *(s.nodes for s in self.slides), offsets]
        )
        scale = np.concatenate(
            [
                tangent.ravel()[variables],
                *(tangent[s.nodes].max(axis=1) for s in self.slides),
                np.ones(len(offsets)),
            ]
        )

        def limit(direction):
            move = np.sqrt(np.bincount(node, (scale * direction) ** 2, len(self.uv)))
            factor = np.ones_like(move)
            far = move > radius
            factor[far] = radius / move[far]
            return direction * factor[node]

        return limit

    @property
    def bounds(self):
        """``(lower, upper)`` of the variables: the parameter domain, and each sliding node's range of arc positions."""
        lower, upper = parameter_box(self.surface)
        variables = self.variables
        d = np.full(len(self.offset_nodes), float(self.surface_tolerance))
        return (
            np.concatenate([np.tile(lower, len(self.uv))[variables], *(slide.lower for slide in self.slides), -d]),
            np.concatenate([np.tile(upper, len(self.uv))[variables], *(slide.upper for slide in self.slides), d]),
        )


def _chain_entries(data, indices, column, along, directions):
    """The entries of :meth:`UVProblem.chain`: each column ``c`` of ``indices`` mapped to ``column[c]``, its value
    multiplied by ``directions[along[c]]`` where ``along[c] >= 0`` and kept as it is elsewhere (the product by 1 of
    a vectorised version, the same bits), in one compiled pass."""
    out_data, out_indices = np.empty(len(data)), np.empty(len(indices), dtype=column.dtype)
    for e in range(len(data)):
        c = indices[e]
        out_indices[e] = column[c]
        out_data[e] = data[e] * directions[along[c]] if along[c] >= 0 else data[e]
    return out_data, out_indices


_chain_entries = compiled(_chain_entries)


def offset_points(surface, uv, offsets=None):
    """(N, 3) ``X^s(u, v) + h N(u, v)`` at the rows of ``uv`` with the offsets ``h`` along the unit normal (none:
    the surface's points)."""
    points = evaluate(surface, uv)
    if offsets is None:
        return points
    return points + np.asarray(offsets, dtype=float)[:, None] * unit_normals(surface, uv)[0]


def unit_normals(surface, uv):
    """``(N, |n|)`` at the rows of ``uv``: the unit normals ``n / |n|`` of ``n = X^s_u x X^s_v`` and their lengths."""
    su, sv = derivatives(surface, uv)
    n = np.cross(su, sv)
    size = np.linalg.norm(n, axis=1)
    return n / size[:, None], size


def parameter_box(surface):
    """The chart's parameter domain as ``(lower, upper)``, each ``(u, v)``
    (:func:`~equimesh.surface.charts.chart.domain_of`)."""
    domain = domain_of(surface)
    return np.asarray(domain.lower, dtype=float), np.asarray(domain.upper, dtype=float)


def free_nodes(n, fixed, slides):
    """(n,) mask of the nodes whose two parameters are variables: all but the ``fixed`` ones (node indices, or a mask
    of the ``n`` nodes; refused by name if neither) and the sliding ones."""
    free = np.ones(n, dtype=bool)
    fixed = np.asarray(fixed)
    if fixed.dtype == bool:
        if fixed.shape != (n,):
            raise EquimeshError(f"fixed as a mask must have one entry per node ({n}), got shape {fixed.shape}")
        free[fixed] = False
    else:
        indices = index_rows(fixed.reshape(-1, 1), 1, n, "fixed", "entry {} of fixed", "node", EquimeshError)
        free[indices.ravel()] = False
    for slide in slides:
        free[slide.nodes] = False
    return free
