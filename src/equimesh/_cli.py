"""The ``equimesh`` command line.

``equimesh mesh SURFACE.json --length L -o OUT`` meshes a surface (JSON, Rhino
``.3dm`` or a triangle mesh ``.obj``/``.stl``/``.ply``/``.vtk``/``.vtu``) and writes
the mesh (format by OUT's extension) and optionally a member schedule;
``equimesh table1`` and ``equimesh figures`` regenerate the paper's Table 1
and figures (they run the scripts in the source checkout's ``experiments/``).

Every run ends in one of four ways, always without a traceback:

* 0, the outputs written;
* 2 (:data:`EXIT_USAGE`), bad input or an output that cannot be written: one
  line on standard error, and no output file touched (paths are checked before
  the mesh is computed; all outputs of a run are renamed into place together);
  running out of memory ends here too, since the remedy is a smaller request;
* 3 (:data:`EXIT_INTERNAL`), a bug (an :class:`equimesh.InternalError`, a
  proven guarantee failing, or any other unexpected exception): one line
  asking for a report; ``--traceback`` shows the details;
* 130 (:data:`EXIT_INTERRUPTED`, 128 + SIGINT as shells count), Ctrl-C: one
  line, temporary files removed, no output file touched.
"""

import argparse
import importlib.util
import re
import signal
import sys
import warnings
from pathlib import Path

from ._streams import library_quiet, say
from .errors import EquimeshError, SurfaceWarning

EXIT_USAGE = 2
EXIT_INTERNAL = 3
EXIT_INTERRUPTED = 130
EXPERIMENTS = Path(__file__).resolve().parents[2] / "experiments"


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors (no usage dump) and exit code 2, and values that start with a minus sign.

    argparse takes ``-1%`` or ``-1e3`` for an unknown option (its pattern of negative numbers is ``-5`` and ``-.5``),
    so ``--tolerance -1%`` would fail with "expected one argument" instead of saying what is wrong with the value.
    Here a word that starts with ``-`` and a digit (or ``-.`` and a digit) is a value: no option of ours looks so.
    """

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = re.compile(r"-\.?\d")

    def error(self, message):
        self.exit(EXIT_USAGE, f"{self.prog}: error: {message}\n")


def build_parser():
    # The library (numpy, scipy, shapely: seconds on a busy machine) is imported here and in
    # _run_mesh, inside main's handlers, so that a Ctrl-C during the import is one line too.
    from .classes import DEFAULT_TOLERANCE, MAX_TOLERANCE
    from .io import INPUT_FORMATS, OUTPUT_SLOTS
    from .planar.insertion import DEFAULT_ENGINE, ENGINES
    from .surface.mesh_outline import DEFAULT_FEATURE_ANGLE
    from .surface.optimize import OBJECTIVES
    from .surface.optimize.solver import factorisation_name
    from .surface.pipeline import DEFAULT_OPTIMIZE, MAX_GRID_CELLS, PLACEMENTS, UNOPTIMIZED_MAX_NODES

    parser = _Parser(
        prog="equimesh",
        description=(
            "Uniform (equal-edge-length) triangle meshes of curved surfaces, after Katoh, Ohsaki and Xu, "
            "'A uniform triangle mesh generation of curved surfaces'."
        ),
    )
    parser.add_argument(
        "--traceback",
        action="store_true",
        help="on an internal error (exit code 3), show the full traceback for a bug report",
    )
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser, metavar="COMMAND")

    mesh = sub.add_parser(
        "mesh",
        help="mesh a surface (JSON description, Rhino file or triangle mesh) and write the mesh",
        description=(
            "Mesh a surface: flatten its auxiliary triangulation (eq. 1), triangulate the plane with a lattice of "
            "spacing L plus a boundary strip (Problem 2), map back to the surface (eqs. 2-3) and optimise the "
            "inner nodes (--optimize). "
            'SURFACE.json: {"type": "bezier", "control_points": [[[x, y, z], ...], ...]} with rows over u and '
            'columns over v, or {"type": "nurbs", "degree": [p, q], "knots_u": [...], "knots_v": [...], '
            '"control_points": ..., "weights": ...}; SURFACE.3dm: a NURBS surface or a single-face Brep '
            "(needs the extra [rhino]); SURFACE.obj|.stl|.ply|.vtk|.vtu: a triangle mesh (quadrilaterals are split), "
            "connected, manifold, with a boundary, used as the auxiliary triangulation itself (--grid is not used): "
            "its further boundary loops are kept as openings and every node lies on its triangles. Boundary nodes "
            "slide along their boundary loops under --optimize bounded (corners stay put) and are fixed under paper."
        ),
    )
    mesh.add_argument(
        "surface",
        metavar="SURFACE",
        help=f"surface description; format from the extension: {', '.join(sorted(INPUT_FORMATS))}",
    )
    mesh.add_argument(
        "--object",
        metavar="NAME|INDEX",
        help="which object of a Rhino file to mesh, by name or index (needed when it holds several)",
    )
    mesh.add_argument("--length", "-l", type=_number, required=True, metavar="L", help="target member length")
    mesh.add_argument(
        "--grid",
        type=_whole_number,
        nargs=2,
        default=(15, 15),
        metavar=("NU", "NV"),
        help="auxiliary grid cells along u and v (default: 15 15; not used for triangle meshes); at most "
        f"{MAX_GRID_CELLS} cells, because flattening time and memory grow with NU x NV "
        "(about 40 s and 0.6 GB at 200 x 200 on a 2-core machine)",
    )
    mesh.add_argument(
        "--optimize",
        choices=["none", *OBJECTIVES],
        default=DEFAULT_OPTIMIZE,
        help=f"final optimisation of the inner nodes (default: {DEFAULT_OPTIMIZE})",
    )
    mesh.add_argument(
        "--placement",
        choices=PLACEMENTS,
        default="best",
        help="lattice placement: searched for the most equal members, or angle 0 at the origin (default: best)",
    )
    mesh.add_argument(
        "--engine",
        choices=sorted(ENGINES),
        default=DEFAULT_ENGINE,
        help="farthest-point insertion engine of Problem 2: the compiled one, or the reference that "
        f"reads like the paper (default: {DEFAULT_ENGINE})",
    )
    mesh.add_argument(
        "--max-nodes",
        type=_max_nodes,
        default=argparse.SUPPRESS,
        metavar="N",
        help="refuse, before any heavy work, a mesh estimated to need more than N nodes; 'none' for "
        "no limit. The defaults ("
        + ", ".join(
            [f"{UNOPTIMIZED_MAX_NODES} nodes with --optimize none"]
            + [f"{record.node_limit()} with --optimize {name}" for name, record in OBJECTIVES.items()]
        )
        + f", with the factorisation {factorisation_name()} of the optimisation) bound the time of a run to about "
        "two minutes on a 2-core machine (docs/performance.md); beyond them time grows faster than the node count",
    )
    for slot, record in OUTPUT_SLOTS.items():
        mesh.add_argument(
            *(("-o", "--output") if slot == "mesh" else (f"--{slot}",)),
            dest=_output_dest(slot),
            required=record.required,
            metavar=record.metavar,
            help=_output_help(slot, record),
        )
    mesh.add_argument(
        "--feature-angle",
        type=_feature_angle,
        default=argparse.SUPPRESS,
        metavar="DEGREES",
        help="triangle meshes only: a boundary vertex is a corner, a node that stays put, where the boundary turns "
        "by more than DEGREES over a stretch of about L; the rest of each boundary loop is resampled as a curve "
        f"(default: {DEFAULT_FEATURE_ANGLE:g}, at least 0 and below 180)",
    )
    mesh.add_argument(
        "--dxf-labels",
        action="store_true",
        help="in a .dxf mesh file, also write each member's length class as text at its midpoint (layer labels)",
    )
    mesh.add_argument(
        "--tolerance",
        type=_tolerance,
        default=DEFAULT_TOLERANCE,
        metavar="TOL",
        help=(
            "fabrication tolerance of a length class, relative to L: every member of a class is "
            "within +-TOL L of its nominal length, with the fewest classes; '0.5%' or '0.005', "
            f"above 0 and below {MAX_TOLERANCE:.0%} (default: {DEFAULT_TOLERANCE:.1%})"
        ).replace("%", "%%"),
    )
    mesh.add_argument(
        "--surface-tolerance",
        type=_surface_tolerance,
        default=0.0,
        metavar="D",
        help="with --optimize bounded or classes, let every node leave the surface by at most D (a length, below L) "
        "along its normal; the summary reports the deviation (default: 0, every node on the surface)",
    )
    mesh.add_argument(
        "--lengths",
        type=_lengths,
        default=None,
        metavar="L1,L2,...",
        help="with --optimize classes, a catalogue of stock lengths in [L, 2L] (e.g. 5,5.8,7.1): members are cut "
        "from them within --tolerance where possible, the rest reported in the summary and the classes CSV",
    )
    mesh.add_argument(
        "--quiet", "-q", action="store_true", help="print nothing but errors (no progress lines, no summary)"
    )
    mesh.set_defaults(run=_run_mesh)

    for name, text in (
        ("table1", "regenerate Table 1 (results/table1.*)"),
        ("figures", "regenerate Figs 1-5 (paper_figs/) from results/table1_mesh.npz"),
    ):
        # No options of its own: everything, --help included, goes to experiments/<name>.py.
        exp = sub.add_parser(name, help=text, add_help=False)
        exp.set_defaults(run=_run_experiment, experiment=name)
    return parser


def main(argv=None):
    """Run the command line; return the exit code (see the module docstring), never raise but ``SystemExit``."""
    show_traceback = False
    try:
        parser = build_parser()
        args, extra = parser.parse_known_args(argv)
        show_traceback = args.traceback
        if args.run is _run_experiment:
            args.args = extra
        elif extra:
            parser.error(f"unrecognized arguments: {' '.join(extra)}")
        return args.run(args) or 0
    except EquimeshError as exc:
        return _fail(EXIT_USAGE, f"error: {exc}")
    except MemoryError:
        return _fail(EXIT_USAGE, "error: out of memory; use a larger --length, a smaller --grid or a lower --max-nodes")
    except KeyboardInterrupt:
        # An interrupt can leave a library's object half-built (llvmlite's, while numba compiles a kernel), whose
        # finaliser then raises as the interpreter ends: after the one line, such noise is not printed.
        sys.unraisablehook = _quiet
        return _fail(EXIT_INTERRUPTED, "interrupted")
    except Exception as exc:  # InternalError, or any other bug: one line, not a traceback
        if show_traceback:
            raise
        asks = "report" in str(exc)  # the library's own message may ask already (InternalError does)
        return _fail(
            EXIT_INTERNAL,
            f"internal error: {type(exc).__name__}: {exc} ({'' if asks else 'please report this; '}"
            "--traceback shows the details)",
        )


class _Interrupt:
    """Ctrl-C kept until the run sees it.

    Python raises ``KeyboardInterrupt`` wherever the program is; one raised
    inside a finaliser (llvmlite's, while numba compiles a kernel) goes to
    :data:`sys.unraisablehook` and is dropped, and the run would go on to
    write its outputs.  Inside this context a SIGINT is also recorded, such
    unraisable interrupts are not printed, and :meth:`check` (after each
    stage and before the outputs are written) raises the one recorded.
    """

    def __init__(self):
        self.seen = False

    def _handler(self, signum, frame):
        self.seen = True
        raise KeyboardInterrupt

    def _unraisable(self, unraisable):
        if not issubclass(unraisable.exc_type, KeyboardInterrupt):
            self._hook(unraisable)

    def __enter__(self):
        self._hook, sys.unraisablehook = sys.unraisablehook, self._unraisable
        try:
            self._signal = signal.signal(signal.SIGINT, self._handler)
        except ValueError:  # not the main thread: signals go to the main thread's handler
            self._signal = None
        return self

    def __exit__(self, *exc):
        if self._signal is not None:
            signal.signal(signal.SIGINT, self._signal)
        if sys.unraisablehook == self._unraisable:
            sys.unraisablehook = self._hook

    def check(self):
        """Raise the recorded interrupt, if any."""
        if self.seen:
            raise KeyboardInterrupt


def _quiet(unraisable):
    """An unraisable-exception hook that prints nothing (:data:`sys.unraisablehook`)."""


def _fail(code, message):
    """Print ``message`` as one line on standard error and return ``code``."""
    say("equimesh: " + " ".join(message.split()))
    return code


def _output_dest(slot):
    """The attribute of an output option: ``args.output`` for the mesh (``-o``), ``args.<slot>`` for the others."""
    return "output" if slot == "mesh" else slot


def _output_help(slot, record):
    """The help of an output option: what it writes, then every format of the registry, with the extra it needs."""
    from .io import output_formats

    formats = "; ".join(
        f"{ext} ({fmt.name}" + (f", extra [{fmt.extra}]" if fmt.extra else "") + f": {fmt.holds})"
        for ext, fmt in output_formats(slot).items()
    )
    return f"{record.help}; format from the extension: {formats}; all outputs are written together or none"


def _number(text, whole=False):
    """A number as a person types it (:func:`equimesh._checks.number_text`: ``1_0`` is refused, not read as 10)."""
    from ._checks import number_text

    return number_text(text, "the value", argparse.ArgumentTypeError, whole=whole)


def _whole_number(text):
    return _number(text, whole=True)


def _max_nodes(text):
    """``--max-nodes``: a positive whole number, or 'none' for no limit."""
    if text.strip().lower() == "none":
        return None
    from ._checks import check_count

    try:
        return check_count(_whole_number(text), "--max-nodes")
    except (ValueError, argparse.ArgumentTypeError):  # not a whole number, or below 1 (EquimeshError is a ValueError)
        raise argparse.ArgumentTypeError(f"expected a positive whole number or 'none', got {text!r}") from None


def _tolerance(text):
    """``--tolerance``: a fraction of L or a percentage (:func:`equimesh.classes.check_tolerance`)."""
    from .classes import check_tolerance

    try:
        return check_tolerance(text)
    except EquimeshError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def _surface_tolerance(text):
    """``--surface-tolerance``: a length of at least 0 (its bound by L is checked with L)."""
    try:
        value = _number(text)
    except argparse.ArgumentTypeError:
        raise argparse.ArgumentTypeError(f"expected a length of at least 0, got {text!r}") from None
    if not value >= 0:  # also NaN
        raise argparse.ArgumentTypeError(f"expected a length of at least 0, got {text!r}")
    return value


def _lengths(text):
    """``--lengths``: comma-separated numbers (each in [L, 2L], checked with L)."""
    items = [item.strip() for item in text.split(",")]
    try:
        values = [_number(item) for item in items if item]
    except argparse.ArgumentTypeError:
        raise argparse.ArgumentTypeError(
            f"expected numbers separated by commas, such as 5,5.8,7.1, got {text!r}"
        ) from None
    if not values:
        raise argparse.ArgumentTypeError("expected at least one stock length, such as 5,5.8,7.1")
    return values


def _feature_angle(text):
    """``--feature-angle``: degrees as typed (:func:`_number`), at least 0 and below 180
    (``mesh_outline.check_feature_angle``)."""
    from ._checks import number_text
    from .surface.mesh_outline import check_feature_angle

    try:
        return check_feature_angle(number_text(text, "the value", EquimeshError))
    except EquimeshError:  # not a number, or out of range
        raise argparse.ArgumentTypeError(f"expected degrees, at least 0 and below 180, got {text!r}") from None


def _run_mesh(args):
    from ._run_summary import summary
    from .io import OUTPUT_SLOTS, load_surface, surface_mesh_writer
    from .surface.pipeline import mesh_surface

    outputs = {slot: getattr(args, _output_dest(slot)) for slot in OUTPUT_SLOTS}
    write = surface_mesh_writer(
        outputs, inputs=[args.surface], dxf_labels=args.dxf_labels, parameters=_parameters(args)
    )
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", SurfaceWarning)
        surface = load_surface(args.surface, **({"object": args.object} if args.object is not None else {}))
    for warning in caught:
        say(f"equimesh: warning: {warning.message}")

    def progress(stage, seconds):
        interrupt.check()
        if not args.quiet:
            say(f"  {stage}: {seconds:.2f} s")

    given = {name: getattr(args, name) for name in ("max_nodes", "feature_angle") if name in args}
    with library_quiet(), _Interrupt() as interrupt:
        mesh = mesh_surface(
            surface,
            args.length,
            grid=tuple(args.grid),
            optimize=args.optimize,
            placement=args.placement,
            engine=args.engine,
            progress=progress,
            tolerance=args.tolerance,
            lengths=args.lengths,
            surface_tolerance=args.surface_tolerance,
            **given,
        )
        interrupt.check()
    write(mesh, args.tolerance)
    if not args.quiet:
        n_g1 = int(mesh.g1_mask.sum())
        say(
            f"wrote {', '.join(map(str, write.paths))}: {len(mesh.points)} nodes, {len(mesh.edges)} members "
            f"({n_g1} in the equal-length group G1), {len(mesh.triangles)} triangles"
        )
        text, notes = summary(mesh, args.optimize, args.tolerance, args.lengths)
        say(text, sys.stdout)
        for note in notes:
            say(f"equimesh: note: {note}")
    return 0


def _parameters(args):
    """What the run was given, for the report's provenance: the input file and every option set."""
    keys = ("surface", "object", "length", "grid", "optimize", "placement", "engine", "max_nodes", "feature_angle")
    keys += ("tolerance", "surface_tolerance", "lengths")
    return {("input" if k == "surface" else k): getattr(args, k) for k in keys if getattr(args, k, None)}


def _run_experiment(args):
    script = EXPERIMENTS / f"{args.experiment}.py"
    if not script.is_file():
        raise EquimeshError(f"'equimesh {args.experiment}' needs a source checkout: {script} not found")
    spec = importlib.util.spec_from_file_location(f"equimesh_experiment_{args.experiment}", script)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    argv0, sys.argv[0] = sys.argv[0], f"equimesh {args.experiment}"  # the script's usage line names the subcommand
    try:
        return module.main(args.args)
    finally:
        sys.argv[0] = argv0


if __name__ == "__main__":
    sys.exit(main())
