#!/usr/bin/env python3
"""Writes "Sponza town": NX x NZ copies of Dabrovic Sponza side by side (courtyards in a town
block), with the three Sponza views of assets/scenes/ set in the middle copy. It is the large
scene of docs/design/clipmaps.md, where one fitted grid can no longer resolve what the
camera sees and clipmaps (Freed 2018 §2.3.2; Wicked Engine's VXGI) are meant to pay. The
middle copy keeps Sponza's own coordinates, so the views' cameras and sun are unchanged.

    python3 scripts/sponza-town.py [--tiles 3] [--gap 0.5] [--out /tmp/vct-town]

Reads ../shared/scenes/sponza/ beside the checkout (not part of this repository); writes
town.obj, links to sponza.mtl and textures/, and town.toml, town-arcade.toml, town-end.toml."""
import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
SPONZA = os.path.join(REPO, "..", "shared", "scenes", "sponza")
VIEWS = {"town": "sponza.toml", "town-arcade": "sponza-arcade.toml", "town-end": "sponza-end.toml"}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tiles", type=int, default=3, help="copies along x and along z (odd)")
    ap.add_argument("--gap", type=float, default=0.5, help="metres between neighbouring copies")
    ap.add_argument("--out", default="/tmp/vct-town")
    args = ap.parse_args()
    if args.tiles < 1 or args.tiles % 2 == 0:
        sys.exit("--tiles must be odd and at least 1 (the middle copy holds the views)")
    if not args.gap >= 0.0:
        sys.exit("--gap must be a finite length of at least 0")
    src = os.path.join(SPONZA, "sponza.obj")
    if not os.path.exists(src):
        sys.exit(f"{src}: not found (the shared scene folder beside the checkout)")

    verts, rest = [], []
    with open(src) as f:
        for line in f:
            (verts if line.startswith("v ") else rest).append(line)
    pos = [tuple(map(float, v.split()[1:4])) for v in verts]
    lo = [min(p[i] for p in pos) for i in range(3)]
    hi = [max(p[i] for p in pos) for i in range(3)]
    step_x = hi[0] - lo[0] + args.gap
    step_z = hi[2] - lo[2] + args.gap
    n = len(pos)
    half = args.tiles // 2

    os.makedirs(args.out, exist_ok=True)
    obj = os.path.join(args.out, "town.obj")
    with open(obj, "w") as out:
        out.write(f"# {args.tiles} x {args.tiles} copies of Dabrovic Sponza (CC BY-NC), "
                  f"by scripts/sponza-town.py\nmtllib sponza.mtl\n")
        tiles = [(i, k) for i in range(-half, half + 1) for k in range(-half, half + 1)]
        for (i, k) in tiles:
            dx, dz = i * step_x, k * step_z
            for (x, y, z) in pos:
                out.write(f"v {x + dx:.6f} {y:.6f} {z + dz:.6f}\n")
        for t, (i, k) in enumerate(tiles):
            for line in rest:
                if line.startswith("f "):
                    corners = []
                    for c in line.split()[1:]:
                        idx = c.split("/")
                        v = int(idx[0])
                        if v < 0:
                            sys.exit(f"{src}: relative vertex indices are not handled")
                        idx[0] = str(v + t * n)
                        corners.append("/".join(idx))
                    out.write("f " + " ".join(corners) + "\n")
                elif line.startswith("o ") or line.startswith("g "):
                    out.write(f"{line.rstrip()}_{i}_{k}\n")
                elif line.startswith("mtllib"):
                    continue
                elif t == 0 or line.startswith("usemtl") or line.startswith("s "):
                    out.write(line)
    for name in ("sponza.mtl", "textures"):
        link = os.path.join(args.out, name)
        if not os.path.lexists(link):
            os.symlink(os.path.abspath(os.path.join(SPONZA, name)), link)
    for view, scene in VIEWS.items():
        with open(os.path.join(REPO, "assets", "scenes", scene)) as f:
            text = f.read()
        text = text.replace('mesh = "../../../shared/scenes/sponza/sponza.obj"',
                            f'mesh = "{obj}"')
        header = (f"# Sponza town ({args.tiles} x {args.tiles} copies, by scripts/sponza-town.py): "
                  f"{scene}'s view in the middle copy.\n")
        with open(os.path.join(args.out, view + ".toml"), "w") as f:
            f.write(header + text)
    span = (args.tiles * step_x - args.gap, hi[1] - lo[1], args.tiles * step_z - args.gap)
    print(f"{obj}: {len(tiles)} copies, {len(tiles) * n} vertices, "
          f"{span[0]:.1f} x {span[1]:.1f} x {span[2]:.1f} m")


if __name__ == "__main__":
    main()
