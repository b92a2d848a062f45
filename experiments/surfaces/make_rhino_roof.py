"""Write roof.3dm: the NURBS roof of nurbs_roof.json as a Rhino file, with a second, trimmed object.

Objects: 0 "roof" (the NURBS surface of nurbs_roof.json), 1 "skylight plate" (a planar Brep
trimmed by a circle: read untrimmed, with a warning).  Needs rhino3dm
(``pip install 'equimesh[rhino]'``).  Run ``python experiments/surfaces/make_rhino_roof.py``;
``equimesh mesh experiments/surfaces/roof.3dm --object roof ...`` then meshes the roof.
"""

import sys
from pathlib import Path

import rhino3dm

from equimesh.io import load_surface, to_rhino_surface

HERE = Path(__file__).resolve().parent


def main(argv=None):
    model = rhino3dm.File3dm()
    roof = rhino3dm.ObjectAttributes()
    roof.Name = "roof"
    model.Objects.AddSurface(to_rhino_surface(load_surface(HERE / "nurbs_roof.json")), roof)
    plate = rhino3dm.ObjectAttributes()
    plate.Name = "skylight plate"
    circle = rhino3dm.Circle(rhino3dm.Point3d(30.0, 20.0, 0.0), 6.0).ToNurbsCurve()
    model.Objects.AddBrep(rhino3dm.Brep.CreateTrimmedPlane(rhino3dm.Plane.WorldXY(), circle), plate)
    out = HERE / "roof.3dm"
    if not model.Write(str(out), 7):
        raise OSError(f"rhino3dm could not write {out}")
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
