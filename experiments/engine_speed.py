"""Speed of the fast insertion engine against Triangle's own quality refinement (Problem 1 on a unit square).

For each target size, one fresh process (so that its peak memory is its own):

* ``equimesh.increment(unit square, l, engine="fast")``, ``l`` chosen for
  about ``n`` output vertices; time of the whole call and of the engine alone;
* ``triangle.triangulate(square, "qa<area>Q")`` with the area bound scaled to
  give about the same vertex count, in the same process;
* peak resident memory of the process (``ru_maxrss``) after the increment
  call and at the end (after Triangle too), import and first-call time
  (compilation, or loading numba's cache).

Run by hand (not a test; times are machine-dependent)::

    PYTHONPATH=src python experiments/engine_speed.py 10000 100000 1000000
"""

import json
import math
import subprocess
import sys
import time


def measure(n):
    """One size, in this process: a dict of timings and counts."""
    import resource

    t0 = time.perf_counter()
    import numpy as np
    import triangle

    import equimesh
    import equimesh.planar.increment as inc
    from equimesh.planar.insertion import insert

    out = {"n_target": n, "import_s": time.perf_counter() - t0}
    t0 = time.perf_counter()
    equimesh.increment([[0, 0], [3, 0], [3, 3], [0, 3]], 1.0, engine="fast")
    out["first_call_s"] = time.perf_counter() - t0

    engine_time = []

    def timed(region, l, engine):
        start = time.perf_counter()
        result = insert(region, l, engine=engine)
        engine_time.append(time.perf_counter() - start)
        return result

    inc.insert = timed
    # Farthest-point insertion at spacing l puts about 0.68 / l^2 points in a unit area (measured).
    l = math.sqrt(0.68 / n)
    t0 = time.perf_counter()
    mesh = equimesh.increment([[0, 0], [1, 0], [1, 1], [0, 1]], l, engine="fast")
    out.update(total_s=time.perf_counter() - t0, engine_s=engine_time[0], n_points=int(mesh.n_nodes), l=l)
    out["peak_rss_mb_increment"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    del mesh

    square = {"vertices": np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float), "segments": [[0, 1], [1, 2], [2, 3], [3, 0]]}
    area = 1.0 / n
    for _ in range(2):  # two rounds of scaling the area bound to the vertex count
        t0 = time.perf_counter()
        tri = triangle.triangulate(square, f"pqa{area:.15f}Q")
        out["triangle_s"] = time.perf_counter() - t0
        out["triangle_points"] = len(tri["vertices"])
        area *= out["triangle_points"] / out["n_points"]
    out["fast_us_per_vertex"] = 1e6 * out["engine_s"] / out["n_points"]
    out["triangle_us_per_vertex"] = 1e6 * out["triangle_s"] / out["triangle_points"]
    out["ratio"] = out["fast_us_per_vertex"] / out["triangle_us_per_vertex"]
    out["peak_rss_mb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    return out


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ["--one"]:
        print(json.dumps(measure(int(argv[1]))))
        return
    rows = []
    for n in (int(a) for a in (argv or ["10000", "100000"])):
        proc = subprocess.run([sys.executable, __file__, "--one", str(n)], capture_output=True, text=True, check=True)
        rows.append(json.loads(proc.stdout.strip().splitlines()[-1]))
    cols = ["n_points", "engine_s", "total_s", "fast_us_per_vertex", "triangle_points", "triangle_s",
            "triangle_us_per_vertex", "ratio", "peak_rss_mb_increment", "peak_rss_mb", "import_s", "first_call_s"]
    print("| " + " | ".join(cols) + " |")
    print("|" + "---|" * len(cols))
    for r in rows:
        print("| " + " | ".join(f"{r[c]:.4g}" if isinstance(r[c], float) else str(r[c]) for c in cols) + " |")


if __name__ == "__main__":
    main()
