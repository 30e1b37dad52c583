#!/usr/bin/python3
"""Independent finite-element reference for the rigid strip footing benchmarks (CalculiX).

Writes a CalculiX input deck for a named case and mesh, runs `ccx` (one process,
OMP_NUM_THREADS=1) in a scratch directory, reads the total vertical reaction of the footing
nodes per increment from the .dat file and writes a CSV of w/B against q/c_u.

Model: plane strain CPE8R (8-node quads, reduced integration), 1 m thick; half model
[0, W] x [0, H] with symmetry plane x = 0 (u_x = 0), base y = 0 fixed, far side x = W with
u_x = 0; weightless; linear elastic E, nu and von Mises perfect plasticity with
sigma_y = sqrt(3) c_u (the plane-strain Tresca limit load). The rigid footing of half width b
is the top nodes with x <= b: vertical displacement ramped linearly over the step to the final
settlement; rough also holds u_x = 0 there, smooth leaves u_x free (except at x = 0).

Usage (Debian's python3, standard library and numpy):
  /usr/bin/python3 benchmarks/references/footing_calculix.py --case footing --mesh fine --nlgeom
  /usr/bin/python3 benchmarks/references/footing_calculix.py --all
"""

import argparse
import datetime
import math
import os
import re
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
WORK = os.path.join(HERE, "work")

# Geometry and material of each case (benchmarks/scenes/*.toml).
CASES = {
    "footing": dict(scene="benchmarks/scenes/footing.toml", W=5.0, H=5.0, b=1.0,
                    E=1.0e6, nu=0.497, cu=10.0e3, w_over_B=0.1, increments=100),
    "footing-stiff": dict(scene="benchmarks/scenes/footing.toml with E = 10 MPa (I_r = 334)",
                          W=5.0, H=5.0, b=1.0, E=1.0e7, nu=0.497, cu=10.0e3,
                          w_over_B=0.05, increments=50, automatic=True),
    "footing-deep": dict(scene="benchmarks/scenes/footing-deep.toml", W=5.0, H=5.0, b=0.5,
                         E=1.0e5, nu=0.495, cu=1.0e3, w_over_B=0.1, increments=100),
}

# Structured meshes: elements across the footing (0..b), beside it (b..W) and in depth, and the
# smallest element size (at the footing's edge x = b, y = H) as a fraction of b.
MESHES = {
    "coarse": dict(n_under=16, n_beside=22, n_depth=36, h0_over_b=0.025),
    "fine": dict(n_under=24, n_beside=32, n_depth=54, h0_over_b=0.0125),
}

# The committed CSVs: (case, mesh, nlgeom, surface, output path relative to this folder).
ALL_RUNS = [
    ("footing", "coarse", False, "rough", "footing/small-coarse.csv"),
    ("footing", "fine", False, "rough", "footing/small-fine.csv"),
    ("footing", "coarse", True, "rough", "footing/nlgeom-coarse.csv"),
    ("footing", "fine", True, "rough", "footing/nlgeom-fine.csv"),
    ("footing-deep", "coarse", True, "rough", "footing-deep/nlgeom-coarse.csv"),
    ("footing-deep", "fine", True, "rough", "footing-deep/nlgeom-fine.csv"),
    ("footing-stiff", "fine", False, "rough", "footing-stiff/rough.csv"),
    ("footing-stiff", "fine", False, "smooth", "footing-stiff/smooth.csv"),
    ("footing-stiff", "coarse", True, "rough", "footing-stiff/rough-nlgeom-coarse.csv"),
]


def graded(length, n, h0):
    """n + 1 coordinates from 0 to length, sizes h0 r^i (geometric), first size h0."""
    if abs(n * h0 - length) < 1e-12 * length:
        return np.linspace(0.0, length, n + 1)
    lo, hi = (1.0 + 1e-12, 10.0) if n * h0 < length else (1e-6, 1.0 - 1e-12)
    for _ in range(200):
        r = 0.5 * (lo + hi)
        s = h0 * (r ** n - 1.0) / (r - 1.0)
        if (s > length) == (n * h0 < length):
            hi = r
        else:
            lo = r
    r = 0.5 * (lo + hi)
    sizes = h0 * r ** np.arange(n)
    sizes *= length / sizes.sum()
    return np.concatenate([[0.0], np.cumsum(sizes)])


def mesh_lines(case, mesh):
    c, m = CASES[case], MESHES[mesh]
    b, W, H = c["b"], c["W"], c["H"]
    h0 = m["h0_over_b"] * b
    left = b - graded(b, m["n_under"], h0)[::-1]          # 0 .. b, finest at b
    right = b + graded(W - b, m["n_beside"], h0)           # b .. W, finest at b
    xs = np.concatenate([left, right[1:]])
    ys = H - graded(H, m["n_depth"], h0)[::-1]             # 0 .. H, finest at H
    xs[0], ys[0], ys[-1] = 0.0, 0.0, H
    return xs, ys, h0


def build_mesh(xs, ys):
    """CPE8R mesh on the tensor grid xs x ys: nodes (id -> (x, y)) and elements."""
    nx, ny = len(xs) - 1, len(ys) - 1
    # quadratic node grid: corners at even indices, mid-side nodes between
    xq = np.empty(2 * nx + 1)
    xq[0::2] = xs
    xq[1::2] = 0.5 * (xs[:-1] + xs[1:])
    yq = np.empty(2 * ny + 1)
    yq[0::2] = ys
    yq[1::2] = 0.5 * (ys[:-1] + ys[1:])
    ids = {}
    nodes = []
    for j in range(2 * ny + 1):
        for i in range(2 * nx + 1):
            if i % 2 == 1 and j % 2 == 1:
                continue  # no centre node in an 8-node quad
            ids[(i, j)] = len(nodes) + 1
            nodes.append((ids[(i, j)], xq[i], yq[j], i, j))
    elems = []
    for ej in range(ny):
        for ei in range(nx):
            i, j = 2 * ei, 2 * ej
            corners = [ids[(i, j)], ids[(i + 2, j)], ids[(i + 2, j + 2)], ids[(i, j + 2)]]
            mids = [ids[(i + 1, j)], ids[(i + 2, j + 1)], ids[(i + 1, j + 2)], ids[(i, j + 1)]]
            elems.append((len(elems) + 1, corners + mids))
    return nodes, elems, 2 * nx, 2 * ny


def write_inp(path, case, mesh, nlgeom, surface, increments, fields=False):
    c = CASES[case]
    b, W, H = c["b"], c["W"], c["H"]
    xs, ys, h0 = mesh_lines(case, mesh)
    nodes, elems, imax, jmax = build_mesh(xs, ys)
    tol = 1e-9
    sym = [n for n in nodes if n[3] == 0]
    base = [n for n in nodes if n[4] == 0]
    far = [n for n in nodes if n[3] == imax]
    foot = [n for n in nodes if n[4] == jmax and n[1] <= b + tol]
    settlement = c["w_over_B"] * 2.0 * b
    sigma_y = math.sqrt(3.0) * c["cu"]

    def nset(name, lst):
        out = [f"*NSET, NSET={name}"]
        idl = [str(n[0]) for n in lst]
        for k in range(0, len(idl), 12):
            out.append(", ".join(idl[k:k + 12]) + ",")
        return out

    L = ["*HEADING", f"rigid strip footing, case {case}, mesh {mesh}, "
         f"{'NLGEOM' if nlgeom else 'small strain'}, {surface}", "*NODE"]
    L += [f"{n[0]}, {n[1]:.10g}, {n[2]:.10g}" for n in nodes]
    L.append("*ELEMENT, TYPE=CPE8R, ELSET=SOIL")
    L += [f"{e}, " + ", ".join(str(k) for k in conn) for e, conn in elems]
    L += nset("SYM", sym) + nset("BASE", base) + nset("FAR", far) + nset("FOOT", foot)
    L += ["*MATERIAL, NAME=CLAY", "*ELASTIC", f"{c['E']:.10g}, {c['nu']:.10g}",
          "*PLASTIC", f"{sigma_y:.10g}, 0.0",
          "*SOLID SECTION, ELSET=SOIL, MATERIAL=CLAY", "1.0",
          "*BOUNDARY", "SYM, 1, 1", "BASE, 1, 2", "FAR, 1, 1"]
    if surface == "rough":
        L.append("FOOT, 1, 1")
    dt = 1.0 / increments
    if fields:  # displacements at half and full settlement in the .frd (for --fields)
        L += ["*TIME POINTS, NAME=TF", "0.5, 1.0"]
    if nlgeom or c.get("automatic"):
        # With NLGEOM a fixed increment diverges now and then under the footing's edge (coarse
        # mesh: at w/B 0.021 with 100 increments, at 0.042 with 200), and so does the second
        # fixed increment of footing-stiff (E = 10 MPa, small strain); automatic incrementation
        # cuts such an increment back and retries it. The increment is capped at dt and
        # *TIME POINTS makes ccx land on (and print at) every multiple of dt.
        times = [f"{k * dt:.12g}" for k in range(1, increments + 1)]
        L += ["*TIME POINTS, NAME=TP"]
        L += [", ".join(times[k:k + 8]) for k in range(0, len(times), 8)]
        L += [f"*STEP{', NLGEOM' if nlgeom else ''}, INC={20 * increments}",
              "*STATIC", f"{dt:.12g}, 1.0, 1e-7, {dt:.12g}",
              "*BOUNDARY", f"FOOT, 2, 2, {-settlement:.12g}",
              "*NODE PRINT, NSET=FOOT, TOTALS=ONLY, TIME POINTS=TP", "RF"]
        L += ["*NODE FILE, TIME POINTS=TF", "U"] if fields else []
        L += ["*END STEP"]
    else:
        L += [f"*STEP, INC={10 * increments}",
              "*STATIC, DIRECT", f"{dt:.12g}, 1.0",
              "*CONTROLS, PARAMETERS=TIME INCREMENTATION", "20, 30, 9, 60, 10, 4, , 5",
              "*BOUNDARY", f"FOOT, 2, 2, {-settlement:.12g}",
              "*NODE PRINT, NSET=FOOT, TOTALS=ONLY", "RF"]
        L += ["*NODE FILE, TIME POINTS=TF", "U"] if fields else []
        L += ["*END STEP"]
    with open(path, "w") as f:
        f.write("\n".join(L) + "\n")
    return dict(n_elem=len(elems), n_node=len(nodes), h0=h0, xs=xs, ys=ys,
                n_foot=len(foot), settlement=settlement)


def parse_dat(path):
    """(time, fx, fy) of each 'total force' block for set FOOT."""
    out = []
    with open(path) as f:
        lines = f.readlines()
    for k, line in enumerate(lines):
        m = re.search(r"total force \(fx,fy,fz\) for set FOOT and time\s+(\S+)", line)
        if not m:
            continue
        t = float(m.group(1))
        for nxt in lines[k + 1:k + 5]:
            vals = nxt.split()
            if len(vals) >= 2:
                out.append((t, float(vals[0]), float(vals[1])))
                break
    return out


def ccx_version():
    try:
        r = subprocess.run(["ccx", "-v"], capture_output=True, text=True, timeout=30)
        m = re.search(r"Version\s+(\S+)", r.stdout + r.stderr)
        return m.group(1) if m else "unknown"
    except OSError:
        return "unknown"


def run_case(case, mesh, nlgeom, surface, out_csv, increments=None, max_refine=2,
             keep=False, fields=False):
    c = CASES[case]
    b = c["b"]
    inc0 = increments or c["increments"]
    tag = f"{case}-{mesh}-{'nlgeom' if nlgeom else 'small'}-{surface}"
    workdir = os.path.join(WORK, tag)
    notes = []
    total_time = 0.0
    for attempt in range(max_refine + 1):
        inc = inc0 * 2 ** attempt
        if os.path.isdir(workdir):  # keep the previous attempt's log and status
            for name in ("ccx.log", "footing.sta", "footing.cvg"):
                if os.path.exists(os.path.join(workdir, name)):
                    os.replace(os.path.join(workdir, name),
                               os.path.join(workdir, f"previous-{name}"))
            for name in os.listdir(workdir):
                if not name.startswith("previous-"):
                    os.remove(os.path.join(workdir, name))
        os.makedirs(workdir, exist_ok=True)
        info = write_inp(os.path.join(workdir, "footing.inp"), case, mesh, nlgeom, surface, inc,
                          fields)
        env = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_EQUATION_SOLVER="1")
        t0 = time.time()
        with open(os.path.join(workdir, "ccx.log"), "w") as log:
            subprocess.run(["ccx", "-i", "footing"], cwd=workdir, env=env, stdout=log,
                           stderr=subprocess.STDOUT)
        elapsed = time.time() - t0
        total_time += elapsed
        rows = parse_dat(os.path.join(workdir, "footing.dat"))
        with open(os.path.join(workdir, "footing.sta")) as f:
            cutbacks = sum(1 for line in f if re.match(r"\s+\d+\s+\d+\s+\d+U", line))
        reached = rows[-1][0] if rows else 0.0
        print(f"{tag}: {inc} increments, {len(rows)} printed, reached t = {reached:.4f}, "
              f"{elapsed:.0f} s", flush=True)
        if reached > 1.0 - 1e-6:
            break
        notes.append(f"with increments of 1/{inc} ccx stopped at w/B = "
                     f"{reached * c['w_over_B']:.4f} (no convergence); rerun with 1/{2 * inc}")
    else:
        notes.append("did not reach the final settlement; the CSV ends where ccx stopped")

    m = MESHES[mesh]
    cmd = ("/usr/bin/python3 benchmarks/references/footing_calculix.py "
           f"--case {case} --mesh {mesh}{' --nlgeom' if nlgeom else ''}"
           f"{' --smooth' if surface == 'smooth' else ''}")
    if increments:
        cmd += f" --increments {increments}"
    hdr = [
        f"# CalculiX reference: rigid strip footing, case '{case}' ({c['scene']})",
        f"# program: CalculiX ccx {ccx_version()}, single thread (OMP_NUM_THREADS=1); "
        f"run time {total_time:.0f} s on the project machine (2 cores, beside a build)",
        f"# elements: CPE8R (8-node plane strain, reduced integration), thickness 1 m; "
        f"{info['n_elem']} elements, {info['n_node']} nodes",
        f"# mesh '{mesh}': structured, {m['n_under']} x {m['n_beside']} elements under/beside "
        f"the footing and {m['n_depth']} in depth, graded geometrically toward the footing "
        f"edge (x = b, y = H); smallest element {info['h0'] * 100:.3g} cm square there, "
        f"largest x {np.diff(info['xs']).max():.3g} m, y {np.diff(info['ys']).max():.3g} m",
        f"# geometry: half model [0, {c['W']:g}] x [0, {c['H']:g}] m, footing half width "
        f"b = {b:g} m (B = {2 * b:g} m), weightless",
        f"# material: linear elastic E = {c['E']:g} Pa, nu = {c['nu']:g}; von Mises perfect "
        f"plasticity sigma_y = sqrt(3) c_u = {math.sqrt(3) * c['cu']:.6g} Pa "
        f"(c_u = {c['cu']:g} Pa, plane-strain Tresca limit load)",
        f"# boundary: x = 0 u_x = 0 (symmetry); y = 0 u_x = u_y = 0; x = {c['W']:g} u_x = 0; "
        f"footing = {info['n_foot']} top nodes with x <= b, u_y ramped linearly to "
        f"-{info['settlement']:g} m"
        + (", u_x = 0 (rough)" if surface == "rough" else ", u_x free (smooth)"),
        (f"# kinematics: {'NLGEOM (large deformation)' if nlgeom else 'small strain'}; "
         f"*STATIC with automatic incrementation, "
         f"increment at most 1/{inc} of the step, printed at every 1/{inc} (*TIME POINTS) to "
         f"w/B = {c['w_over_B']:g}; {cutbacks} increments were cut back and retried"
         if nlgeom or c.get("automatic") else
         f"# kinematics: small strain; *STATIC, DIRECT with {inc} fixed increments to "
         f"w/B = {c['w_over_B']:g}"),
        "# q/c_u = F / (b c_u), F = total vertical reaction of the footing nodes per metre "
        "(half model); w/B = settlement / (2 b)",
    ]
    hdr += [f"# note: {n}" for n in notes]
    hdr += [f"# regenerate: {cmd}",
            f"# date: {datetime.datetime.now().strftime('%Y-%m-%d %H:%M')}"]
    out_path = out_csv if os.path.isabs(out_csv) else os.path.join(REPO, out_csv)
    os.makedirs(os.path.dirname(out_path), exist_ok=True)
    with open(out_path, "w") as f:
        f.write("\n".join(hdr) + "\n")
        f.write("w_over_B,q_over_cu\n")
        f.write("0,0\n")
        for t, fx, fy in rows:
            f.write(f"{t * c['w_over_B']:.6g},{-fy / (b * c['cu']):.6g}\n")
    print(f"wrote {os.path.relpath(out_path, REPO)}", flush=True)
    if not keep:
        for name in os.listdir(workdir):
            if name.endswith(".frd") or name.endswith(".inp"):
                os.remove(os.path.join(workdir, name))
    return rows, total_time


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--case", choices=sorted(CASES))
    ap.add_argument("--mesh", choices=sorted(MESHES), default="fine")
    ap.add_argument("--nlgeom", action="store_true", help="large deformation (*STEP, NLGEOM)")
    ap.add_argument("--smooth", action="store_true", help="smooth footing (u_x free)")
    ap.add_argument("--increments", type=int, help="fixed increments (default per case)")
    ap.add_argument("--out", help="CSV path (default: the committed one, or work/)")
    ap.add_argument("--keep", action="store_true", help="keep the .inp and .frd in work/")
    ap.add_argument("--fields", action="store_true",
                    help="also write displacements at w/B half-way and at the end to the .frd "
                         "(implies --keep)")
    ap.add_argument("--all", action="store_true", help="regenerate every committed CSV")
    a = ap.parse_args()
    if a.all:
        for case, mesh, nlgeom, surface, rel in ALL_RUNS:
            run_case(case, mesh, nlgeom, surface, os.path.join(HERE, rel), keep=a.keep)
        return
    if not a.case:
        ap.error("--case or --all")
    surface = "smooth" if a.smooth else "rough"
    out = a.out
    if not out:
        for case, mesh, nlgeom, surf, rel in ALL_RUNS:
            if (case, mesh, nlgeom, surf) == (a.case, a.mesh, a.nlgeom, surface):
                out = os.path.join(HERE, rel)
        if not out:
            out = os.path.join(WORK, f"{a.case}-{a.mesh}-{'nlgeom' if a.nlgeom else 'small'}"
                                     f"-{surface}.csv")
    run_case(a.case, a.mesh, a.nlgeom, surface, out, increments=a.increments,
             keep=a.keep or a.fields, fields=a.fields)


if __name__ == "__main__":
    sys.exit(main())
