"""The linear-elastic embankment quake of inputs/scenes/elastic_embankment_quake.yaml in OpenSees
(openseespy), on the mesh cfrd wrote into a run's results.h5: stdBrick elements on an
ElasticIsotropic material, consistent mass, Rayleigh damping on the initial stiffness, the
three record components as uniform excitation, Newmark average acceleration, the linear
algorithm factoring once. Writes the crest node's relative displacement at every step and
prints the seconds of the time stepping.

usage: python3 opensees_embankment.py RESULTS_H5 RECORD_CSV CREST_NODE_ID OUT_CSV
"""

import math
import sys
import time

import h5py
import numpy as np
import openseespy.opensees as ops

# the scene's values (inputs/scenes/elastic_embankment_quake.yaml)
YOUNG, POISSON, DENSITY = 3.0e8, 0.3, 2100.0
RATIO, F1, F2 = 0.05, 1.0, 5.0
DT, STEPS = 0.01, 1000


def build(h5_path):
    """Nodes, fixities and bricks from cfrd's mesh; returns the node ids."""
    with h5py.File(h5_path, "r") as f:
        xyz = f["mesh/coordinates"][:]
        ids = f["mesh/node_ids"][:]
        topo = f["mesh/topology"][:]
    ops.wipe()
    ops.model("basic", "-ndm", 3, "-ndf", 3)
    y_lo, y_hi = xyz[:, 1].min(), xyz[:, 1].max()
    for i, (x, y, z) in enumerate(xyz):
        ops.node(int(ids[i]), float(x), float(y), float(z))
        if abs(z) < 1e-9 or abs(y - y_lo) < 1e-9 or abs(y - y_hi) < 1e-9:
            ops.fix(int(ids[i]), 1, 1, 1)
    ops.nDMaterial("ElasticIsotropic", 1, YOUNG, POISSON, DENSITY)
    for e, nodes in enumerate(topo):
        ops.element("stdBrick", e + 1, *[int(ids[n]) for n in nodes], 1)
    return ids


def excite(record_csv):
    """The record's three components as uniform excitation (a_x, a_y, a_z in m/s²)."""
    rec = np.genfromtxt(record_csv, delimiter=",", names=True)
    for axis, name in enumerate(["a_x", "a_y", "a_z"], start=1):
        ops.timeSeries("Path", axis, "-dt", DT, "-values", *map(float, rec[name]))
        ops.pattern("UniformExcitation", axis, axis, "-accel", axis)


def main():
    h5_path, record_csv, crest, out_csv = sys.argv[1:5]
    crest = int(crest)
    build(h5_path)
    excite(record_csv)
    w1, w2 = 2 * math.pi * F1, 2 * math.pi * F2
    a_m, a_k = 2 * RATIO * w1 * w2 / (w1 + w2), 2 * RATIO / (w1 + w2)
    ops.rayleigh(a_m, 0.0, a_k, 0.0)
    ops.constraints("Plain")
    ops.numberer("RCM")
    ops.system("Mumps")
    ops.algorithm("Linear", "-factorOnce")
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")
    rows = [(0.0, 0.0, 0.0, 0.0)]
    started = time.perf_counter()
    for k in range(1, STEPS + 1):
        if ops.analyze(1, DT) != 0:
            sys.exit(f"OpenSees failed at step {k}")
        rows.append((k * DT, *ops.nodeDisp(crest)))
    seconds = time.perf_counter() - started
    np.savetxt(out_csv, rows, delimiter=",", header="t,u_x,u_y,u_z", comments="")
    print(f"opensees_seconds {seconds:.3f} steps {STEPS}")


if __name__ == "__main__":
    main()
