"""Write examples/hopper.stl: a square hopper (ASCII STL, metres): a vertical bin of half-width 30 mm from
z = 60 mm to z = 120 mm over a pyramid frustum narrowing to a square orifice of half-width 8 mm at
z = 20 mm (faces 61 degrees from the horizontal), each flat face two triangles, open at the top and at the
orifice. Load it with dem_contact.walls.MeshWall.from_stl("examples/hopper.stl").

    python examples/make_hopper_stl.py [--out examples/hopper.stl] [--binary]
"""
import argparse
import pathlib

import numpy as np

from dem_contact.walls import write_stl

TOP, BIN, ORIFICE = 0.030, (0.060, 0.120), 0.008     # half-widths [m], bin heights [m]
Z_ORIFICE = 0.020                                      # [m]


def hopper():
    """(vertices, triangles) of the hopper: rings of 4 corners at the orifice, the bin's bottom and top."""
    rings = [(ORIFICE, Z_ORIFICE), (TOP, BIN[0]), (TOP, BIN[1])]
    corners = [(-1, -1), (1, -1), (1, 1), (-1, 1)]
    v = np.array([[h * a, h * b, z] for h, z in rings for a, b in corners])
    t = []
    for ring in range(len(rings) - 1):
        for k in range(4):
            a, b = 4 * ring + k, 4 * ring + (k + 1) % 4
            t += [[a, b, b + 4], [a, b + 4, a + 4]]
    return v, np.array(t)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--out", default=str(pathlib.Path(__file__).with_name("hopper.stl")), help="STL file to write")
    p.add_argument("--binary", action="store_true", help="binary STL (float32) instead of ASCII")
    a = p.parse_args(argv)
    write_stl(a.out, *hopper(), ascii=not a.binary, name="hopper")
    print(a.out)


if __name__ == "__main__":
    main()
