"""The report in a real browser: headless Chromium opens it offline, draws the mesh, and logs no JavaScript error.

Chromium runs with a fresh profile, no network (every host name resolves to
nothing) and software WebGL.  A copy of the page gets a first script that
records every error (``window.onerror``, unhandled rejections,
``console.error``) and, once the page has set ``data-ready``, writes them with
the 3-D view's position into the DOM, which ``--dump-dom`` prints; a second run
takes a screenshot of the page itself, whose pixels inside the view must show
the classes' colours.  Skipped with the reason where Chromium is missing
(``make test`` installs it with apt-get where it can).
"""

import json
import re
import shutil
import subprocess

import numpy as np
import pytest
import report_meshes
from matplotlib.image import imread

from equimesh.io import write_report
from equimesh.io._view import PALETTE

large_mesh = report_meshes.large_mesh  # the shared fixture
roof_mesh = report_meshes.roof_mesh  # the shared fixture

pytest.importorskip("plotly", reason="the report needs plotly: pip install 'equimesh[report]'")
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
pytestmark = pytest.mark.skipif(
    CHROMIUM is None, reason="no chromium on PATH (`make test` installs it with apt-get where it is root)"
)

FLAGS = (
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--enable-unsafe-swiftshader",  # WebGL in software, without a GPU
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--hide-scrollbars",
    "--host-resolver-rules=MAP * ~NOTFOUND",  # offline: any request for a host fails
    "--enable-logging=stderr",
    "--v=0",
)
WINDOW = (1280, 900)
#: Virtual time the page gets to draw (ms); a budget, not a measurement: virtual time runs as fast as the page idles.
BUDGET = 60_000

HARNESS = """<script>
window.__errors = [];
addEventListener("error", (e) => __errors.push(String(e.message || e)));
addEventListener("unhandledrejection", (e) => __errors.push("unhandled rejection: " + e.reason));
const __error = console.error;
console.error = (...args) => { __errors.push(args.map(String).join(" ")); __error(...args); };
addEventListener("load", () => {
  const poll = () => {
    if (!document.documentElement.dataset.ready) return setTimeout(poll, 50);
    const box = (e) => { const r = e.getBoundingClientRect(); return [r.left, r.top, r.width, r.height]; };
    const out = document.createElement("pre");
    out.id = "harness";
    out.textContent = JSON.stringify({
      errors: __errors, view: box(document.getElementById("view")),
      legend: box(document.querySelector("#view .legend")),
      canvases: document.querySelectorAll("#view canvas").length,
    });
    document.body.appendChild(out);
  };
  poll();
});
</script>"""


def chromium(tmp_path, url, *args):
    """Run Chromium on ``url`` with a fresh profile; return its standard output and error."""
    profile = tmp_path / f"profile-{len(list(tmp_path.glob('profile-*')))}"
    run = subprocess.run(
        [CHROMIUM, *FLAGS, f"--user-data-dir={profile}", f"--window-size={WINDOW[0]},{WINDOW[1]}",
         f"--virtual-time-budget={BUDGET}", *args, url],
        capture_output=True, text=True, timeout=300, check=False,
    )  # fmt: skip
    return run.stdout, run.stderr


def uncaught(stderr):
    """JavaScript errors in Chromium's log: the console lines of uncaught exceptions."""
    return [line for line in stderr.splitlines() if "CONSOLE" in line and "Uncaught" in line]


def open_report(tmp_path, report, fragment=""):
    """Load ``report`` (with the harness) and take a screenshot (without); return the harness's record and pixels."""
    text = report.read_text(encoding="utf-8")
    probed = tmp_path / "probed.html"
    probed.write_text(text.replace("<head>", "<head>\n" + HARNESS, 1), encoding="utf-8")
    dom, log = chromium(tmp_path, probed.as_uri() + fragment, "--dump-dom")
    found = re.search(r'<pre id="harness">(.*?)</pre>', dom, re.S)
    assert found, f"the page never set data-ready; log: {uncaught(log) or log[-2000:]}"
    record = json.loads(found.group(1).replace("&quot;", '"').replace("&amp;", "&"))
    assert record["errors"] == [] and uncaught(log) == []
    assert record["canvases"] > 0  # plotly's WebGL scene
    shot = tmp_path / "shot.png"
    _, log = chromium(tmp_path, report.as_uri() + fragment, f"--screenshot={shot}")
    assert uncaught(log) == []
    pixels = (imread(shot)[..., :3] * 255).round().astype(int)
    assert pixels.shape[:2] == (WINDOW[1], WINDOW[0])
    left, top, width, height = (int(v) for v in record["legend"])
    pixels[max(top, 0) : top + height, max(left, 0) : left + width] = 255  # the legend's swatches are no mesh
    left, top, width, height = (int(v) for v in record["view"])
    return pixels[max(top, 0) : min(top + height, WINDOW[1]), max(left, 0) : left + width]


def share_near(pixels, colours, distance=40):
    """Fraction of ``pixels`` within ``distance`` (RGB) of one of ``colours`` ("#rrggbb")."""
    rgb = np.array([[int(c[i : i + 2], 16) for i in (1, 3, 5)] for c in np.atleast_1d(colours)])
    return float(np.mean((np.linalg.norm(pixels[..., None, :] - rgb, axis=-1) < distance).any(axis=-1)))


def test_the_roof_is_drawn_in_its_class_colours_offline_without_errors(roof_mesh, tmp_path):
    report = tmp_path / "roof.html"
    write_report(roof_mesh, report)
    view = open_report(tmp_path, report)
    assert view.size and share_near(view, "#ffffff", 10) < 0.97  # not a blank canvas
    assert share_near(view, PALETTE) > 0.01 and share_near(view, "#000000", 60) > 0.002  # members, boundary


def test_deviation_colouring_from_the_address(roof_mesh, tmp_path):
    from equimesh.io._report import DEVIATION_SCALE

    report = tmp_path / "roof.html"
    write_report(roof_mesh, report)
    view = open_report(tmp_path, report, "#deviation")
    assert share_near(view, DEVIATION_SCALE[1][1], 60) > 0.005  # members near l in the scale's middle colour


def test_a_mesh_of_more_than_100000_members_is_drawn(large_mesh, tmp_path):
    report = tmp_path / "large.html"
    write_report(large_mesh, report)
    view = open_report(tmp_path, report)
    assert share_near(view, PALETTE[0]) > 0.05  # the largest class, the lattice
