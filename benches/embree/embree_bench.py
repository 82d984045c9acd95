#!/usr/bin/env python3
"""Embree 4 (through embreex) on the rays `dump_rays` wrote, against obvhs.

Loads `rays.bin` (Sponza's triangles and 1024x1024 primary rays, format in
dump_rays.rs), builds an Embree scene of the same triangles, times closest-hit
(`INTERSECT`) and occlusion (`OCCLUDED`) queries of every ray on one thread
(embreex traces a batch one ray after another on the calling thread), median
of 5 passes after a warm-up, and prints both libraries' rates with obvhs' as a
percentage of Embree's (obvhs' from `obvhs.json`, written by dump_rays).

    python3 benches/embree/embree_bench.py [DIR]    (default target/embree)
"""

import json
import os
import struct
import sys
import time

import numpy as np
from embreex import rtcore_scene
from embreex.mesh_construction import TriangleMesh

RUNS = 5


def load(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"SUBCRAYS":
        sys.exit(f"{path}: not a rays file written by dump_rays")
    version, ntri, nrays = struct.unpack_from("<3I", data, 8)
    if version != 1:
        sys.exit(f"{path}: version {version}, expected 1")
    floats = np.frombuffer(data, dtype="<f4", offset=20)
    if floats.size != ntri * 9 + nrays * 6:
        sys.exit(f"{path}: truncated")
    tris = floats[: ntri * 9].reshape(ntri, 3, 3)
    rays = floats[ntri * 9 :].reshape(nrays, 6)
    return (
        np.ascontiguousarray(tris, dtype=np.float32),
        np.ascontiguousarray(rays[:, :3], dtype=np.float32),
        np.ascontiguousarray(rays[:, 3:], dtype=np.float32),
    )


def median_mrays(n, run):
    run()  # warm-up
    times = []
    for _ in range(RUNS):
        start = time.perf_counter()
        run()
        times.append(time.perf_counter() - start)
    times.sort()
    return n / times[RUNS // 2] / 1e6


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join("target", "embree")
    tris, origins, dirs = load(os.path.join(out, "rays.bin"))
    with open(os.path.join(out, "obvhs.json")) as f:
        obvhs = json.load(f)
    scene = rtcore_scene.EmbreeScene()
    TriangleMesh(scene, tris)
    n = len(origins)
    hits = int((scene.run(origins, dirs, query="INTERSECT") >= 0).sum())
    embree = {
        "closest": median_mrays(n, lambda: scene.run(origins, dirs, query="INTERSECT")),
        "occluded": median_mrays(n, lambda: scene.run(origins, dirs, query="OCCLUDED")),
    }
    print(
        f"{obvhs['scene']}: {len(tris)} triangles, {n} primary rays, one thread, "
        f"median of {RUNS} (Embree {hits} hits)"
    )
    print(f"{'':24}{'closest hit':>16}{'occlusion':>16}")
    print(f"{'Embree 4 (embreex)':24}{embree['closest']:>10.2f} Mr/s{embree['occluded']:>10.2f} Mr/s")
    for name, rates in obvhs["paths"].items():
        c, o = rates["closest_mrays"], rates["occluded_mrays"]
        print(f"{'obvhs, ' + name:24}{c:>10.2f} Mr/s{o:>10.2f} Mr/s")
        print(
            f"{'  as % of Embree':24}{100 * c / embree['closest']:>14.1f} %"
            f"{100 * o / embree['occluded']:>14.1f} %"
        )


if __name__ == "__main__":
    main()
